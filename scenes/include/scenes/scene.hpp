// lodopt scene model: objects with discrete levels of detail, materials, textures, viewpoints.
//
// A Scene is a flat list of Objects. Each Object has a world transform and 1..N Levels
// ordered finest (index 0) to coarsest. A Level is one or more Meshes, each drawn with one
// Material; materials and textures are shared scene-wide by index. Statistics per level
// (vertices, triangles, texture bytes, draw calls, bounds) are precomputed by
// updateStatistics() so that the time model and the optimizer never walk geometry.
//
// A Combination picks one level per object (kNotDrawn leaves the object out). Cameras are
// the scene's viewpoints.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace lodopt::scenes {

// Bad scene data from outside (a file, a command line): the message names the file and the
// element (e.g. "model.gltf: meshes[3].primitives[0].indices: index 812 >= vertex count 800").
class SceneError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// RGBA8, rows top to bottom, tightly packed (width * 4 bytes per row).
struct Texture {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
};

// How a texture is read (glTF 2.0 §3.8.4 samplers). The defaults are what a glTF texture
// without a sampler gets: repeat, linear filtering, trilinear mipmaps.
enum class WrapMode : std::uint8_t { Repeat, ClampToEdge, MirroredRepeat };
enum class FilterMode : std::uint8_t { Nearest, Linear };
enum class MipmapMode : std::uint8_t { None, Nearest, Linear };
struct SamplerState {
    WrapMode wrapS = WrapMode::Repeat;
    WrapMode wrapT = WrapMode::Repeat;
    FilterMode magFilter = FilterMode::Linear;
    FilterMode minFilter = FilterMode::Linear;
    MipmapMode mipmap = MipmapMode::Linear;
    bool operator==(const SamplerState&) const = default;
};

// KHR_texture_transform: uv' = translate(offset) * rotate(rotation) * scale(scale) * uv, the
// extension's matrix (rotation in radians; positive turns UVs clockwise, as the spec's matrix).
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;
    glm::vec2 scale{1.0f};
    bool isIdentity() const { return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f); }
    glm::mat3 matrix() const;  // column-major, applied to (u, v, 1)
};

// A material's use of a texture: which image, which UV set, how it is sampled and transformed.
struct TextureRef {
    int texture = -1;  // index into Scene::textures, -1 for none
    int texCoord = 0;  // TEXCOORD_<n>: 0 or 1
    SamplerState sampler;
    TextureTransform transform;
    bool present() const { return texture >= 0; }
};

// glTF 2.0 alphaMode: OPAQUE ignores alpha, MASK discards below alphaCutoff, BLEND composites.
enum class AlphaMode : std::uint8_t { Opaque, Mask, Blend };

// glTF 2.0 metallic-roughness material (§3.9). Defaults are the spec's (a material with no
// properties, also used for meshes without one). Factors are linear; base color and emissive
// images hold sRGB-encoded values, the others linear data.
struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};  // linear multiplier of the texture (or the color alone)
    TextureRef baseColorTexture;
    float metallicFactor = 1.0f;
    float roughnessFactor = 1.0f;
    TextureRef metallicRoughnessTexture;  // blue = metallic, green = roughness
    TextureRef normalTexture;             // tangent space, [0, 1] -> [-1, 1]
    float normalScale = 1.0f;
    TextureRef occlusionTexture;  // red channel
    float occlusionStrength = 1.0f;
    TextureRef emissiveTexture;
    glm::vec3 emissiveFactor{0.0f};
    float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    bool unlit = false;  // KHR_materials_unlit: base color only, no lighting
};

// A material for the built-in scenes: a rough dielectric drawn from both sides (their leaf
// cards and open meshes have no back side), with an optional base-color texture.
Material diffuseMaterial(std::string name, glm::vec3 color, int baseColorTexture = -1);

// One draw call: triangles with one material. Normals always present (generated if the
// source had none); the other attributes empty or one per position.
struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;          // TEXCOORD_0
    std::vector<glm::vec2> uvs1;         // TEXCOORD_1
    std::vector<glm::vec4> tangents;     // xyz unit tangent, w = +-1 bitangent sign (glTF TANGENT)
    std::vector<glm::vec4> colors;       // COLOR_0, linear RGBA
    std::vector<std::uint32_t> indices;  // 3 per triangle, each < positions.size()
    int material = -1;                   // index into Scene::materials, -1 for the default
    // The file gave no NORMAL: drawn with each triangle's own normal (glTF 2.0 §3.7.2.1: flat
    // normals). `normals` then holds smooth ones, which keep the vertices welded for LOD
    // generation; the exporter writes none.
    bool flatNormals = false;
};

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    glm::vec3 sphereCenter{0.0f};
    float sphereRadius = 0.0f;
    bool empty() const { return max.x < min.x; }
};

struct LevelStats {
    std::uint64_t vertices = 0;
    std::uint64_t triangles = 0;
    std::uint64_t textureBytes = 0;  // distinct textures its materials use, width*height*4 each
    std::uint32_t drawCalls = 0;     // meshes (one material each)
    Bounds bounds;                   // object space
};

struct Level {
    std::vector<Mesh> meshes;
    LevelStats stats;
    // Screen-coverage threshold (fraction of viewport height) above which this level is
    // used, from MSFT_screencoverage; empty when the source did not say.
    std::optional<float> screenCoverage;
    // meshoptimizer's relative simplification error of this level against level 0
    // (0 for authored levels and level 0).
    float simplificationError = 0.0f;
    // Two-sided maximum surface deviation from level 0 in world units (the object's transform
    // applied; geometric_error.hpp); 0 for level 0; unset until computeGeometricErrors.
    std::optional<float> geometricError;
};

struct Object {
    std::string name;
    glm::mat4 transform{1.0f};  // object space → world space
    std::vector<Level> levels;  // finest (0) to coarsest; never empty in a valid scene
};

struct Camera {
    std::string name;
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovYDegrees = 45.0f;  // vertical field of view
    float nearPlane = 0.1f;
    float farPlane = 1000.0f;
};

// A sequence of camera poses (one per frame) for walk-throughs and the scheduler.
struct CameraPath {
    std::string name;
    float framesPerSecond = 30.0f;
    std::vector<Camera> frames;
};

struct Scene {
    std::string name;
    std::vector<Object> objects;
    std::vector<Material> materials;
    std::vector<Texture> textures;
    std::vector<Camera> views;
    std::vector<CameraPath> paths;
};

// One level per object, in object order; kNotDrawn leaves an object out of the frame.
using Combination = std::vector<int>;
inline constexpr int kNotDrawn = -1;

// Every object at level 0: the reference combination.
Combination referenceCombination(const Scene& scene);
// Every object at its coarsest level.
Combination coarsestCombination(const Scene& scene);
// Throws SceneError unless `combination` has one valid level (or kNotDrawn) per object.
void validateCombination(const Scene& scene, const Combination& combination);

// Recomputes every level's LevelStats from its meshes.
void updateStatistics(Scene& scene);
LevelStats computeLevelStats(const Scene& scene, const Level& level);
// Object-space bounds of some meshes (empty Bounds when there are no vertices).
Bounds computeBounds(const std::vector<Mesh>& meshes);
// World-space bounds of an object's level.
Bounds worldBounds(const Object& object, int level);

// Fills `mesh.normals` with area-weighted vertex normals.
void computeNormals(Mesh& mesh);
// Fills `mesh.tangents` from the normals and the UV set `texCoord` (0 or 1, which must be
// present) the way MikkTSpace builds a tangent frame: per triangle corner the tangent and
// bitangent from the UV derivatives, each corner weighted by its angle, summed per vertex, made
// orthogonal to the normal (Gram-Schmidt), w the sign of -dP/dv against cross(normal, tangent)
// (glTF's v runs down the image, a normal map's green up it). Unlike MikkTSpace, vertices are not split where mirrored
// UV islands meet (the sums are averaged there). A vertex whose triangles all have degenerate UVs gets a unit vector
// orthogonal to its normal.
void computeTangents(Mesh& mesh, int texCoord = 0);

// Checks the invariants above (indices in range, normals/uvs sized, material and texture
// indices valid, at least one level per object); throws SceneError naming the element.
void validateScene(const Scene& scene);

// Camera matrices (right-handed, OpenGL clip space). `aspect` = width / height.
glm::mat4 viewMatrix(const Camera& camera);
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

// Counts points (clip coordinates) outside each of the six clip planes. When all the points
// of a shape are outside one plane, so is the shape's convex hull: each plane is a linear
// inequality in clip coordinates, whatever the sign of w.
struct ClipPlaneCounts {
    std::size_t points = 0;
    std::size_t outside[6] = {};
    void add(const glm::vec4& clip) {
        ++points;
        outside[0] += clip.x < -clip.w;
        outside[1] += clip.x > clip.w;
        outside[2] += clip.y < -clip.w;
        outside[3] += clip.y > clip.w;
        outside[4] += clip.z < -clip.w;
        outside[5] += clip.z > clip.w;
    }
    bool allOutsideOnePlane() const {
        for (std::size_t plane : outside) {
            if (points > 0 && plane == points) return true;
        }
        return false;
    }
};

}  // namespace lodopt::scenes
