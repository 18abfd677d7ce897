#include "evaluation/level_costs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "box_objects.hpp"
#include "scenes/viewpoints.hpp"

namespace lodopt::evaluation {
namespace {

TEST(LevelCosts, ExchangeRateHandWorked) {
    // A finer move gaining 0.02 for 1 ms and a coarser one losing 0.05 to save 1 ms: every rate
    // in [0.02, 0.05] makes the answer the best of its moves; the geometric middle.
    EXPECT_NEAR(exchangeRate(std::vector<double>{0.02, -0.05}, std::vector<double>{1.0, -1.0}), std::sqrt(0.02 * 0.05),
                1e-12);
    // Conflicting moves (a finer one worth 0.1 per ms, a coarser one losing only 0.01 per ms):
    // the summed violation is 0.09 anywhere in [0.01, 0.1], its flat minimum.
    EXPECT_NEAR(exchangeRate(std::vector<double>{0.1, -0.01}, std::vector<double>{1.0, -1.0}), std::sqrt(0.001), 1e-12);
    // Only coarser moves: any rate up to the cheapest loss per ms holds; half of it.
    EXPECT_NEAR(exchangeRate(std::vector<double>{-0.04, -0.3}, std::vector<double>{-2.0, -3.0}), 0.01, 1e-12);
    EXPECT_EQ(exchangeRate(std::vector<double>{}, std::vector<double>{}), 0.0);
    EXPECT_THROW(exchangeRate(std::vector<double>{1.0}, std::vector<double>{}), std::invalid_argument);
}

TEST(LevelCosts, CoarserLevelsOfTheReferenceAnswerCostFitness) {
    scenes::Scene scene;
    scene.name = "boxes";
    scene.objects = {test_scenes::boxObject("near", {0, 0, 0}, {{1, 0.5f, 0.5f}, {0.7f, 0.35f, 0.35f}, {0.4f, 0.2f, 0.2f}}, -1),
                     test_scenes::boxObject("behind_camera", {0, 0, 10}, {{1, 1, 1}, {0.5f, 0.5f, 0.5f}}, -1)};
    scenes::updateStatistics(scene);
    renderer::RenderSettings render;
    render.width = render.height = 64;
    renderer::Renderer renderer(scene, render);
    scenes::Camera camera;
    camera.position = {0.0f, 1.0f, 4.0f};
    camera.target = {0.0f, 0.0f, 0.0f};
    // The answer: every object at level 0 (a budget that holds everything); the hidden object is
    // listed as searched although the view skips it.
    ViewChoices choices{{0, 0}, {}, {0, 1}};
    for (const scenes::Object& object : scene.objects) {
        choices.screenSizes.push_back(scenes::screenSize(scenes::worldBounds(object, 0), camera));
    }
    const FrameTimeEstimator estimator = [](const timemodel::FrameFeatures& f) {
        return 1.0 + 1e-3 * f[timemodel::Feature::kRasterPixels];
    };
    SearchViewSettings settings;
    settings.budgetMs = 1e6;
    const ViewLevelCosts costs =
        measureLevelCosts(scene, camera, choices, renderer, {}, estimator, timemodel::everyFeature(), settings);
    ASSERT_EQ(costs.levelCost.size(), 2u);
    ASSERT_EQ(costs.levelCost[0].size(), 3u);
    EXPECT_GT(costs.lambda, 0.0);
    EXPECT_EQ(costs.levelCost[0][0], 0.0);  // the answer's own level
    // Coarser levels lose more fitness than the rate values the time they save.
    EXPECT_GT(costs.levelCost[0][1], 0.0);
    EXPECT_GT(costs.levelCost[0][2], 0.0);
    // The object behind the camera is not searched by the view: no costs.
    EXPECT_EQ(costs.levelCost[1], (std::vector<double>{0.0, 0.0}));
    const ViewChoices bad{{0}, {}, {0}};
    EXPECT_THROW(measureLevelCosts(scene, camera, bad, renderer, {}, estimator, timemodel::everyFeature(), settings),
                 std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::evaluation
