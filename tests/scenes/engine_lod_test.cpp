#include "scenes/engine_lod.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scenes/viewpoints.hpp"

namespace lodopt::scenes {
namespace {

// A 2 x 1 x 1 box at the origin: largest extent 2, sphere radius half the diagonal, sqrt(6) / 2.
Bounds box() {
    Bounds bounds;
    bounds.min = glm::vec3(-1.0f, -0.5f, -0.5f);
    bounds.max = glm::vec3(1.0f, 0.5f, 0.5f);
    bounds.sphereCenter = glm::vec3(0.0f);
    bounds.sphereRadius = 0.5f * glm::length(bounds.max - bounds.min);
    return bounds;
}

TEST(EngineLod, HandWorkedConversionsOfOneThreshold) {
    const Bounds bounds = box();
    const double r = std::sqrt(6.0) / 2.0;
    // Screen size 0.5 under a 90-degree vertical field of view (tan 45 = 1).
    EXPECT_DOUBLE_EQ(unrealScreenSize(0.5), 0.5);
    EXPECT_NEAR(unityRelativeHeight(0.5, bounds), 0.5 * 2.0 / (2.0 * r), 1e-7);  // 0.40825
    EXPECT_NEAR(unityRelativeHeight(0.5, bounds), 0.408248, 1e-6);
    EXPECT_NEAR(switchDistance(0.5, bounds, 90.0), r / 0.5, 1e-6);  // 2.44949
    EXPECT_NEAR(babylonScreenCoverage(0.5, 1.0), 0.19635, 1e-5);    // pi 0.25 / 4
    EXPECT_NEAR(babylonScreenCoverage(0.5, 2.0), 0.098175, 1e-6);   // a view twice as wide
    EXPECT_NEAR(screenSizeFromUnityRelativeHeight(unityRelativeHeight(0.37, bounds), bounds), 0.37, 1e-7);
}

TEST(EngineLod, TheSwitchDistanceGivesTheThresholdsScreenSize) {
    const Bounds bounds = box();
    for (double fov : {30.0, 45.0, 60.0}) {
        for (double size : {0.8, 0.1, 0.004}) {
            Camera camera;
            camera.fovYDegrees = float(fov);
            camera.position = glm::vec3(0.0f, 0.0f, float(switchDistance(size, bounds, fov)));
            EXPECT_NEAR(screenSize(bounds, camera) / size, 1.0, 1e-6) << fov << " " << size;
        }
    }
}

}  // namespace
}  // namespace lodopt::scenes
