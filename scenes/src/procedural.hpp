// Shared helpers of the procedural built-in scenes (forest, city): a portable random number
// generator, tileable value noise for textures, meshes with explicit UVs, and camera paths
// sampled at constant speed.
//
// Portability: std::uniform_*_distribution differ between standard libraries, so the scenes
// draw every random number from splitmix64 (Steele, Lea & Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014) with our own integer → float conversion. All
// structural choices (counts, species, roof types) are integer arithmetic on that stream and
// identical everywhere; positions go through libm (sin, cos, exp), which may differ in the
// last bit between C libraries.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes::procedural {

class Rng {
public:
    explicit Rng(std::uint64_t seed) : mState(seed) {}
    // An independent stream for one purpose (terrain, tree 17, ...): adding a consumer of
    // one stream does not shift the numbers of another.
    Rng(std::uint32_t seed, std::uint64_t stream);

    std::uint64_t next();
    // [0, 1) with 24 random bits: exactly representable, never 1.
    float uniform();
    // [lo, hi)
    float uniform(float lo, float hi);
    // [lo, hi], both inclusive; lo <= hi. Multiply-shift reduction (bias < 2^-32).
    int uniformInt(int lo, int hi);
    // true with probability p.
    bool chance(float p);
    // Uniform on the unit sphere.
    glm::vec3 unitVector();

private:
    std::uint64_t mState;
};

// 32-bit integer hash of a lattice point (x, y) and a seed.
std::uint32_t hashLattice(std::int32_t x, std::int32_t y, std::uint32_t seed);
// Value noise in [0, 1): smooth in (x, y), lattice spacing 1, repeating every `periodX`
// lattice cells in x and `periodY` in y (both >= 1) so textures tile.
float valueNoise(float x, float y, int periodX, int periodY, std::uint32_t seed);
// Sum of `octaves` (>= 1) value noises, frequency doubling and amplitude halving per octave,
// rescaled to [0, 1); tiles like the first octave. Texture use: x = u * periodX, y = v * periodY.
float fractalNoise(float x, float y, int periodX, int periodY, int octaves, std::uint32_t seed);

// An RGBA8 texture (alpha 255) from `color(u, v)` → RGB in [0, 1] (clamped). Row r of the
// image holds v = (r + 0.5) / height, column c holds u = (c + 0.5) / width, so a mesh's uv
// (u, v) samples color(u, v) whatever the renderer's row convention.
Texture makeTexture(std::string name, int width, int height, const std::function<glm::vec3(float u, float v)>& color);

// Appends a planar quad a-b-c-d, counter-clockwise seen from the front, with explicit UVs
// and its flat normal (4 vertices, 2 triangles).
void appendQuad(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec2 ta, glm::vec2 tb,
                glm::vec2 tc, glm::vec2 td);
void appendTriangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec2 ta, glm::vec2 tb, glm::vec2 tc);
// Appends `source`'s vertices and triangles (its material is ignored).
void appendMesh(Mesh& mesh, const Mesh& source);

// Appends to the scene and returns the new index.
int addTexture(Scene& scene, Texture texture);
int addDiffuseMaterial(Scene& scene, std::string name, glm::vec3 color, int baseColorTexture = -1);

// Centripetal Catmull-Rom spline through `points` (>= 2), sampled at `count` (>= 2) points
// evenly spaced in arc length, first and last point included.
std::vector<glm::vec3> sampleSplineEvenly(const std::vector<glm::vec3>& points, int count);

// A camera path from eye positions: each frame looks at the position `lookAhead` samples
// further on (the last frames keep the final direction), lowered by `pitchDrop` world units
// so the view tilts slightly down.
CameraPath makeLookAheadPath(std::string name, float framesPerSecond, const std::vector<glm::vec3>& eyes, int lookAhead,
                             float pitchDrop, const Camera& lens);

}  // namespace lodopt::scenes::procedural
