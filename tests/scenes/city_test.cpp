// The built-in city: building count and levels, determinism, per-level statistics, facade
// geometry, viewpoints and the fly-through path.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>

#include "scenes/builtin.hpp"
#include "scenes/scene.hpp"

namespace {

using namespace lodopt::scenes;

const Scene& citySeed1() {
    static const Scene scene = makeCityScene(1);
    return scene;
}

bool isBuilding(const Object& object) {
    return object.name.rfind("building_", 0) == 0;
}

bool finite(glm::vec3 v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

const std::string& materialName(const Scene& scene, const Mesh& mesh) {
    return scene.materials[std::size_t(mesh.material)].name;
}

bool startsWith(const std::string& text, const std::string& prefix) {
    return text.rfind(prefix, 0) == 0;
}

TEST(CityScene, IsValidAndNamed) {
    const Scene& scene = citySeed1();
    EXPECT_EQ(scene.name, "city");
    EXPECT_NO_THROW(validateScene(scene));
    EXPECT_TRUE(isBuiltinScene("city"));
}

TEST(CityScene, HasOverAThousandBuildingsWithThreeLevelsForSeveralSeeds) {
    for (std::uint32_t seed : {1u, 2u, 99u, 0xFFFFFFFFu}) {
        Scene scene = makeCityScene(seed);
        int buildings = 0, ground = 0;
        for (const Object& object : scene.objects) {
            if (isBuilding(object)) {
                ++buildings;
                EXPECT_EQ(object.levels.size(), 3u) << object.name;
            } else {
                ++ground;
                EXPECT_EQ(object.name, "ground");
                EXPECT_GE(object.levels.size(), 1u);
                EXPECT_LE(object.levels.size(), 2u);
            }
        }
        EXPECT_GE(buildings, 1000) << "seed " << seed;
        EXPECT_EQ(ground, 1) << "seed " << seed;
    }
}

TEST(CityScene, SameSeedGivesIdenticalSceneAndDifferentSeedsDiffer) {
    const auto start = std::chrono::steady_clock::now();
    Scene a = makeCityScene(5);
    const double buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    RecordProperty("build_ms", std::to_string(buildMs));  // reported, not asserted
    Scene b = makeCityScene(5);
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (std::size_t o = 0; o < a.objects.size(); ++o) {
        const Object &x = a.objects[o], &y = b.objects[o];
        ASSERT_EQ(x.name, y.name);
        EXPECT_TRUE(x.transform == y.transform) << x.name;
        ASSERT_EQ(x.levels.size(), y.levels.size());
        for (std::size_t l = 0; l < x.levels.size(); ++l) {
            ASSERT_EQ(x.levels[l].meshes.size(), y.levels[l].meshes.size());
            for (std::size_t m = 0; m < x.levels[l].meshes.size(); ++m) {
                const Mesh &p = x.levels[l].meshes[m], &q = y.levels[l].meshes[m];
                EXPECT_TRUE(p.positions == q.positions && p.normals == q.normals && p.uvs == q.uvs &&
                            p.indices == q.indices && p.material == q.material)
                    << x.name << " level " << l;
            }
        }
    }
    for (std::size_t t = 0; t < a.textures.size(); ++t) EXPECT_TRUE(a.textures[t].rgba == b.textures[t].rgba);

    Scene c = makeCityScene(6);
    bool differs = a.objects.size() != c.objects.size();
    for (std::size_t o = 0; !differs && o < a.objects.size(); ++o) {
        differs = a.objects[o].transform != c.objects[o].transform ||
                  a.objects[o].levels[0].meshes[0].positions != c.objects[o].levels[0].meshes[0].positions;
    }
    EXPECT_TRUE(differs);
}

TEST(CityScene, StatisticsShrinkFromFinestToCoarsestAndNoLevelIsEmpty) {
    const Scene& scene = citySeed1();
    for (const Object& object : scene.objects) {
        for (std::size_t l = 0; l < object.levels.size(); ++l) {
            const Level& level = object.levels[l];
            EXPECT_EQ(level.stats.triangles, computeLevelStats(scene, level).triangles) << object.name;
            EXPECT_GT(level.stats.triangles, 0u) << object.name << " level " << l;
            EXPECT_GT(level.stats.drawCalls, 0u) << object.name << " level " << l;
            for (const Mesh& mesh : level.meshes) EXPECT_FALSE(mesh.indices.empty()) << object.name << " level " << l;
            if (l == 0) continue;
            const LevelStats& finer = object.levels[l - 1].stats;
            if (isBuilding(object)) {
                // Walls with windows + roof, facade + roof, box.
                const std::uint32_t expected[3] = {2, 2, 1};
                EXPECT_EQ(level.stats.drawCalls, expected[l]) << object.name << " level " << l;
            }
            EXPECT_LT(level.stats.vertices, finer.vertices) << object.name << " level " << l;
            EXPECT_LT(level.stats.triangles, finer.triangles) << object.name << " level " << l;
            EXPECT_LT(level.stats.textureBytes, finer.textureBytes) << object.name << " level " << l;
            EXPECT_LE(level.stats.drawCalls, finer.drawCalls) << object.name << " level " << l;
        }
    }
}

TEST(CityScene, DetailedLevelHasRecessedWindowsAndRoofShapes) {
    const Scene& scene = citySeed1();
    int flat = 0, pitched = 0;
    for (const Object& building : scene.objects) {
        if (!isBuilding(building)) continue;
        const Level& detailed = building.levels[0];
        ASSERT_EQ(detailed.meshes.size(), 2u) << building.name;
        const Mesh &wall = detailed.meshes[0], &roof = detailed.meshes[1];
        ASSERT_TRUE(startsWith(materialName(scene, wall), "wall_")) << building.name;
        // Window ribbons are the vertices in the window half of the texture (v >= 0.5): they
        // sit 0.3 m inside the footprint on every side, while plaster reaches the footprint.
        const Bounds footprint = building.levels[2].stats.bounds;  // the box: exactly the footprint
        glm::vec3 windowMax(-1e30f), windowMin(1e30f);
        float plasterMaxX = -1e30f;
        int windowVertices = 0;
        for (std::size_t v = 0; v < wall.positions.size(); ++v) {
            const glm::vec3& p = wall.positions[v];
            if (wall.uvs[v].y >= 0.5f) {
                ++windowVertices;
                windowMax = glm::max(windowMax, p);
                windowMin = glm::min(windowMin, p);
            } else {
                plasterMaxX = std::max(plasterMaxX, p.x);
            }
        }
        ASSERT_GT(windowVertices, 0) << building.name;
        EXPECT_NEAR(windowMax.x, footprint.max.x - 0.3f, 1e-3f) << building.name;
        EXPECT_NEAR(windowMin.x, footprint.min.x + 0.3f, 1e-3f) << building.name;
        EXPECT_NEAR(windowMax.z, footprint.max.z - 0.3f, 1e-3f) << building.name;
        EXPECT_NEAR(windowMin.z, footprint.min.z + 0.3f, 1e-3f) << building.name;
        EXPECT_GE(plasterMaxX, footprint.max.x - 1e-4f) << building.name;
        if (materialName(scene, roof) == "roof_tiles")
            ++pitched;
        else if (materialName(scene, roof) == "roof_gravel")
            ++flat;
        else
            ADD_FAILURE() << building.name << ": unexpected roof material " << materialName(scene, roof);
    }
    EXPECT_GT(flat, 100);
    EXPECT_GT(pitched, 100);
}

bool insideAnyBuilding(const Scene& scene, glm::vec3 p, float margin) {
    for (const Object& object : scene.objects) {
        if (!isBuilding(object)) continue;
        Bounds b = worldBounds(object, 0);
        if (p.x > b.min.x - margin && p.x < b.max.x + margin && p.y < b.max.y + margin && p.z > b.min.z - margin &&
            p.z < b.max.z + margin) {
            return true;
        }
    }
    return false;
}

int buildingsInView(const Scene& scene, const Camera& camera) {
    const glm::mat4 clip = projectionMatrix(camera, 1.0f) * viewMatrix(camera);
    int count = 0;
    for (const Object& object : scene.objects) {
        if (!isBuilding(object)) continue;
        glm::vec4 p = clip * glm::vec4(worldBounds(object, 0).sphereCenter, 1.0f);
        if (p.w > 0.0f && std::abs(p.x) < p.w && std::abs(p.y) < p.w && p.z > -p.w && p.z < p.w) ++count;
    }
    return count;
}

TEST(CityScene, NamedViewsSeeBuildingsFromOutsideThem) {
    const Scene& scene = citySeed1();
    for (const char* name : {"street", "avenue", "aerial", "skyline"}) {
        const Camera& camera = scene.views[std::size_t(findView(scene, name))];
        EXPECT_TRUE(finite(camera.position) && finite(camera.target)) << name;
        EXPECT_GT(glm::length(camera.target - camera.position), 1.0f) << name;
        EXPECT_GT(camera.position.y, 1.0f) << name;
        EXPECT_FALSE(insideAnyBuilding(scene, camera.position, 1.0f)) << name;
        EXPECT_GE(buildingsInView(scene, camera), 20) << name;
    }
    EXPECT_LT(scene.views[std::size_t(findView(scene, "street"))].position.y, 2.0f);
    EXPECT_GT(scene.views[std::size_t(findView(scene, "aerial"))].position.y, 200.0f);
}

TEST(CityScene, FlythroughPathStaysOutsideBuildingsAndLooksAtTheCity) {
    const Scene& scene = citySeed1();
    ASSERT_EQ(scene.paths.size(), 1u);
    const CameraPath& path = scene.paths[0];
    EXPECT_EQ(path.name, "flythrough");
    ASSERT_GE(path.frames.size(), 200u);
    EXPECT_GT(path.framesPerSecond, 0.0f);
    int framesSeeingBuildings = 0;
    for (std::size_t i = 0; i < path.frames.size(); ++i) {
        const Camera& frame = path.frames[i];
        ASSERT_TRUE(finite(frame.position) && finite(frame.target)) << "frame " << i;
        EXPECT_GT(glm::length(frame.target - frame.position), 1.0f) << "frame " << i;
        EXPECT_GT(frame.position.y, 5.0f) << "frame " << i;
        EXPECT_FALSE(insideAnyBuilding(scene, frame.position, 2.0f)) << "frame " << i;
        if (i > 0) {
            EXPECT_LT(glm::length(frame.position - path.frames[i - 1].position), 5.0f) << "frame " << i;
        }
        if (i % 50 == 0) {
            int seen = buildingsInView(scene, frame);
            EXPECT_GE(seen, 20) << "frame " << i;
            if (seen >= 20) ++framesSeeingBuildings;
        }
    }
    EXPECT_EQ(framesSeeingBuildings, int((path.frames.size() + 49) / 50));
}

}  // namespace
