// The PBR shading's GL state and draw pass (docs/renderer.md "Shading"): its program and
// uniforms, the textures in the color space each material slot reads, one sampler object per
// sampler state, and the engine-order draw (opaque and masked, then blended back to front).
// Private to the renderer; the Renderer owns the context, framebuffer and meshes.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "gl_common.hpp"
#include "renderer/renderer.hpp"
#include "shaders.hpp"

namespace lodopt::renderer {

class PbrPass {
public:
    // Creates the program and uploads every texture a material uses (the context is current).
    PbrPass(const scenes::Scene& scene, const RenderSettings& settings);
    ~PbrPass();
    PbrPass(const PbrPass&) = delete;
    PbrPass& operator=(const PbrPass&) = delete;

    // Which surfaces a draw covers. A full render draws All; a layer of an object with blended
    // surfaces draws them apart (Renderer::renderLayer): Opaque (and masked), then Blended with
    // the blending of All, then listBlendedFragments.
    enum class Surfaces { All, Opaque, Blended };
    // Draws `combination` into whatever framebuffer and scissor are set.
    void draw(const scenes::Combination& combination, const scenes::Camera& camera, const glm::mat4& viewProjection,
              const gl::GpuMeshes& meshes, Surfaces surfaces = Surfaces::All);

    // One blended fragment as the fragment-list program appends it.
    struct ListedFragment {
        std::uint32_t pixel;  // x | y << 16, window coordinates (bottom-left origin)
        float depth;
        std::uint8_t rgba[4];
        std::uint32_t draw, primitive;  // blending order: by draw, then primitive
    };
    // Draws the blended surfaces of `combination` as Surfaces::Blended orders them, writing no
    // color and no depth, and returns every fragment that passes the depth test against the
    // depth buffer as it is, in no particular order.
    std::vector<ListedFragment> listBlendedFragments(const scenes::Combination& combination,
                                                     const scenes::Camera& camera, const glm::mat4& viewProjection,
                                                     const gl::GpuMeshes& meshes);
    // Whether object `object`'s level `level` has a mesh whose material blends.
    bool blends(std::size_t object, int level) const { return mBlends[object][std::size_t(level)] != 0; }
    // The key the full render orders blended objects by, back to front: the distance from the
    // eye to the centre of the object's bounds at `level` (ties: lower object index first).
    float blendDistance(std::size_t object, int level, const scenes::Camera& camera) const;

private:
    struct Uniforms {
        GLint model = -1, modelViewProjection = -1, normalMatrix = -1, mirror = -1;
        GLint mapPresent = -1, mapUvSet = -1, mapTransform = -1;
        GLint baseColorFactor = -1, metallicFactor = -1, roughnessFactor = -1, normalScale = -1, occlusionStrength = -1;
        GLint emissive = -1, alphaMode = -1, alphaCutoff = -1, unlit = -1;
        GLint cameraPosition = -1, toLight = -1, keyIrradiance = -1, skyIrradiance = -1, groundIrradiance = -1;
        GLint flatNormals = -1;  // after the others: linkPbrProgram fills them in this order
    };

    struct Program {
        GLuint id = 0;
        Uniforms uniforms;
        GLint drawIndex = -1;  // the fragment-list variant's uDrawIndex
    };
    static Program linkPbrProgram(const char* fragmentSource);
    // Binds `program` and sets the light rig's uniforms.
    void use(Program& program, const scenes::Camera& camera);
    // The blended objects of `combination` into mBlended, back to front.
    void sortBlended(const scenes::Combination& combination, const scenes::Camera& camera);
    GLuint samplerFor(const scenes::SamplerState& state);
    void drawObject(std::size_t object, int level, const glm::mat4& viewProjection, const gl::GpuMeshes& meshes,
                    bool blendPass);
    void bindMaterial(const scenes::Material& material, bool hasTangents);

    const scenes::Scene& mScene;
    const RenderSettings& mSettings;
    Program mMain;
    Program mFragmentList;  // linked on first use
    Program* mActive = &mMain;
    GLuint mFragmentBuffer = 0;
    std::size_t mFragmentCapacity = 0;
    int mDrawIndex = 0;  // mesh draws so far in a fragment-list pass
    std::vector<GLuint> mLinearTextures;  // per scene texture, 0 when no linear slot reads it
    std::vector<GLuint> mSrgbTextures;    // per scene texture, 0 when no sRGB slot reads it
    std::map<std::tuple<int, int, int, int, int>, GLuint> mSamplers;
    std::vector<std::vector<char>> mBlends;               // [object][level]: blends()
    std::vector<std::pair<float, std::size_t>> mBlended;  // (blendDistance, object)
};

}  // namespace lodopt::renderer
