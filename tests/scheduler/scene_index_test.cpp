// The scheduler's per-frame knowledge without rendering: frustum culling, the projected box,
// the Bounds-mode features against the exact FeatureTable, and the quadtree of tiles.
#include "scheduler/scene_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures.hpp"
#include "scenes/mesh_builder.hpp"
#include "scheduler/tiles.hpp"
#include "timemodel/features.hpp"

namespace lodopt::scheduler {
namespace {

using timemodel::Feature;

TEST(Frustum, CullsSpheresAndBoxes) {
    const scenes::Camera camera = testing::lookAt({0, 0, 0}, {0, 0, -1}, 60.0f);
    const glm::mat4 vp = scenes::projectionMatrix(camera, 1.0f) * scenes::viewMatrix(camera);
    const Frustum f = Frustum::fromViewProjection(vp);
    EXPECT_TRUE(f.intersectsSphere({0, 0, -10}, 1.0f));
    EXPECT_FALSE(f.intersectsSphere({0, 0, 10}, 1.0f));      // behind
    EXPECT_FALSE(f.intersectsSphere({100, 0, -10}, 1.0f));   // far to the right
    EXPECT_TRUE(f.intersectsSphere({6.5f, 0, -10}, 1.0f));   // tan 30° · 10 = 5.77: touches
    EXPECT_FALSE(f.intersectsSphere({0, 0, -20000}, 1.0f));  // beyond the far plane
    EXPECT_TRUE(f.intersectsBox({-1, -1, -11}, {1, 1, -9}));
    EXPECT_FALSE(f.intersectsBox({-1, -1, 9}, {1, 1, 11}));
    EXPECT_TRUE(f.intersectsBox({-1000, -1, -11}, {1000, 1, -9}));  // spans the view
}

TEST(ProjectBox, VisibleAreaIsTheTimeModelsProjectedPixels) {
    const scenes::Scene scene = testing::makeGridScene(3, 3, 4.0f);
    const std::vector<scenes::Camera> cameras = {testing::lookAt({0, 3, 12}, {0, 0, 0}),
                                                 testing::lookAt({2, 1, 3}, {8, 0, 0}),  // partly off screen
                                                 testing::lookAt({0, 40, 1}, {0, 0, 0})};
    for (const scenes::Camera& camera : cameras) {
        const glm::mat4 vp = scenes::projectionMatrix(camera, 1.5f) * scenes::viewMatrix(camera);
        for (const scenes::Object& object : scene.objects) {
            for (const scenes::Level& level : object.levels) {
                const glm::mat4 mvp = vp * object.transform;
                const ProjectedBox box = projectBox(level.stats.bounds, mvp, 150, 100);
                EXPECT_DOUBLE_EQ(box.visibleArea, timemodel::projectedPixels(level.stats.bounds, mvp, 150, 100));
                EXPECT_GE(box.area + 1e-6, box.visibleArea);
            }
        }
    }
}

// Bounds mode approximates the geometry-walking features; here every object is either fully
// in view or partly cut by the viewport, from directions between the canonical ones.
TEST(SceneIndex, BoundsFeaturesTrackExactOnes) {
    const scenes::Scene scene = testing::makeGridScene(3, 3, 5.0f);
    const SceneIndex bounds(scene, 128, 96, FeatureMode::Bounds);
    const SceneIndex exact(scene, 128, 96, FeatureMode::Exact);
    FrameObjects a, b;
    int compared = 0;
    for (const scenes::Camera& camera :
         {testing::lookAt({3, 6, 18}, {0, 0, 0}), testing::lookAt({-14, 4, 9}, {0, 1, 0}),
          testing::lookAt({1, 2, 9}, {3, 1, 0})}) {
        bounds.beginFrame(camera, a);
        exact.beginFrame(camera, b);
        double sumA[timemodel::kFeatureCount] = {}, sumB[timemodel::kFeatureCount] = {};
        for (int o = 0; o < bounds.objectCount(); ++o) {
            const bool seenA = bounds.observe(o, a);
            const bool seenB = exact.observe(o, b);
            ASSERT_EQ(seenA, seenB);  // culling does not depend on the mode
            if (!seenA) continue;
            for (int l = 0; l < bounds.levelCount(o); ++l) {
                const timemodel::FrameFeatures& fa = a.contributions[bounds.firstLevel(o) + l];
                const timemodel::FrameFeatures& fb = b.contributions[exact.firstLevel(o) + l];
                // Stats are exact in both modes, the projected box too (up to the 2% box tolerance
                // under which a level reuses the previous level's projection).
                for (Feature f :
                     {Feature::kVertices, Feature::kTriangles, Feature::kDrawCalls, Feature::kDrawnObjects}) {
                    EXPECT_NEAR(fa[f], fb[f], 1e-6 * std::max(1.0, fb[f])) << timemodel::featureName(f);
                }
                const double pixelTolerance = l == 0 ? 1e-6 * fb[Feature::kPixels] : 0.05 * fb[Feature::kPixels] + 1.0;
                EXPECT_NEAR(fa[Feature::kPixels], fb[Feature::kPixels], pixelTolerance) << "level " << l;
                for (std::size_t k = 0; k < timemodel::kFeatureCount; ++k) {
                    sumA[k] += fa.values[k];
                    sumB[k] += fb.values[k];
                }
                ++compared;
            }
        }
        // Frame sums of the approximated features: within 35% (the canonical directions are
        // 45° apart and the share of a box on screen is not the share of its triangles).
        for (Feature f : {Feature::kVisibleTriangles, Feature::kRasterPixels}) {
            const std::size_t k = std::size_t(f);
            EXPECT_NEAR(sumA[k], sumB[k], 0.35 * sumB[k]) << timemodel::featureName(f);
        }
    }
    EXPECT_GT(compared, 20);
}

// An object the eye is close to (within 1.5 of its radii) is measured through stand-ins of
// about 256 triangles per level. The pixels a level covers must come out level by level, or the
// scheduler sees savings that are not there: on the harbor's approach, with an even sample of
// the sea's triangles, what a step between its levels saves came out 113% off on average. Two
// surfaces seen from just above them: a wavy sea (one welded grid per level, which simplifies)
// and a paved ground (a soup of separate quads, which simplification would cluster away).
TEST(SceneIndex, NearALargeSurfaceEachLevelCoversWhatItCovers) {
    const auto sea = [] {
        scenes::Object object;
        object.name = "sea";
        for (int cells : {96, 48, 24, 1}) {
            scenes::MeshBuilder builder;
            const float amplitude = cells > 1 ? 0.6f : 0.0f;
            builder.addHeightGrid({0, 0, 0}, {400, 400}, cells, cells, [&](float x, float z) {
                return amplitude * std::sin(0.11f * x) * std::cos(0.07f * z);
            });
            scenes::Level level;
            level.meshes.push_back(builder.finish());
            object.levels.push_back(std::move(level));
        }
        return object;
    };
    const auto paving = [] {
        scenes::Object object;
        object.name = "paving";
        for (bool curbs : {true, false}) {
            scenes::MeshBuilder builder;
            for (float x : {-200.0f, 0.0f}) {
                for (float z : {-200.0f, 0.0f})
                    builder.addQuad({x, 0, z + 200}, {x + 200, 0, z + 200}, {x + 200, 0, z}, {x, 0, z});
            }
            // Curbs: 900 small raised quads, separate from each other and from the paving.
            for (int i = 0; curbs && i < 900; ++i) {
                const float x = -150.0f + float(i % 30) * 10.0f, z = -150.0f + float(i / 30) * 10.0f;
                builder.addQuad({x, 0.15f, z + 0.3f}, {x + 2, 0.15f, z + 0.3f}, {x + 2, 0.15f, z}, {x, 0.15f, z});
            }
            scenes::Level level;
            level.meshes.push_back(builder.finish());
            object.levels.push_back(std::move(level));
        }
        return object;
    };
    for (const scenes::Object& surface : {sea(), paving()}) {
        scenes::Scene scene;
        scene.name = surface.name;
        scene.objects.push_back(surface);
        scenes::updateStatistics(scene);
        const SceneIndex bounds(scene, 256, 256, FeatureMode::Bounds);
        const SceneIndex exact(scene, 256, 256, FeatureMode::Exact);
        FrameObjects a, b;
        for (const scenes::Camera& camera :
             {testing::lookAt({10, 3, 20}, {0, 0, -60}), testing::lookAt({-40, 25, 60}, {20, 0, -40})}) {
            bounds.beginFrame(camera, a);
            exact.beginFrame(camera, b);
            ASSERT_TRUE(bounds.observe(0, a));
            ASSERT_TRUE(exact.observe(0, b));
            for (int l = 0; l < bounds.levelCount(0); ++l) {
                const timemodel::FrameFeatures& fa = a.contributions[bounds.firstLevel(0) + l];
                const timemodel::FrameFeatures& fb = b.contributions[exact.firstLevel(0) + l];
                for (Feature f : {Feature::kRasterPixels, Feature::kShadedPixels}) {
                    ASSERT_GT(fb[f], 0.25 * 256 * 256) << surface.name;  // the surface fills much of the view
                    EXPECT_NEAR(fa[f], fb[f], 0.1 * fb[f])
                        << surface.name << " level " << l << " " << timemodel::featureName(f);
                }
            }
        }
    }
}

// An object's fragments hidden by an object drawn before it are not shaded (early depth test).
// Where that other object passes through its box (the sea through a ship's hull, a terrain
// through a trunk's base), it hides them from every view above it, so the canonical
// measurements include it: measured alone, the hull under the water counted as shaded, and the
// harbor's ship came out up to 1.8 times its exact shaded pixels near the end of the approach.
TEST(SceneIndex, WhatPassesThroughAnObjectHidesItsShadedFragments) {
    scenes::Scene scene;
    scene.name = "moored";
    scenes::Object sea;
    sea.name = "sea";
    scenes::MeshBuilder water;
    water.addHeightGrid({0, 0, 0}, {400, 400}, 40, 40, [](float, float) { return 0.0f; });
    sea.levels.emplace_back().meshes.push_back(water.finish());
    scenes::Object hull;
    hull.name = "hull";
    for (glm::vec3 half : {glm::vec3(12, 4, 4), glm::vec3(11.5f, 3.8f, 3.8f)}) {
        scenes::MeshBuilder builder;
        builder.addBox({0, 0, 0}, half);  // half of it under the water
        hull.levels.emplace_back().meshes.push_back(builder.finish());
    }
    scene.objects = {sea, hull};
    scenes::updateStatistics(scene);
    const SceneIndex bounds(scene, 256, 256, FeatureMode::Bounds);
    const SceneIndex exact(scene, 256, 256, FeatureMode::Exact);
    FrameObjects a, b;
    // From afar (the canonical measurements) and from within 1.5 radii (the stand-ins).
    for (const bool near : {false, true}) {
        const scenes::Camera camera =
            near ? testing::lookAt({-14, 5, 11}, {0, 0, 0}) : testing::lookAt({-50, 12, 40}, {0, 0, 0});
        bounds.beginFrame(camera, a);
        exact.beginFrame(camera, b);
        for (int o = 0; o < 2; ++o) {
            ASSERT_TRUE(bounds.observe(o, a));
            ASSERT_TRUE(exact.observe(o, b));
        }
        for (int l = 0; l < bounds.levelCount(1); ++l) {
            const timemodel::FrameFeatures& fa = a.contributions[bounds.firstLevel(1) + l];
            const timemodel::FrameFeatures& fb = b.contributions[exact.firstLevel(1) + l];
            // The water hides over half of what the hull rasterizes (measured alone: 4% near,
            // 20% from afar). The share of shaded fragments comes within 20% (the shares are
            // measured from directions about 28° apart and at set distances), and near the eye,
            // where the stand-ins give the raster pixels exactly, so do the shaded pixels.
            const double exactShare = fb[Feature::kShadedPixels] / fb[Feature::kRasterPixels];
            ASSERT_LT(exactShare, 0.5);
            EXPECT_NEAR(fa[Feature::kShadedPixels] / fa[Feature::kRasterPixels], exactShare, 0.2 * exactShare)
                << "level " << l << (near ? " near" : " afar");
            if (near) {
                EXPECT_NEAR(fa[Feature::kShadedPixels], fb[Feature::kShadedPixels], 0.2 * fb[Feature::kShadedPixels])
                    << "level " << l;
            }
        }
    }
}

TEST(SceneIndex, MeasuringOnThreadsChangesNothing) {
    // Each object's canonical measurements go to its own slots, whichever thread takes it.
    const scenes::Scene scene = testing::makeGridScene(4, 3, 5.0f);
    const SceneIndex one(scene, 128, 96, FeatureMode::Bounds, 1);
    const SceneIndex three(scene, 128, 96, FeatureMode::Bounds, 3);
    FrameObjects a, b;
    int compared = 0;
    for (const scenes::Camera& camera : {testing::lookAt({3, 6, 18}, {0, 0, 0}), testing::lookAt({1, 2, 9}, {3, 1, 0}),
                                         testing::lookAt({0.5f, 1, 0.5f}, {4, 1, 0})}) {  // inside the grid: proxies
        one.beginFrame(camera, a);
        three.beginFrame(camera, b);
        for (int o = 0; o < one.objectCount(); ++o) {
            ASSERT_EQ(one.observe(o, a), three.observe(o, b));
            if (!a.visible[std::size_t(o)]) continue;
            for (int l = 0; l < one.levelCount(o); ++l) {
                const timemodel::FrameFeatures& fa = a.contributions[one.firstLevel(o) + l];
                const timemodel::FrameFeatures& fb = b.contributions[three.firstLevel(o) + l];
                for (std::size_t k = 0; k < timemodel::kFeatureCount; ++k) {
                    EXPECT_EQ(fa.values[k], fb.values[k]) << "object " << o << " level " << l << " feature " << k;
                }
                ++compared;
            }
        }
    }
    EXPECT_GT(compared, 20);
}

TEST(Quadtree, EveryObjectInOneLeafWithinCapacity) {
    const scenes::Scene scene = testing::makeGridScene(12, 9, 3.0f);
    const SceneIndex index(scene, 64, 64, FeatureMode::Exact);
    std::vector<ObjectShape> shapes;
    for (int o = 0; o < index.objectCount(); ++o) shapes.push_back(index.shape(o));
    const Quadtree tree(shapes, {8, 10});
    EXPECT_GT(tree.leafCount(), 108 / 8);
    std::vector<int> seen(shapes.size(), 0);
    for (const Quadtree::Tile& tile : tree.tiles()) {
        if (!tile.leaf) continue;
        EXPECT_LE(tile.objectCount, 8);
        for (int k = tile.firstObject; k < tile.firstObject + tile.objectCount; ++k) {
            const int o = tree.objects()[k];
            ++seen[o];
            for (int axis = 0; axis < 3; ++axis) {  // the tile box holds its objects' spheres
                EXPECT_LE(tile.low[axis], shapes[o].center[axis] - shapes[o].radius + 1e-4f);
                EXPECT_GE(tile.high[axis], shapes[o].center[axis] + shapes[o].radius - 1e-4f);
            }
        }
    }
    for (int count : seen) EXPECT_EQ(count, 1);
    // Visible leaves come nearest first, and a short view of one corner culls most of them.
    scenes::Camera camera = testing::lookAt({-24, 3, -18}, {-16, 0, -12}, 40.0f);
    camera.farPlane = 20.0f;
    const glm::mat4 vp = scenes::projectionMatrix(camera, 1.0f) * scenes::viewMatrix(camera);
    std::vector<int> leaves;
    std::vector<double> scratch;
    tree.visibleLeaves(Frustum::fromViewProjection(vp), camera.position, leaves, scratch);
    EXPECT_GT(leaves.size(), 0u);
    EXPECT_LT(int(leaves.size()), tree.leafCount() / 2);
    for (std::size_t i = 1; i < leaves.size(); ++i) EXPECT_LE(scratch[leaves[i - 1]], scratch[leaves[i]]);
    EXPECT_THROW(Quadtree(shapes, {0, 10}), std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::scheduler
