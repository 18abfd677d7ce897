// The built-in forest: 45-80 trees of three species (oak, pine, birch; forest_tree.hpp) on
// rolling terrain, denser in a grove than on the surrounding meadow, with named viewpoints
// and a walk-through path from the meadow into the grove (the natural scene of Dong et al.
// 2015, whose experiments use 30 trees).
//
// Layout, all deterministic from the seed, each part on its own random stream:
//  - terrain: a sum of three sinusoids (wavelengths 75, 36, 17 m; amplitudes 1.6, 0.7,
//    0.3 m) over a 140 m square; one object with two levels (96^2 and 24^2 cells);
//  - grove: a centre G near (-17, -13); tree density 0.1 + 0.9 exp(-|p - G|^2 / (2 * 16^2));
//  - path: a spline from the meadow (G + 26 m along a seeded direction) through G and out
//    the other side, walked in kWalkFrames frames at eye height;
//  - trees: rejection sampling of the density with 3.2 m spacing, kept 2.5 m from the path
//    and the viewpoints so no camera stands in a trunk; species by local density (pines
//    in the grove, oaks and birches on the meadow), at least two species guaranteed.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "forest_tree.hpp"
#include "procedural.hpp"
#include "procedural_textures.hpp"
#include "scenes/builtin.hpp"
#include "scenes/mesh_builder.hpp"

namespace lodopt::scenes {

namespace {

using forest::Species;
using procedural::Rng;

constexpr float kTerrainHalfSize = 70.0f;  // metres
constexpr float kPlantHalfSize = 58.0f;    // trees stay this far from the centre (metres)
constexpr float kEyeHeight = 1.7f;         // metres above the ground
constexpr float kGroveSigma = 16.0f;       // metres
constexpr float kTreeSpacing = 3.2f;       // metres between trunks
constexpr float kCameraClearance = 2.5f;   // metres from the path and viewpoints to a trunk
constexpr int kWalkFrames = 720;           // 24 s at 30 fps, about 2 m/s
constexpr float kWalkFramesPerSecond = 30.0f;

enum Stream : std::uint64_t { kTerrainStream = 1, kLayoutStream = 2, kPathStream = 3, kTreeStreamBase = 1000 };

struct Terrain {
    std::array<glm::vec2, 3> direction;
    std::array<float, 3> phase;

    float height(float x, float z) const {
        static constexpr float kAmplitude[3] = {1.6f, 0.7f, 0.3f};
        static constexpr float kWavelength[3] = {75.0f, 36.0f, 17.0f};
        float h = 0.0f;
        for (int i = 0; i < 3; ++i) {
            float s = glm::dot(direction[i], glm::vec2(x, z)) / kWavelength[i];
            h += kAmplitude[i] * std::sin(glm::two_pi<float>() * s + phase[i]);
        }
        return h;
    }
};

Terrain makeTerrain(std::uint32_t seed) {
    Rng rng(seed, kTerrainStream);
    Terrain terrain;
    for (int i = 0; i < 3; ++i) {
        float angle = rng.uniform(0.0f, glm::two_pi<float>());
        terrain.direction[i] = {std::cos(angle), std::sin(angle)};
        terrain.phase[i] = rng.uniform(0.0f, glm::two_pi<float>());
    }
    return terrain;
}

// Textures and materials: per species bark, small bark, leaf card and foliage; grass at two
// sizes. Returns the tree materials per species and sets the two terrain materials.
std::array<forest::TreeMaterials, forest::kSpeciesCount> addForestMaterials(Scene& scene, std::uint32_t seed,
                                                                            int& grass, int& grassSmall) {
    auto addTexture = [&](Texture texture) { return procedural::addTexture(scene, std::move(texture)); };
    auto addMaterial = [&](std::string name, glm::vec3 color, int texture) {
        return procedural::addDiffuseMaterial(scene, std::move(name), color, texture);
    };
    std::array<forest::TreeMaterials, forest::kSpeciesCount> result;
    for (int s = 0; s < forest::kSpeciesCount; ++s) {
        const auto species = Species(s);
        const std::string name = forest::speciesName(species);
        const glm::vec3 bark = forest::barkColor(species), leaf = forest::leafColor(species);
        const std::uint32_t textureSeed = seed * 31u + std::uint32_t(s) * 7u;
        int barkTexture = addTexture(
            procedural::makeBarkTexture(name + "_bark", 64, 128, bark, s == 0 ? 0 : (s == 1 ? 1 : 2), textureSeed));
        int barkSmall = addTexture(procedural::makeBarkTexture(name + "_bark_small", 16, 32, bark,
                                                               s == 0 ? 0 : (s == 1 ? 1 : 2), textureSeed));
        int leafTexture = addTexture(procedural::makeLeafTexture(name + "_leaf", 32, leaf, textureSeed + 1u));
        int foliage = addTexture(procedural::makeFoliageTexture(name + "_foliage", 32, leaf, textureSeed + 2u));
        forest::TreeMaterials& m = result[std::size_t(s)];
        m.bark = addMaterial(name + "_bark", glm::vec3(1.0f), barkTexture);
        m.leaves = addMaterial(name + "_leaves", glm::vec3(1.0f), leafTexture);
        m.hullTrunk = addMaterial(name + "_hull_trunk", glm::vec3(1.0f), barkSmall);
        m.crown = addMaterial(name + "_crown", glm::vec3(1.0f), foliage);
        m.flatTrunk = addMaterial(name + "_flat_trunk", bark, -1);
    }
    grass = addMaterial("grass", glm::vec3(1.0f), addTexture(procedural::makeGrassTexture("grass", 128, seed)));
    grassSmall =
        addMaterial("grass_small", glm::vec3(1.0f), addTexture(procedural::makeGrassTexture("grass_small", 32, seed)));
    return result;
}

Object makeTerrainObject(const Terrain& terrain, int grass, int grassSmall) {
    Object object;
    object.name = "terrain";
    const int cells[2] = {96, 24};
    const int materials[2] = {grass, grassSmall};
    const float repeats = 2.0f * kTerrainHalfSize / 8.0f;  // one texture repeat per 8 m
    for (int level = 0; level < 2; ++level) {
        MeshBuilder builder(materials[level]);
        builder.addHeightGrid(glm::vec3(0.0f), glm::vec2(2.0f * kTerrainHalfSize), cells[level], cells[level],
                              [&](float x, float z) { return terrain.height(x, z); });
        Mesh mesh = builder.finish();
        for (glm::vec2& uv : mesh.uvs) uv *= repeats;
        Level result;
        result.meshes.push_back(std::move(mesh));
        object.levels.push_back(std::move(result));
    }
    return object;
}

float distanceToPolyline(glm::vec2 p, const std::vector<glm::vec3>& polyline) {
    float best = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
        glm::vec2 a(polyline[i].x, polyline[i].z), b(polyline[i + 1].x, polyline[i + 1].z);
        glm::vec2 ab = b - a;
        float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
        best = std::min(best, glm::length(p - (a + t * ab)));
    }
    return best;
}

struct TreeSite {
    glm::vec2 position;
    Species species;
};

Species pickSpecies(float density, Rng& rng) {
    float r = rng.uniform();
    if (density > 0.5f) return r < 0.55f ? Species::Pine : (r < 0.85f ? Species::Oak : Species::Birch);
    return r < 0.5f ? Species::Oak : (r < 0.8f ? Species::Birch : Species::Pine);
}

std::vector<TreeSite> placeTrees(std::uint32_t seed, glm::vec2 grove, const std::vector<glm::vec3>& path,
                                 const std::vector<glm::vec3>& viewpoints) {
    Rng rng(seed, kLayoutStream);
    const int target = rng.uniformInt(45, 80);
    std::vector<TreeSite> sites;
    for (int attempt = 0; attempt < 40000 && int(sites.size()) < target; ++attempt) {
        glm::vec2 p(rng.uniform(-kPlantHalfSize, kPlantHalfSize), rng.uniform(-kPlantHalfSize, kPlantHalfSize));
        glm::vec2 fromGrove = p - grove;
        float density = 0.1f + 0.9f * std::exp(-glm::dot(fromGrove, fromGrove) / (2.0f * kGroveSigma * kGroveSigma));
        Species species = pickSpecies(density, rng);
        if (!rng.chance(density)) continue;
        bool crowded = std::any_of(sites.begin(), sites.end(),
                                   [&](const TreeSite& s) { return glm::length(s.position - p) < kTreeSpacing; });
        if (crowded || distanceToPolyline(p, path) < kCameraClearance) continue;
        if (std::any_of(viewpoints.begin(), viewpoints.end(),
                        [&](glm::vec3 v) { return glm::length(glm::vec2(v.x, v.z) - p) < kCameraClearance; })) {
            continue;
        }
        sites.push_back({p, species});
    }
    // Two species at least, whatever the draw: turn the first tree into another species.
    bool mixed =
        std::any_of(sites.begin(), sites.end(), [&](const TreeSite& s) { return s.species != sites[0].species; });
    if (!sites.empty() && !mixed) sites[0].species = sites[0].species == Species::Oak ? Species::Pine : Species::Oak;
    return sites;
}

Camera eyeLevelLens() {
    Camera lens;
    lens.fovYDegrees = 60.0f;
    lens.nearPlane = 0.1f;
    lens.farPlane = 400.0f;
    return lens;
}

Camera makeView(const std::string& name, glm::vec3 position, glm::vec3 target, const Camera& lens) {
    Camera camera = lens;
    camera.name = name;
    camera.position = position;
    camera.target = target;
    return camera;
}

}  // namespace

Scene makeForestScene(std::uint32_t seed) {
    Scene scene;
    scene.name = "forest";
    const Terrain terrain = makeTerrain(seed);
    auto ground = [&](glm::vec2 p, float above) { return glm::vec3(p.x, terrain.height(p.x, p.y) + above, p.y); };

    // The grove and the walk: from the meadow along `outward` back through the grove.
    Rng pathRng(seed, kPathStream);
    const glm::vec2 grove(pathRng.uniform(-22.0f, -12.0f), pathRng.uniform(-18.0f, -8.0f));
    const float heading = std::atan2(0.8f, 1.0f) + pathRng.uniform(-0.3f, 0.3f);
    const glm::vec2 outward(std::cos(heading), std::sin(heading));
    const glm::vec2 across(-outward.y, outward.x);
    const float stations[5] = {26.0f, 14.0f, 3.0f, -8.0f, -17.0f};
    const float sway[5] = {2.0f, -1.5f, 1.0f, -2.0f, 1.0f};
    std::vector<glm::vec3> controls;
    for (int i = 0; i < 5; ++i) {
        glm::vec2 p = grove + outward * stations[i] + across * (sway[i] * pathRng.uniform(0.5f, 1.5f));
        controls.push_back({p.x, 0.0f, p.y});
    }
    std::vector<glm::vec3> eyes = procedural::sampleSplineEvenly(controls, kWalkFrames);
    for (glm::vec3& eye : eyes) eye = ground({eye.x, eye.z}, kEyeHeight);

    // Viewpoints: inside the grove, out on the meadow, at the grove's edge, and from above.
    const Camera lens = eyeLevelLens();
    std::size_t nearest = 0;
    for (std::size_t i = 0; i < eyes.size(); ++i) {
        if (glm::length(glm::vec2(eyes[i].x, eyes[i].z) - grove) <
            glm::length(glm::vec2(eyes[nearest].x, eyes[nearest].z) - grove)) {
            nearest = i;
        }
    }
    // In the grove, looking across the path (the path itself is kept clear of trunks).
    const glm::vec3 densePosition = eyes[nearest];
    const glm::vec3 denseTarget = ground(glm::vec2(densePosition.x, densePosition.z) + across * 20.0f, 3.0f);
    // On the meadow, looking away from the grove.
    const glm::vec3 sparsePosition = ground(grove + outward * 34.0f, kEyeHeight);
    const glm::vec3 sparseTarget = ground(grove + outward * 80.0f, kEyeHeight + 2.0f);
    const glm::vec3 edgePosition = ground(grove + outward * 30.0f - across * 6.0f, kEyeHeight);
    const glm::vec3 edgeTarget = ground(grove, 4.0f);
    scene.views.push_back(makeView("dense", densePosition, denseTarget, lens));
    scene.views.push_back(makeView("sparse", sparsePosition, sparseTarget, lens));
    scene.views.push_back(makeView("edge", edgePosition, edgeTarget, lens));
    Camera overview = makeView("overview", ground(grove * 0.3f + outward * 80.0f - across * 20.0f, 45.0f),
                               ground(grove * 0.6f, 0.0f), lens);
    overview.fovYDegrees = 50.0f;
    overview.nearPlane = 0.5f;
    overview.farPlane = 600.0f;
    scene.views.push_back(overview);
    scene.paths.push_back(procedural::makeLookAheadPath("walkthrough", kWalkFramesPerSecond, eyes, 45, -0.3f, lens));

    int grass = -1, grassSmall = -1;
    const auto treeMaterials = addForestMaterials(scene, seed, grass, grassSmall);
    scene.objects.push_back(makeTerrainObject(terrain, grass, grassSmall));

    const std::vector<TreeSite> sites = placeTrees(seed, grove, eyes, {densePosition, sparsePosition, edgePosition});
    for (std::size_t i = 0; i < sites.size(); ++i) {
        Rng treeRng(seed, kTreeStreamBase + i);
        const TreeSite& site = sites[i];
        forest::TreeSkeleton skeleton = forest::growTree(site.species, treeRng);
        Object tree;
        char name[48];
        std::snprintf(name, sizeof(name), "tree_%03zu_%s", i, forest::speciesName(site.species));
        tree.name = name;
        tree.transform = glm::rotate(glm::translate(glm::mat4(1.0f), ground(site.position, 0.0f)),
                                     treeRng.uniform(0.0f, glm::two_pi<float>()), glm::vec3(0.0f, 1.0f, 0.0f));
        tree.levels = forest::buildTreeLevels(skeleton, treeMaterials[std::size_t(site.species)]);
        scene.objects.push_back(std::move(tree));
    }
    updateStatistics(scene);
    validateScene(scene);
    return scene;
}

}  // namespace lodopt::scenes
