// The built-in forest: tree count and species, determinism, per-level statistics, DONG15
// leaf pruning (checked against an independent reimplementation of the rule on the meshes),
// viewpoints and the walk-through path.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "scenes/builtin.hpp"
#include "scenes/scene.hpp"

namespace {

using namespace lodopt::scenes;

const Scene& forestSeed1() {
    static const Scene scene = makeForestScene(1);
    return scene;
}

bool isTree(const Object& object) {
    return object.name.rfind("tree_", 0) == 0;
}

std::string speciesOf(const Object& tree) {
    return tree.name.substr(tree.name.find_last_of('_') + 1);
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 translationOf(const Object& object) {
    return glm::vec3(object.transform[3]);
}

TEST(ForestScene, IsValidAndNamed) {
    const Scene& scene = forestSeed1();
    EXPECT_EQ(scene.name, "forest");
    EXPECT_NO_THROW(validateScene(scene));
    EXPECT_TRUE(isBuiltinScene("forest"));
    EXPECT_EQ(makeBuiltinScene("forest", 1).objects.size(), scene.objects.size());
}

TEST(ForestScene, HasThirtyToHundredTreesOfSeveralSpeciesForManySeeds) {
    for (std::uint32_t seed : {1u, 2u, 3u, 4u, 5u, 17u, 123456u, 0xFFFFFFFFu}) {
        Scene scene = makeForestScene(seed);
        int trees = 0;
        std::set<std::string> species;
        for (const Object& object : scene.objects) {
            if (!isTree(object)) continue;
            ++trees;
            species.insert(speciesOf(object));
            EXPECT_GE(object.levels.size(), 4u) << object.name;
        }
        EXPECT_GE(trees, 30) << "seed " << seed;
        EXPECT_LE(trees, 100) << "seed " << seed;
        EXPECT_GE(species.size(), 2u) << "seed " << seed;
        for (const std::string& name : species) {
            EXPECT_TRUE(name == "oak" || name == "pine" || name == "birch") << name;
        }
    }
}

void expectSameMesh(const Mesh& a, const Mesh& b, const std::string& where) {
    EXPECT_EQ(a.material, b.material) << where;
    EXPECT_TRUE(a.positions == b.positions) << where;
    EXPECT_TRUE(a.normals == b.normals) << where;
    EXPECT_TRUE(a.uvs == b.uvs) << where;
    EXPECT_TRUE(a.indices == b.indices) << where;
}

TEST(ForestScene, SameSeedGivesIdenticalScene) {
    const auto start = std::chrono::steady_clock::now();
    Scene a = makeForestScene(42);
    const double buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    RecordProperty("build_ms", std::to_string(buildMs));  // reported, not asserted
    Scene b = makeForestScene(42);
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (std::size_t o = 0; o < a.objects.size(); ++o) {
        const Object &x = a.objects[o], &y = b.objects[o];
        EXPECT_EQ(x.name, y.name);
        EXPECT_TRUE(x.transform == y.transform) << x.name;
        ASSERT_EQ(x.levels.size(), y.levels.size()) << x.name;
        for (std::size_t l = 0; l < x.levels.size(); ++l) {
            ASSERT_EQ(x.levels[l].meshes.size(), y.levels[l].meshes.size());
            for (std::size_t m = 0; m < x.levels[l].meshes.size(); ++m) {
                expectSameMesh(x.levels[l].meshes[m], y.levels[l].meshes[m], x.name + " level " + std::to_string(l));
            }
        }
    }
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (std::size_t t = 0; t < a.textures.size(); ++t) EXPECT_TRUE(a.textures[t].rgba == b.textures[t].rgba);
    ASSERT_EQ(a.paths.size(), b.paths.size());
    for (std::size_t f = 0; f < a.paths[0].frames.size(); ++f) {
        EXPECT_EQ(a.paths[0].frames[f].position, b.paths[0].frames[f].position);
    }
}

TEST(ForestScene, DifferentSeedGivesDifferentScene) {
    Scene a = makeForestScene(1), b = makeForestScene(2);
    bool differs = a.objects.size() != b.objects.size();
    for (std::size_t o = 0; !differs && o < a.objects.size(); ++o) {
        differs = a.objects[o].transform != b.objects[o].transform ||
                  a.objects[o].levels[0].meshes[0].positions != b.objects[o].levels[0].meshes[0].positions;
    }
    EXPECT_TRUE(differs);
}

TEST(ForestScene, StatisticsShrinkFromFinestToCoarsestAndNoLevelIsEmpty) {
    const Scene& scene = forestSeed1();
    for (const Object& object : scene.objects) {
        for (std::size_t l = 0; l < object.levels.size(); ++l) {
            const Level& level = object.levels[l];
            const LevelStats fresh = computeLevelStats(scene, level);
            EXPECT_EQ(level.stats.vertices, fresh.vertices) << object.name;
            EXPECT_EQ(level.stats.triangles, fresh.triangles) << object.name;
            EXPECT_GT(level.stats.triangles, 0u) << object.name << " level " << l;
            EXPECT_GT(level.stats.vertices, 0u) << object.name << " level " << l;
            EXPECT_GT(level.stats.drawCalls, 0u) << object.name << " level " << l;
            for (const Mesh& mesh : level.meshes) EXPECT_FALSE(mesh.indices.empty()) << object.name << " level " << l;
            if (l == 0) continue;
            const LevelStats& finer = object.levels[l - 1].stats;
            EXPECT_LE(level.stats.vertices, finer.vertices) << object.name << " level " << l;
            EXPECT_LT(level.stats.triangles, finer.triangles) << object.name << " level " << l;
            EXPECT_LE(level.stats.textureBytes, finer.textureBytes) << object.name << " level " << l;
            EXPECT_LE(level.stats.drawCalls, finer.drawCalls) << object.name << " level " << l;
        }
    }
}

// A leaf card read back from a level's leaf mesh: 4 vertices (base, right, tip, left).
struct CardLeaf {
    glm::vec3 base, tip, right, left;
    float length() const { return glm::length(tip - base); }
    float width() const { return glm::length(right - left); }
    float area() const { return 0.5f * length() * width(); }
    glm::vec3 center() const { return 0.5f * (base + tip); }
    glm::vec3 normal() const {
        return glm::normalize(glm::cross(glm::normalize(right - left), glm::normalize(tip - base)));
    }
};

const Mesh* leafMesh(const Scene& scene, const Level& level) {
    for (const Mesh& mesh : level.meshes) {
        const std::string& name = scene.materials[std::size_t(mesh.material)].name;
        if (name.size() > 7 && name.compare(name.size() - 7, 7, "_leaves") == 0) return &mesh;
    }
    return nullptr;
}

std::vector<CardLeaf> readLeaves(const Mesh& mesh) {
    std::vector<CardLeaf> leaves;
    for (std::size_t v = 0; v + 3 < mesh.positions.size(); v += 4) {
        leaves.push_back({mesh.positions[v], mesh.positions[v + 2], mesh.positions[v + 1], mesh.positions[v + 3]});
    }
    return leaves;
}

// DONG15 eq. (1) with the normalisation documented in forest_tree.hpp, written again here
// so that the test does not share the implementation's mistakes.
std::vector<float> importance(const std::vector<CardLeaf>& leaves) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    float maxArea = 0.0f;
    for (const CardLeaf& leaf : leaves) {
        lo = glm::min(lo, leaf.center());
        hi = glm::max(hi, leaf.center());
        maxArea = std::max(maxArea, leaf.area());
    }
    glm::vec3 crown = 0.5f * (lo + hi);
    float maxDistance = 0.0f;
    for (const CardLeaf& leaf : leaves) maxDistance = std::max(maxDistance, glm::length(leaf.center() - crown));
    std::vector<float> result;
    for (const CardLeaf& leaf : leaves) {
        glm::vec3 radial(leaf.center().x, 0.0f, leaf.center().z);
        radial = glm::length(radial) > 1e-6f ? glm::normalize(radial) : glm::vec3(1, 0, 0);
        float dis = glm::length(leaf.center() - crown) / maxDistance;
        float cosine = std::abs(glm::dot(leaf.normal(), radial));
        result.push_back(0.3f * dis + 0.4f * cosine + 0.3f * leaf.area() / maxArea);
    }
    return result;
}

TEST(ForestScene, CoarserLevelsPruneLeavesByVisualImportanceAndEnlargeTheRest) {
    const Scene& scene = forestSeed1();
    const float lambdas[3] = {1.0f, 0.5f, 0.25f};
    int checkedTrees = 0;
    for (const Object& tree : scene.objects) {
        if (!isTree(tree)) continue;
        const Mesh* fine = leafMesh(scene, tree.levels[0]);
        ASSERT_NE(fine, nullptr) << tree.name << ": level 0 has no leaf cards";
        const std::vector<CardLeaf> leaves = readLeaves(*fine);
        ASSERT_GT(leaves.size(), 100u) << tree.name;
        const std::vector<float> eps = importance(leaves);
        std::map<std::tuple<float, float, float>, std::size_t> byBase;
        for (std::size_t i = 0; i < leaves.size(); ++i)
            byBase[{leaves[i].base.x, leaves[i].base.y, leaves[i].base.z}] = i;
        for (int l = 1; l <= 2; ++l) {
            const Mesh* pruned = leafMesh(scene, tree.levels[std::size_t(l)]);
            ASSERT_NE(pruned, nullptr) << tree.name << " level " << l;
            const std::vector<CardLeaf> kept = readLeaves(*pruned);
            EXPECT_EQ(kept.size(), std::size_t(std::ceil(double(lambdas[l]) * double(leaves.size())))) << tree.name;
            std::vector<bool> isKept(leaves.size(), false);
            for (const CardLeaf& leaf : kept) {
                auto found = byBase.find({leaf.base.x, leaf.base.y, leaf.base.z});
                ASSERT_NE(found, byBase.end()) << tree.name << " level " << l << ": a leaf that level 0 does not have";
                isKept[found->second] = true;
                // DONG15 eq. (3): area x 1/sqrt(lambda).
                EXPECT_NEAR(leaf.area() / leaves[found->second].area(), 1.0f / std::sqrt(lambdas[l]), 1e-3f)
                    << tree.name;
            }
            float minKept = 1e30f, maxDropped = -1e30f;
            for (std::size_t i = 0; i < leaves.size(); ++i) {
                if (isKept[i])
                    minKept = std::min(minKept, eps[i]);
                else
                    maxDropped = std::max(maxDropped, eps[i]);
            }
            // Tolerance: the test recomputes eps from rounded vertex positions.
            EXPECT_GE(minKept, maxDropped - 1e-4f) << tree.name << " level " << l;
        }
        for (std::size_t l = 3; l < tree.levels.size(); ++l) {
            EXPECT_EQ(leafMesh(scene, tree.levels[l]), nullptr)
                << tree.name << " level " << l << " still has leaf cards";
            EXPECT_LT(tree.levels[l].stats.triangles, 200u) << tree.name << " level " << l << " is no hull/billboard";
        }
        ++checkedTrees;
    }
    EXPECT_GE(checkedTrees, 30);
}

// How many trees have their bounding-sphere centre inside the camera's view frustum.
int treesInView(const Scene& scene, const Camera& camera) {
    const glm::mat4 clip = projectionMatrix(camera, 1.0f) * viewMatrix(camera);
    int count = 0;
    for (const Object& object : scene.objects) {
        if (!isTree(object)) continue;
        glm::vec4 p = clip * glm::vec4(worldBounds(object, 0).sphereCenter, 1.0f);
        if (p.w > 0.0f && std::abs(p.x) < p.w && std::abs(p.y) < p.w && p.z > -p.w && p.z < p.w) ++count;
    }
    return count;
}

int treesWithin(const Scene& scene, glm::vec3 position, float radius) {
    int count = 0;
    for (const Object& object : scene.objects) {
        if (!isTree(object)) continue;
        glm::vec3 base = translationOf(object);
        if (glm::length(glm::vec2(base.x - position.x, base.z - position.z)) < radius) ++count;
    }
    return count;
}

float nearestTrunk(const Scene& scene, glm::vec3 position) {
    float best = 1e30f;
    for (const Object& object : scene.objects) {
        if (!isTree(object)) continue;
        glm::vec3 base = translationOf(object);
        best = std::min(best, glm::length(glm::vec2(base.x - position.x, base.z - position.z)));
    }
    return best;
}

TEST(ForestScene, NamedViewsLookAtTrees) {
    for (std::uint32_t seed : {1u, 2u, 3u}) {
        Scene scene = makeForestScene(seed);
        for (const char* name : {"dense", "sparse", "edge", "overview"}) {
            const Camera& camera = scene.views[std::size_t(findView(scene, name))];
            EXPECT_TRUE(finite(camera.position) && finite(camera.target)) << name;
            EXPECT_GT(glm::length(camera.target - camera.position), 1.0f) << name;
            EXPECT_GT(camera.farPlane, camera.nearPlane) << name;
            EXPECT_GE(treesInView(scene, camera), std::string(name) == "sparse" ? 2 : 8) << name << " seed " << seed;
            if (std::string(name) != "overview") {
                EXPECT_GT(nearestTrunk(scene, camera.position), 2.0f) << name << " stands in a tree, seed " << seed;
            }
        }
        const Camera& dense = scene.views[std::size_t(findView(scene, "dense"))];
        const Camera& sparse = scene.views[std::size_t(findView(scene, "sparse"))];
        EXPECT_GT(treesWithin(scene, dense.position, 20.0f), treesWithin(scene, sparse.position, 20.0f)) << seed;
        const Camera& overview = scene.views[std::size_t(findView(scene, "overview"))];
        EXPECT_GT(overview.position.y, dense.position.y + 20.0f);
    }
}

TEST(ForestScene, WalkthroughPathIsSmoothAndKeepsClearOfTrunks) {
    const Scene& scene = forestSeed1();
    ASSERT_EQ(scene.paths.size(), 1u);
    const CameraPath& path = scene.paths[0];
    EXPECT_EQ(path.name, "walkthrough");
    EXPECT_GT(path.framesPerSecond, 0.0f);
    ASSERT_GE(path.frames.size(), 200u);
    EXPECT_LE(path.frames.size(), 3000u);
    float length = 0.0f;
    for (std::size_t i = 0; i < path.frames.size(); ++i) {
        const Camera& frame = path.frames[i];
        ASSERT_TRUE(finite(frame.position) && finite(frame.target)) << "frame " << i;
        glm::vec3 view = frame.target - frame.position;
        EXPECT_GT(glm::length(view), 1.0f) << "frame " << i;
        EXPECT_LT(std::abs(view.y), glm::length(glm::vec2(view.x, view.z))) << "frame " << i << " looks too steeply";
        EXPECT_GT(nearestTrunk(scene, frame.position), 2.0f) << "frame " << i;
        if (i > 0) {
            float step = glm::length(frame.position - path.frames[i - 1].position);
            EXPECT_LT(step * path.framesPerSecond, 5.0f) << "frame " << i << ": faster than a walk";
            length += step;
        }
    }
    EXPECT_GT(length, 20.0f);
    EXPECT_GT(treesInView(scene, path.frames.front()), 3);
}

}  // namespace
