// The time model's software depth pass (timemodel/src/occlusion.hpp): sampling each triangle
// only on the cells its rows can reach counts exactly what sampling its whole bounding box
// counts, on the built-in scenes and on random and degenerate triangles.
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "occlusion.hpp"
#include "scenes/builtin.hpp"
#include "scenes/mesh_builder.hpp"
#include "timemodel/features.hpp"

namespace {

using lodopt::timemodel::detail::depthPassShares;
constexpr int kCells = lodopt::timemodel::FeatureTable::kDepthPassCells;
namespace scenes = lodopt::scenes;

glm::mat4 viewProjection(const scenes::Camera& camera, float aspect) {
    return scenes::projectionMatrix(camera, aspect) * scenes::viewMatrix(camera);
}

void expectSameShares(const scenes::Scene& scene, const glm::mat4& vp, float aspect, const std::string& what) {
    const std::vector<double> spans = depthPassShares(scene, vp, aspect, kCells);
    const std::vector<double> boxes = depthPassShares(scene, vp, aspect, kCells, true);
    ASSERT_EQ(spans.size(), boxes.size());
    for (std::size_t o = 0; o < spans.size(); ++o) EXPECT_EQ(spans[o], boxes[o]) << what << ", object " << o;
}

TEST(DepthPass, SpansCountWhatTheBoxCountsOnTheBuiltInScenes) {
    for (const char* name : {"harbor", "forest"}) {
        const scenes::Scene scene = scenes::makeBuiltinScene(name);
        for (const scenes::Camera& view : scene.views) {
            expectSameShares(scene, viewProjection(view, 1.0f), 1.0f, std::string(name) + " " + view.name);
        }
        // A wide viewport too: the grid is 128 x 64.
        expectSameShares(scene, viewProjection(scene.views[0], 2.0f), 2.0f, std::string(name) + " wide");
    }
}

TEST(DepthPass, SpansCountWhatTheBoxCountsOnRandomAndThinTriangles) {
    // One object of many triangles, some slivers thinner than a cell, some with vertices on
    // cell-centre rows, some behind the camera (clipped at the near plane).
    std::mt19937 random(11);
    std::uniform_real_distribution<float> coordinate(-1.5f, 1.5f), depth(-3.0f, 1.5f);
    scenes::MeshBuilder builder;
    for (int t = 0; t < 400; ++t) {
        glm::vec3 a(coordinate(random), coordinate(random), depth(random));
        glm::vec3 b(coordinate(random), coordinate(random), depth(random));
        glm::vec3 c = t % 3 == 0 ? a + (b - a) * 0.37f + glm::vec3(1e-4f, 0.0f, 0.0f)  // a sliver
                                 : glm::vec3(coordinate(random), coordinate(random), depth(random));
        if (t % 5 == 0) b.y = a.y;  // a horizontal edge
        builder.addTriangle(a, b, c);
    }
    scenes::Scene scene;
    scenes::Object object;
    object.name = "triangles";
    object.levels.push_back(scenes::Level{});
    object.levels[0].meshes.push_back(builder.finish());
    scene.objects.push_back(object);
    scene.objects.push_back(object);  // a second copy: every fragment of it fails or ties
    scenes::Camera camera;
    camera.position = {0.0f, 0.0f, 2.5f};
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.nearPlane = 0.5f;
    camera.farPlane = 10.0f;
    for (float aspect : {1.0f, 0.7f, 1.6f}) {
        expectSameShares(scene, viewProjection(camera, aspect), aspect, "random, aspect " + std::to_string(aspect));
    }
    // And the shares are not trivial: the 400 triangles hide most of each other, and the copy
    // drawn second ties everywhere with the first, so LESS passes none of it.
    const std::vector<double> shares = depthPassShares(scene, viewProjection(camera, 1.0f), 1.0f, kCells);
    EXPECT_GT(shares[0], 0.05);
    EXPECT_LT(shares[0], 0.5);
    EXPECT_EQ(shares[1], 0.0);
}

TEST(DepthPass, TestedSharesAreWhatTheTableScalesShadedPixelsBy) {
    // timemodel::depthTestedShares, public for the scheduler's set-up, is the share the table's
    // shaded pixels take of its raster pixels at level 0: some of the harbor's ship is hidden.
    const scenes::Scene scene = scenes::makeBuiltinScene("harbor");
    const scenes::Camera& view = scene.views[1];
    const std::vector<double> shares = lodopt::timemodel::depthTestedShares(scene, view, 256, 256, kCells);
    const lodopt::timemodel::FeatureTable table(scene, view, 256, 256, kCells);
    ASSERT_EQ(shares.size(), scene.objects.size());
    int hidden = 0;
    for (std::size_t o = 0; o < shares.size(); ++o) {
        const auto& f = table.contribution(int(o), 0);
        using lodopt::timemodel::Feature;
        if (f[Feature::kRasterPixels] <= 0.0) continue;
        EXPECT_NEAR(shares[o], f[Feature::kShadedPixels] / f[Feature::kRasterPixels], 1e-9) << "object " << o;
        hidden += shares[o] < 0.99;
    }
    EXPECT_GT(hidden, 0);
}

}  // namespace
