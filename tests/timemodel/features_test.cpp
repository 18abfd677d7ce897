// Frame features: projected box areas worked out by hand, and the table's O(1) deltas.
#include "timemodel/features.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "scenes/mesh_builder.hpp"

using namespace lodopt;
using timemodel::Feature;

namespace {

// Camera at the origin looking down -Z with a 90° vertical field of view, square viewport:
// a point (x, y, -d) lands at NDC (x/d, y/d).
scenes::Camera straightCamera() {
    scenes::Camera camera;
    camera.position = glm::vec3(0.0f);
    camera.target = glm::vec3(0.0f, 0.0f, -1.0f);
    camera.fovYDegrees = 90.0f;
    camera.nearPlane = 0.1f;
    camera.farPlane = 100.0f;
    return camera;
}

glm::mat4 viewProjection(const scenes::Camera& camera) {
    return scenes::projectionMatrix(camera, 1.0f) * scenes::viewMatrix(camera);
}

scenes::Bounds box(glm::vec3 min, glm::vec3 max) {
    scenes::Bounds b;
    b.min = min;
    b.max = max;
    return b;
}

//  A 3-object scene, each object a stack of cubes: object o level l has (3 - l) cubes
//  (12 triangles, 24 vertices each), object 1 carries a 4x4 texture.
//     o0 at z=-5      o1 at z=-10 (textured)      o2 behind the camera (z=+5)
scenes::Scene threeObjectScene() {
    scenes::Scene scene;
    scene.name = "three";
    scenes::Texture texture;
    texture.name = "t";
    texture.width = texture.height = 4;
    texture.rgba.assign(4 * 4 * 4, 200);
    scene.textures.push_back(texture);
    scene.materials.push_back(scenes::diffuseMaterial("plain", glm::vec3(1.0f)));
    scene.materials.push_back(scenes::diffuseMaterial("textured", glm::vec3(1.0f), 0));
    const float depths[3] = {-5.0f, -10.0f, 5.0f};
    for (int o = 0; o < 3; ++o) {
        scenes::Object object;
        object.name = "o" + std::to_string(o);
        object.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, depths[o]));
        for (int l = 0; l < 3; ++l) {
            scenes::MeshBuilder builder(o == 1 ? 1 : 0);
            for (int c = 0; c < 3 - l; ++c) builder.addBox(glm::vec3(0.0f, float(c) * 0.5f, 0.0f), glm::vec3(0.5f));
            scenes::Level level;
            level.meshes.push_back(builder.finish());
            object.levels.push_back(std::move(level));
        }
        scene.objects.push_back(std::move(object));
    }
    scene.views.push_back(straightCamera());
    scenes::updateStatistics(scene);
    scenes::validateScene(scene);
    return scene;
}

}  // namespace

TEST(ProjectedPixels, FlatSquareCoversAQuarterOfTheViewport) {
    // x, y in [-1, 1] at distance 2 → NDC [-0.5, 0.5]² → half the width, half the height.
    const double pixels =
        timemodel::projectedPixels(box({-1, -1, -2}, {1, 1, -2}), viewProjection(straightCamera()), 200, 200);
    EXPECT_NEAR(pixels, 100.0 * 100.0, 1.0);
}

TEST(ProjectedPixels, BoxPartlyOutsideIsClippedToTheViewport) {
    // x in [0, 4] at distance 2 → NDC [0, 2] → clipped to [0, 1]: half the width (100 of 200);
    // y in [-1, 1] → NDC [-0.5, 0.5]: half the height (50 of 100).
    const double pixels =
        timemodel::projectedPixels(box({0, -1, -2}, {4, 1, -2}), viewProjection(straightCamera()), 200, 100);
    EXPECT_NEAR(pixels, 100.0 * 50.0, 1.0);
}

TEST(ProjectedPixels, BoxBehindTheCameraOrOffScreenIsZero) {
    const glm::mat4 vp = viewProjection(straightCamera());
    EXPECT_EQ(timemodel::projectedPixels(box({-1, -1, 2}, {1, 1, 3}), vp, 100, 100), 0.0);
    EXPECT_EQ(timemodel::projectedPixels(box({10, -1, -3}, {12, 1, -2}), vp, 100, 100), 0.0);
    EXPECT_EQ(timemodel::projectedPixels(box({-1, -1, -200}, {1, 1, -150}), vp, 100, 100), 0.0);  // beyond far
    scenes::Bounds empty;
    empty.min = glm::vec3(0.0f);
    empty.max = glm::vec3(-1.0f);
    EXPECT_EQ(timemodel::projectedPixels(empty, vp, 100, 100), 0.0);
}

TEST(ProjectedPixels, CameraInsideTheBoxCoversEverything) {
    const double pixels =
        timemodel::projectedPixels(box({-5, -5, -5}, {5, 5, 5}), viewProjection(straightCamera()), 64, 32);
    EXPECT_NEAR(pixels, 64.0 * 32.0, 1e-6);
}

TEST(ProjectedPixels, BoxCrossingTheNearPlaneUsesItsVisiblePart) {
    // From z = +1 (behind) to z = -4: clipped at the near plane z = -0.1, where x = ±0.2 maps
    // to ±2 → clipped to the whole width; y in [0, 0.01] maps to [0, 0.1] at the near plane.
    const double pixels = timemodel::projectedPixels(box({-0.2f, 0.0f, -4.0f}, {0.2f, 0.01f, 1.0f}),
                                                     viewProjection(straightCamera()), 100, 100);
    EXPECT_NEAR(pixels, 100.0 * 5.0, 0.5);
}

TEST(FeatureTable, SumsTheDrawnLevelsStatistics) {
    const scenes::Scene scene = threeObjectScene();
    const timemodel::FeatureTable table(scene, scene.views[0], 128, 128);
    ASSERT_EQ(table.objectCount(), 3);
    EXPECT_EQ(table.levelCount(1), 3);
    const timemodel::FrameFeatures f = table.features({0, 2, scenes::kNotDrawn});
    EXPECT_EQ(f[Feature::kTriangles], 3 * 12 + 1 * 12);
    EXPECT_EQ(f[Feature::kVertices], 3 * 24 + 1 * 24);
    EXPECT_EQ(f[Feature::kTextureBytes], 4 * 4 * 4);
    EXPECT_EQ(f[Feature::kDrawCalls], 2);
    EXPECT_EQ(f[Feature::kDrawnObjects], 2);
    EXPECT_EQ(f[Feature::kMatrices], 2);
    EXPECT_EQ(f[Feature::kBoundingBoxes], 3);  // every object is tested, drawn or not
    EXPECT_GT(f[Feature::kPixels], 0.0);
    // Object 2 is behind the camera: drawing it adds work but no pixels.
    const timemodel::FrameFeatures behind = table.contribution(2, 0);
    EXPECT_EQ(behind[Feature::kPixels], 0.0);
    EXPECT_EQ(behind[Feature::kTriangles], 36);
}

TEST(FeatureTable, DeltaMatchesRecomputationAndDirectComputation) {
    const scenes::Scene scene = threeObjectScene();
    const timemodel::FeatureTable table(scene, scene.views[0], 96, 64);
    scenes::Combination combination = {1, scenes::kNotDrawn, 2};
    timemodel::FrameFeatures running = table.features(combination);
    const int changes[][2] = {{1, 0}, {0, scenes::kNotDrawn}, {2, 1}, {1, 2}, {0, 0}};
    for (const auto& change : changes) {
        running += table.delta(change[0], combination[change[0]], change[1]);
        combination[change[0]] = change[1];
        const timemodel::FrameFeatures fresh = table.features(combination);
        const timemodel::FrameFeatures direct =
            timemodel::computeFrameFeatures(scene, combination, scene.views[0], 96, 64);
        for (std::size_t k = 0; k < timemodel::kFeatureCount; ++k) {
            EXPECT_NEAR(running.values[k], fresh.values[k], 1e-9) << timemodel::featureName(Feature(k));
            EXPECT_NEAR(direct.values[k], fresh.values[k], 1e-9) << timemodel::featureName(Feature(k));
        }
    }
    const timemodel::FrameFeatures none = table.features({scenes::kNotDrawn, scenes::kNotDrawn, scenes::kNotDrawn});
    EXPECT_EQ(none[Feature::kTriangles], 0.0);
    EXPECT_EQ(none[Feature::kBoundingBoxes], 3.0);
}

TEST(FeatureTable, FinerLevelsOfTheSameObjectNeverHaveFewerPixels) {
    // Level 0 stacks more cubes upwards, so its box contains the coarser levels' boxes.
    const scenes::Scene scene = threeObjectScene();
    const timemodel::FeatureTable table(scene, scene.views[0], 128, 128);
    EXPECT_GT(table.contribution(0, 0)[Feature::kPixels], table.contribution(0, 2)[Feature::kPixels]);
}

TEST(RasterFeatures, OneTriangleByHand) {
    // (0,0,-2), (1,0,-2), (0,1,-2) → NDC (0,0), (0.5,0), (0,0.5) → pixels (0,0), (50,0), (0,50)
    // on a 200 x 200 viewport: area 1250, perimeter 100 + 50·√2.
    scenes::Mesh mesh;
    mesh.positions = {{0, 0, -2}, {1, 0, -2}, {0, 1, -2}};
    mesh.normals.assign(3, glm::vec3(0, 0, 1));
    mesh.indices = {0, 1, 2};
    const timemodel::RasterFeatures f = timemodel::rasterFeatures({mesh}, viewProjection(straightCamera()), 200, 200);
    EXPECT_EQ(f.visibleTriangles, 1.0);
    EXPECT_NEAR(f.rasterPixels, 1250.0, 0.5);
    EXPECT_NEAR(f.edgePixels, 100.0 + 50.0 * std::sqrt(2.0), 0.5);
}

namespace {

// One triangle given in pixels of a 64 x 64 viewport, through an identity projection (NDC =
// position): pixel p lies at p / 32 - 1.
timemodel::RasterFeatures pixelTriangle(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    scenes::Mesh mesh;
    for (glm::vec2 p : {a, b, c}) mesh.positions.push_back({p.x / 32.0f - 1.0f, p.y / 32.0f - 1.0f, 0.0f});
    mesh.normals.assign(3, glm::vec3(0, 0, 1));
    mesh.indices = {0, 1, 2};
    return timemodel::rasterFeatures({mesh}, glm::mat4(1.0f), 64, 64);
}

}  // namespace

TEST(RasterFeatures, PartialBlocksByHand) {
    // Legs on block lines, hypotenuse through block corners: only the 4 diagonal blocks are
    // partly covered (the 6 below them are whole).
    EXPECT_DOUBLE_EQ(pixelTriangle({8, 8}, {24, 8}, {8, 24}).partialBlocks, 4.0);
    // A sliver one pixel high across 48 pixels: 13 blocks of one row, each partly covered,
    // though its edges are 97 pixels long (both long edges cross the same blocks).
    const timemodel::RasterFeatures sliver = pixelTriangle({8.5f, 9}, {56.5f, 9}, {56.5f, 10});
    EXPECT_DOUBLE_EQ(sliver.partialBlocks, 13.0);
    EXPECT_NEAR(sliver.edgePixels, 48.0 + 1.0 + std::sqrt(48.0 * 48.0 + 1.0), 1e-3);
    // Clipped to the viewport, a triangle larger than it covers every block whole.
    EXPECT_DOUBLE_EQ(pixelTriangle({-100, -100}, {300, -100}, {-100, 300}).partialBlocks, 0.0);
    // Moved by one pixel off the block lines, its legs cut blocks too: per block row from the
    // bottom 5, 3, 3, 2 and 1 (one block of the second row is whole).
    EXPECT_DOUBLE_EQ(pixelTriangle({9, 9}, {25, 9}, {9, 25}).partialBlocks, 14.0);
}

namespace {

// Twice the signed area of polygon `p`.
double twiceArea(const std::vector<glm::dvec2>& p) {
    double sum = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i)
        sum += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
    return sum;
}

// The reference: per 4x4 block of the viewport, the triangle clipped to the block's square has
// an area (reached) and not all four corners lie inside the triangle (not whole).
double partialBlocksByClipping(const std::vector<glm::dvec2>& triangle, int width, int height) {
    const double orientation = twiceArea(triangle) > 0.0 ? 1.0 : -1.0;
    auto inside = [&](glm::dvec2 q) {
        for (std::size_t i = 0; i < 3; ++i) {
            const glm::dvec2 a = triangle[i], b = triangle[(i + 1) % 3];
            if (orientation * ((b.x - a.x) * (q.y - a.y) - (b.y - a.y) * (q.x - a.x)) < 0.0) return false;
        }
        return true;
    };
    double partial = 0.0;
    for (int by = 0; by < height; by += 4) {
        for (int bx = 0; bx < width; bx += 4) {
            std::vector<glm::dvec2> polygon = triangle;
            // Keep the side of each square edge: x >= bx, x <= bx + 4, y >= by, y <= by + 4.
            const double limits[4] = {double(bx), double(bx + 4), double(by), double(by + 4)};
            for (int side = 0; side < 4; ++side) {
                const int axis = side / 2;
                const double sign = side % 2 ? -1.0 : 1.0;  // keep sign * (coordinate - limit) >= 0
                std::vector<glm::dvec2> kept;
                for (std::size_t i = 0; i < polygon.size(); ++i) {
                    const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
                    const double da = sign * (a[axis] - limits[side]), db = sign * (b[axis] - limits[side]);
                    if (da >= 0.0) kept.push_back(a);
                    if ((da >= 0.0) != (db >= 0.0)) kept.push_back(a + (b - a) * (da / (da - db)));
                }
                polygon = kept;
            }
            if (polygon.size() < 3 || std::abs(twiceArea(polygon)) < 1e-9) continue;
            const bool whole =
                inside({bx, by}) && inside({bx + 4, by}) && inside({bx, by + 4}) && inside({bx + 4, by + 4});
            if (!whole) partial += 1.0;
        }
    }
    return partial;
}

}  // namespace

TEST(RasterFeatures, PartialBlocksMatchClippingEveryBlock) {
    // Random triangles, many reaching past the viewport, slivers among them, against the
    // block-by-block reference; the pixel coordinates are the ones the feature sees (float
    // positions through the identity projection).
    std::uint64_t state = 7;
    auto uniform = [&state](double low, double high) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return low + (high - low) * double(state >> 11) / double(1ull << 53);
    };
    for (int t = 0; t < 400; ++t) {
        std::vector<glm::vec2> corners;
        for (int k = 0; k < 3; ++k) corners.push_back({float(uniform(-20.0, 84.0)), float(uniform(-20.0, 84.0))});
        if (t % 4 == 0) corners[2] = corners[1] + glm::vec2(float(uniform(-0.5, 0.5)), float(uniform(-0.5, 0.5)));
        std::vector<glm::dvec2> pixels;
        for (glm::vec2 c : corners) {
            const float x = c.x / 32.0f - 1.0f, y = c.y / 32.0f - 1.0f;  // what pixelTriangle stores
            pixels.push_back({double(x) * 32.0 + 32.0, double(y) * 32.0 + 32.0});
        }
        if (std::abs(twiceArea(pixels)) < 1e-6) continue;
        EXPECT_DOUBLE_EQ(pixelTriangle(corners[0], corners[1], corners[2]).partialBlocks,
                         partialBlocksByClipping(pixels, 64, 64))
            << "triangle " << t << ": " << pixels[0].x << "," << pixels[0].y << " " << pixels[1].x << "," << pixels[1].y
            << " " << pixels[2].x << "," << pixels[2].y;
    }
}

TEST(RasterFeatures, TrianglesOutsideTheFrustumAreNotVisible) {
    scenes::Mesh mesh;
    mesh.positions = {{0, 0, 2},    {1, 0, 2},   {0, 1, 2},    // behind the camera
                      {10, 0, -2},  {11, 0, -2}, {10, 1, -2},  // far right of the view
                      {-1, -1, -3}, {1, -1, -3}, {0, 1, -3}};  // in front: counted
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0, 0, 1));
    mesh.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    const timemodel::RasterFeatures f = timemodel::rasterFeatures({mesh}, viewProjection(straightCamera()), 64, 64);
    EXPECT_EQ(f.visibleTriangles, 1.0);
    EXPECT_GT(f.rasterPixels, 0.0);
}

namespace {

// The rectangle [x0, x1] x [-10, 10] in the plane z, facing the straight camera, far larger
// than its view at z = -2 or -4 when it spans x in [-10, 10].
scenes::Mesh quadMesh(float x0, float x1, float z, int material = -1) {
    scenes::MeshBuilder builder(material);
    builder.addQuad({x0, -10, z}, {x1, -10, z}, {x1, 10, z}, {x0, 10, z});
    return builder.finish();
}

scenes::Object oneLevelObject(const std::string& name, std::vector<scenes::Mesh> meshes) {
    scenes::Object object;
    object.name = name;
    scenes::Level level;
    level.meshes = std::move(meshes);
    object.levels.push_back(std::move(level));
    return object;
}

// Two screen-filling quads on the view axis, one at z = -2 and one at z = -4, drawn in the
// given order (object 0 first, as the renderer draws).
scenes::Scene twoQuads(bool nearFirst) {
    scenes::Scene scene;
    scene.name = "quads";
    for (float z : nearFirst ? std::vector<float>{-2.0f, -4.0f} : std::vector<float>{-4.0f, -2.0f}) {
        scene.objects.push_back(oneLevelObject("quad", {quadMesh(-10, 10, z)}));
    }
    scene.views.push_back(straightCamera());
    scenes::updateStatistics(scene);
    return scene;
}

}  // namespace

TEST(FeatureTable, ShadedPixelsFollowTheDepthTestInDrawOrder) {
    const double screen = 100.0 * 100.0;
    {
        // Near quad first: the far one is rasterized in full but fails the depth test.
        const scenes::Scene scene = twoQuads(true);
        const timemodel::FeatureTable table(scene, scene.views[0], 100, 100);
        EXPECT_NEAR(table.contribution(0, 0)[Feature::kRasterPixels], screen, 1.0);
        EXPECT_NEAR(table.contribution(1, 0)[Feature::kRasterPixels], screen, 1.0);
        EXPECT_NEAR(table.contribution(0, 0)[Feature::kShadedPixels], screen, 1.0);
        EXPECT_LT(table.contribution(1, 0)[Feature::kShadedPixels], 0.01 * screen);
    }
    {
        // Far quad first: both pass (the near one overwrites), so both are shaded.
        const scenes::Scene scene = twoQuads(false);
        const timemodel::FeatureTable table(scene, scene.views[0], 100, 100);
        EXPECT_NEAR(table.contribution(0, 0)[Feature::kShadedPixels], screen, 1.0);
        EXPECT_NEAR(table.contribution(1, 0)[Feature::kShadedPixels], screen, 1.0);
    }
}

TEST(FeatureTable, ACoarserDepthPassChangesOnlyTheShares) {
    // The depth pass's grid only sets the shaded share; on a coarse grid the far quad of
    // the near-first pair still fails (nearly) everywhere and every other feature is the same.
    const scenes::Scene scene = twoQuads(true);
    const timemodel::FeatureTable fine(scene, scene.views[0], 100, 100);
    const timemodel::FeatureTable coarse(scene, scene.views[0], 100, 100, 16);
    for (int o = 0; o < 2; ++o) {
        EXPECT_EQ(fine.contribution(o, 0)[Feature::kRasterPixels], coarse.contribution(o, 0)[Feature::kRasterPixels]);
        EXPECT_EQ(fine.contribution(o, 0)[Feature::kTriangles], coarse.contribution(o, 0)[Feature::kTriangles]);
    }
    EXPECT_NEAR(coarse.contribution(0, 0)[Feature::kShadedPixels], 100.0 * 100.0, 1.0);
    EXPECT_LT(coarse.contribution(1, 0)[Feature::kShadedPixels], 0.07 * 100.0 * 100.0);
}

namespace {

// A far object made of a textured left half and a plain right half (z = -4), and a plain
// screen-filling near quad (z = -2); `farFirst` puts the far object first in draw order.
scenes::Scene halfTexturedBehindAQuad(bool farFirst) {
    scenes::Scene scene;
    scene.name = "half_textured";
    scenes::Texture texture;
    texture.name = "t";
    texture.width = texture.height = 2;
    texture.rgba.assign(2 * 2 * 4, 128);
    scene.textures.push_back(texture);
    scene.materials.push_back(scenes::diffuseMaterial("plain", glm::vec3(1.0f)));
    scene.materials.push_back(scenes::diffuseMaterial("textured", glm::vec3(1.0f), 0));
    scenes::Object far = oneLevelObject("far", {quadMesh(-10, 0, -4, 1), quadMesh(0, 10, -4, 0)});
    scenes::Object near = oneLevelObject("near", {quadMesh(-10, 10, -2, 0)});
    if (farFirst) {
        scene.objects.push_back(std::move(far));
        scene.objects.push_back(std::move(near));
    } else {
        scene.objects.push_back(std::move(near));
        scene.objects.push_back(std::move(far));
    }
    scene.views.push_back(straightCamera());
    scenes::updateStatistics(scene);
    return scene;
}

}  // namespace

TEST(FeatureTable, TexturedPixelsAndShadedEdgesFollowTheMaterialsAndTheDepthTest) {
    const double screen = 100.0 * 100.0;
    {
        // Far object first: all its fragments pass; half of them are textured.
        const scenes::Scene scene = halfTexturedBehindAQuad(true);
        const timemodel::FeatureTable table(scene, scene.views[0], 100, 100);
        const timemodel::FrameFeatures& far = table.contribution(0, 0);
        EXPECT_NEAR(far[Feature::kShadedPixels], screen, 1.0);
        EXPECT_NEAR(far[Feature::kTexturedPixels], 0.5 * screen, 1.0);
        EXPECT_GT(far[Feature::kEdgePixels], 100.0);  // the diagonals and the seam
        EXPECT_NEAR(far[Feature::kShadedEdgePixels], far[Feature::kEdgePixels], 1e-6 * far[Feature::kEdgePixels]);
        EXPECT_EQ(table.contribution(1, 0)[Feature::kTexturedPixels], 0.0);  // plain material
    }
    {
        // Near quad first: the far object is rasterized in full but fails the depth test, so it
        // shades (and samples its texture) almost nowhere, along its edges included.
        const scenes::Scene scene = halfTexturedBehindAQuad(false);
        const timemodel::FeatureTable table(scene, scene.views[0], 100, 100);
        const timemodel::FrameFeatures& far = table.contribution(1, 0);
        EXPECT_NEAR(far[Feature::kRasterPixels], screen, 1.0);
        EXPECT_LT(far[Feature::kTexturedPixels], 0.01 * screen);
        EXPECT_LT(far[Feature::kShadedEdgePixels], 0.01 * far[Feature::kEdgePixels]);
    }
}
