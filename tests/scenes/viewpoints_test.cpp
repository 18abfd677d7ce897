#include "scenes/viewpoints.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/mesh_builder.hpp"

namespace lodopt::scenes {
namespace {

TEST(CameraGrid, ParsesCountsHeightAndPitch) {
    const CameraGrid grid = parseCameraGrid("10x4x8@2.5/-30");
    EXPECT_EQ(grid.columns, 10);
    EXPECT_EQ(grid.rows, 4);
    EXPECT_EQ(grid.directions, 8);
    EXPECT_FLOAT_EQ(grid.height, 2.5f);
    EXPECT_FLOAT_EQ(grid.pitchDegrees, -30.0f);
    EXPECT_FLOAT_EQ(parseCameraGrid("1x1x1@60").pitchDegrees, -10.0f);  // the default pitch
}

TEST(CameraGrid, RefusesMalformedSpecsNamingThePart) {
    for (const char* bad : {"10x10@2", "10x10x8", "0x1x1@2", "1x1x1@", "1x1x1@2/90", "ax1x1@2", "1x1x1x1@2",
                            "1x1x1@2/-x"}) {
        EXPECT_THROW(parseCameraGrid(bad), std::invalid_argument) << bad;
    }
    try {
        parseCameraGrid("3xbx1@2");
        FAIL();
    } catch (const std::invalid_argument& error) {
        EXPECT_NE(std::string(error.what()).find("rows"), std::string::npos) << error.what();
    }
}

// Two unit cubes at x = 0 and x = 10 (z in [-0.5, 0.5], y in [0, 1]): the footprint is
// x in [-0.5, 10.5], z in [-0.5, 0.5], ground y = 0.
Scene twoCubes() {
    Scene scene;
    scene.name = "two cubes";
    for (float x : {0.0f, 10.0f}) {
        Object object;
        object.name = "cube";
        MeshBuilder builder;
        builder.addBox(glm::vec3(0.0f), glm::vec3(0.5f));
        Level level;
        level.meshes.push_back(builder.finish());
        object.levels.push_back(level);
        object.transform = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.5f, 0.0f));
        scene.objects.push_back(object);
    }
    updateStatistics(scene);
    return scene;
}

TEST(CameraGrid, PlacesCellCentresOverTheFootprintAndTurnsAroundTheVertical) {
    const Scene scene = twoCubes();
    CameraGrid grid = parseCameraGrid("2x1x4@3/0");
    const std::vector<Camera> cameras = gridCameras(scene, grid);
    ASSERT_EQ(cameras.size(), 8u);
    // Columns at the centres of [-0.5, 5] and [5, 10.5]; one row at z = 0; height 3 over y = 0.
    EXPECT_NEAR(cameras[0].position.x, 2.25f, 1e-5f);
    EXPECT_NEAR(cameras[4].position.x, 7.75f, 1e-5f);
    EXPECT_NEAR(cameras[0].position.z, 0.0f, 1e-5f);
    EXPECT_NEAR(cameras[0].position.y, 3.0f, 1e-5f);
    EXPECT_EQ(cameras[5].name, "grid_0_1_1");
    // Direction 0 looks along +x, direction 1 along +z, level with pitch 0.
    const glm::vec3 look0 = cameras[0].target - cameras[0].position;
    const glm::vec3 look1 = cameras[1].target - cameras[1].position;
    EXPECT_NEAR(look0.x, 1.0f, 1e-5f);
    EXPECT_NEAR(look1.z, 1.0f, 1e-5f);
    EXPECT_NEAR(look1.y, 0.0f, 1e-5f);

    grid.box = GroundBox{0.0f, 0.0f, 4.0f, 8.0f};
    grid.pitchDegrees = -30.0f;
    const std::vector<Camera> boxed = gridCameras(scene, grid);
    EXPECT_NEAR(boxed[0].position.x, 1.0f, 1e-5f);
    EXPECT_NEAR(boxed[0].position.z, 4.0f, 1e-5f);
    EXPECT_NEAR((boxed[0].target - boxed[0].position).y, -0.5f, 1e-5f);  // sin(-30 degrees)
}

TEST(CameraGrid, RefusesAnEmptySceneWithoutABox) {
    Scene empty;
    empty.name = "empty";
    EXPECT_THROW(gridCameras(empty, parseCameraGrid("1x1x1@2")), SceneError);
    CameraGrid grid = parseCameraGrid("1x1x1@2");
    grid.box = GroundBox{0.0f, 0.0f, 1.0f, 1.0f};
    EXPECT_EQ(gridCameras(empty, grid).size(), 1u);
}

TEST(ScreenSize, IsTheSphereDiameterOverTheViewHeight) {
    // A sphere of radius 1 at distance 10 under a 90-degree vertical field of view: the view is
    // 2 * 10 * tan(45) = 20 units high there, the sphere 2 units: screen size 0.1.
    Bounds bounds;
    bounds.min = glm::vec3(-1.0f);
    bounds.max = glm::vec3(1.0f);
    bounds.sphereCenter = glm::vec3(0.0f);
    bounds.sphereRadius = 1.0f;
    Camera camera;
    camera.position = glm::vec3(0.0f, 0.0f, 10.0f);
    camera.fovYDegrees = 90.0f;
    EXPECT_NEAR(screenSize(bounds, camera), 0.1, 1e-6);
    camera.fovYDegrees = 45.0f;  // tan(22.5) = 0.41421: 2 / (20 * 0.41421)
    EXPECT_NEAR(screenSize(bounds, camera), 0.241421, 1e-5);
    EXPECT_EQ(screenSize(Bounds{glm::vec3(0.0f), glm::vec3(-1.0f), glm::vec3(0.0f), 0.0f}, camera), 0.0);
}

}  // namespace
}  // namespace lodopt::scenes
