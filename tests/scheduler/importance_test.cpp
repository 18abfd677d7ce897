// Importance (DONG15 eqs. 11-12): the published Table 4, the extended form, the observation of
// an object from a camera, and the distance thresholds (eq. 4).
#include "scheduler/importance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.hpp"
#include "timemodel/features.hpp"

namespace lodopt::scheduler {
namespace {

constexpr double kPi = 3.14159265358979323846;

ObjectView treeView(double distance, double degrees, double area) {
    ObjectView view;
    view.distance = distance;
    view.viewAngleRadians = degrees * kPi / 180.0;
    view.projectedArea = area;
    return view;
}

// DONG15 Table 4: benchmark (d = 15, θ = 0°, s = 6), α1 = 0.6, α2 = 0.4.
struct Table4Row {
    double distance, degrees, area, published;
};
const Table4Row kTable4[] = {
    {15, 0, 6, 1.00}, {15, 30, 6, 0.75}, {15, 45, 9, 0.69}, {9, 25, 11, 1.35}, {9, 25, 5, 0.98},
};

TEST(Importance, ReproducesDong15Table4) {
    const ObjectView benchmark = treeView(15, 0, 6);
    const ImportanceCoefficients published;  // 0.6, 0.4
    for (const Table4Row& row : kTable4) {
        const double value = importance(treeView(row.distance, row.degrees, row.area), benchmark, published);
        // Within the table's two decimals...
        EXPECT_NEAR(value, row.published, 0.01) << row.distance << ", " << row.degrees << "°, " << row.area;
        // ...and exactly the printed digits once truncated: (15, 45°, 9) is 0.698 and (9, 25°,
        // 11) is 1.356, which rounding would print 0.70 and 1.36. Truncation matches all five.
        EXPECT_DOUBLE_EQ(std::floor(value * 100.0 + 1e-9) / 100.0, row.published) << value;
    }
    EXPECT_NEAR(importance(treeView(15, 45, 9), benchmark, published), 0.6981, 1e-4);
    EXPECT_NEAR(importance(treeView(9, 25, 11), benchmark, published), 1.3560, 1e-4);
}

TEST(Importance, DenominatorIsTheFormula) {
    const ObjectView view = treeView(12, 20, 4);
    const ImportanceCoefficients c{0.3, 0.7, 0.0, 0.0};
    EXPECT_DOUBLE_EQ(importanceDenominator(view, c), 0.3 * (1.0 + std::tan(20 * kPi / 180)) * 12 + 0.7 * 100.0 / 4);
    EXPECT_DOUBLE_EQ(importance(view, importanceDenominator(view, c), c), 1.0);       // its own benchmark
    EXPECT_DOUBLE_EQ(importance(view, importanceDenominator(view, c), c, 2.5), 2.5);  // weight w
}

TEST(Importance, ExtendedTermsAddToTheDenominator) {
    ObjectView view = treeView(10, 0, 5);
    view.projectedPixels = 2500;
    view.centerOffset = 0.5;
    const ImportanceCoefficients published;
    const ImportanceCoefficients extended{0.6, 0.4, 0.2, 3.0};
    EXPECT_DOUBLE_EQ(importanceDenominator(view, extended),
                     importanceDenominator(view, published) + 0.2 * 1e4 / 2500 + 3.0 * 0.5);
    // Fewer pixels and further from the centre: less important under the extended form only.
    ObjectView small = view;
    small.projectedPixels = 100;
    small.centerOffset = 0.9;
    EXPECT_DOUBLE_EQ(importance(small, view, published), 1.0);
    EXPECT_LT(importance(small, view, extended), 1.0);
    // Pixels are floored at one so a sub-pixel object stays finite.
    small.projectedPixels = 0.0;
    EXPECT_TRUE(std::isfinite(importanceDenominator(small, extended)));
}

TEST(Importance, CloserAndLargerIsMoreImportant) {
    const ImportanceCoefficients c;
    const ObjectView base = treeView(20, 10, 8);
    EXPECT_GT(importance(treeView(10, 10, 8), base, c), 1.0);
    EXPECT_GT(importance(treeView(20, 10, 16), base, c), 1.0);
    EXPECT_LT(importance(treeView(20, 40, 8), base, c), 1.0);
}

TEST(Importance, RejectsBadCoefficients) {
    EXPECT_THROW(validateCoefficients({-0.1, 0.4, 0, 0}), std::invalid_argument);
    EXPECT_THROW(validateCoefficients({0.6, std::nan(""), 0, 0}), std::invalid_argument);
    EXPECT_THROW(validateCoefficients({0, 0, 0, 0}), std::invalid_argument);
    EXPECT_NO_THROW(validateCoefficients({0, 0, 1, 0}));
}

TEST(Importance, SilhouetteOfABox) {
    scenes::Bounds box;
    box.min = glm::vec3(-1.0f, -2.0f, -0.5f);
    box.max = glm::vec3(1.0f, 2.0f, 0.5f);  // 2 x 4 x 1
    const glm::mat4 identity(1.0f);
    EXPECT_NEAR(silhouetteArea(box, identity, {0, 0, 1}), 8.0, 1e-5);   // x-y face
    EXPECT_NEAR(silhouetteArea(box, identity, {1, 0, 0}), 4.0, 1e-5);   // y-z face
    EXPECT_NEAR(silhouetteArea(box, identity, {0, -1, 0}), 2.0, 1e-5);  // x-z face
    const glm::vec3 diagonal = glm::normalize(glm::vec3(1, 1, 1));
    EXPECT_NEAR(silhouetteArea(box, identity, diagonal), (8.0 + 4.0 + 2.0) / std::sqrt(3.0), 1e-5);
    // A uniform scale of 2 quadruples it.
    EXPECT_NEAR(silhouetteArea(box, glm::scale(identity, glm::vec3(2.0f)), {0, 0, 1}), 32.0, 1e-4);
}

TEST(Importance, ObserveMeasuresDistanceAngleAreaAndPixels) {
    scenes::Scene scene = testing::makeGridScene(1, 1, 1.0f);
    const ObjectShape shape = objectShape(scene.objects[0]);
    // Camera 10 units in front of the blob's centre, looking at it.
    const scenes::Camera camera = testing::lookAt(shape.center + glm::vec3(0, 0, 10), shape.center);
    const int w = 200, h = 100;
    const glm::mat4 vp = scenes::projectionMatrix(camera, 2.0f) * scenes::viewMatrix(camera);
    const ObjectView view = observe(shape, camera, vp, w, h);
    EXPECT_NEAR(view.distance, 10.0, 1e-4);
    EXPECT_NEAR(view.viewAngleRadians, 0.0, 1e-3);
    const scenes::Bounds box = scene.objects[0].levels[0].stats.bounds;
    EXPECT_NEAR(view.projectedArea, double((box.max.x - box.min.x) * (box.max.y - box.min.y)), 1e-3);
    EXPECT_DOUBLE_EQ(view.projectedPixels, timemodel::projectedPixels(box, vp * scene.objects[0].transform, w, h));
    EXPECT_NEAR(view.centerOffset, 0.0, 1e-4);
    // Looking 30° away: θ follows, the object moves off centre.
    const glm::vec3 aside = camera.position + glm::vec3(std::tan(float(kPi / 6)) * -10.0f, 0, -10.0f);
    const scenes::Camera turned = testing::lookAt(camera.position, aside);
    const glm::mat4 vp2 = scenes::projectionMatrix(turned, 2.0f) * scenes::viewMatrix(turned);
    const ObjectView off = observe(shape, turned, vp2, w, h);
    EXPECT_NEAR(off.viewAngleRadians, kPi / 6, 1e-3);
    EXPECT_GT(off.centerOffset, 0.3);
}

TEST(DistanceThresholds, LevelByBand) {
    const std::vector<double> t = {5, 10, 20};
    EXPECT_EQ(distanceLevel(0.0, t, 4), 0);
    EXPECT_EQ(distanceLevel(4.99, t, 4), 0);
    EXPECT_EQ(distanceLevel(5.0, t, 4), 1);  // d_k <= d < d_{k+1}
    EXPECT_EQ(distanceLevel(19.9, t, 4), 2);
    EXPECT_EQ(distanceLevel(25.0, t, 4), 3);
    EXPECT_EQ(distanceLevel(25.0, t, 2), 1);  // clamped to the coarsest level
    EXPECT_EQ(distanceLevel(25.0, {}, 3), 0);
    const DistanceThresholds g = DistanceThresholds::geometric(3.0, 2.0, 4);
    ASSERT_EQ(g.values.size(), 4u);
    EXPECT_DOUBLE_EQ(g.values[3], 24.0);
    EXPECT_NO_THROW(validateThresholds(g));
    DistanceThresholds bad;
    bad.values = {4, 4};
    EXPECT_THROW(validateThresholds(bad), std::invalid_argument);
    bad.values = {-1};
    EXPECT_THROW(validateThresholds(bad), std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::scheduler
