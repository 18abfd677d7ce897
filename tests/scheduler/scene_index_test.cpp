// The scheduler's per-frame knowledge without rendering: frustum culling, the projected box,
// the Bounds-mode features against the exact FeatureTable, and the quadtree of tiles.
#include "scheduler/scene_index.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures.hpp"
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
