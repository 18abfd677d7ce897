#include "evaluation/engine_thresholds.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "box_objects.hpp"
#include "scenes/engine_lod.hpp"
#include "scheduler/screen_thresholds.hpp"

namespace lodopt::evaluation {
namespace {

// A three-level box (half extents 1, 0.5, 0.5: largest extent 2) and a one-level box.
scenes::Scene twoBoxes() {
    scenes::Scene scene;
    scene.name = "boxes";
    scene.objects = {test_scenes::boxObject("chain", {0, 0, 0}, {{1, 0.5f, 0.5f}, {1, 0.5f, 0.5f}, {1, 0.5f, 0.5f}}, -1),
                     test_scenes::boxObject("single", {5, 0, 0}, {{1, 1, 1}}, -1)};
    scenes::updateStatistics(scene);
    return scene;
}

TEST(EngineThresholds, FitsOnTheFittingViewsAndScoresTheHeldOutOnes) {
    const scenes::Scene scene = twoBoxes();
    // Views 0-2 fit, view 3 is held out (every 4th). The chain chose level 0 at 0.8, 1 at 0.3,
    // 2 at 0.1; held out, level 1 at 0.05 (the rule says 2: disagreement).
    std::vector<ViewChoices> views = {{{0, 0}, {0.8, 0.5}, {0, 1}},
                                      {{1, 0}, {0.3, 0.5}, {0}},
                                      {{2, 0}, {0.1, 0.5}, {0}},
                                      {{1, 0}, {0.05, 0.5}, {0}}};
    ThresholdSettings settings;
    settings.fovYDegrees = 90.0;
    settings.aspect = 2.0;
    const std::vector<ObjectThresholds> results = fitEngineThresholds(scene, views, settings);
    ASSERT_EQ(results.size(), 2u);
    const ObjectThresholds& chain = results[0];
    EXPECT_TRUE(chain.fitted);
    EXPECT_EQ(chain.fitSamples, 3);
    EXPECT_EQ(chain.heldOutSamples, 1);
    ASSERT_EQ(chain.screenSize.size(), 2u);
    EXPECT_NEAR(chain.screenSize[0], std::sqrt(0.8 * 0.3), 1e-12);
    EXPECT_NEAR(chain.screenSize[1], std::sqrt(0.3 * 0.1), 1e-12);
    EXPECT_DOUBLE_EQ(chain.fitAgreement, 1.0);
    EXPECT_DOUBLE_EQ(chain.heldOutAgreement, 0.0);
    // The conventions, from the chain's level-0 bounds (largest extent 2, radius sqrt(6)/2).
    const scenes::Bounds bounds = scenes::worldBounds(scene.objects[0], 0);
    EXPECT_NEAR(chain.unityRelativeHeight[0], scenes::unityRelativeHeight(chain.screenSize[0], bounds), 1e-12);
    EXPECT_NEAR(chain.unityRelativeHeight[0] / chain.screenSize[0], 2.0 / std::sqrt(6.0), 1e-6);
    EXPECT_NEAR(chain.switchDistance[1], std::sqrt(6.0) / 2.0 / chain.screenSize[1], 1e-5);
    EXPECT_NEAR(chain.babylonCoverage[0], M_PI * 0.24 / 8.0, 1e-9);
    // The single-level box: searched once, nothing to switch.
    EXPECT_TRUE(results[1].screenSize.empty());
    EXPECT_EQ(results[1].fitSamples, 1);
}

TEST(EngineThresholds, UnsearchedObjectsKeepTheHalvingChainAndBadViewsAreRefused) {
    const scenes::Scene scene = twoBoxes();
    const std::vector<ViewChoices> none = {{{2, 0}, {0.4, 0.5}, {}}};  // nothing searched
    const std::vector<ObjectThresholds> results = fitEngineThresholds(scene, none, {});
    EXPECT_FALSE(results[0].fitted);
    EXPECT_EQ(results[0].screenSize, (std::vector<double>{1.0, 0.5}));
    EXPECT_TRUE(std::isnan(results[0].heldOutAgreement));
    const std::vector<ViewChoices> shortView = {{{0}, {0.4}, {0}}};
    EXPECT_THROW(fitEngineThresholds(scene, shortView, {}), std::invalid_argument);
    const std::vector<ViewChoices> outOfRange = {{{0, 0}, {0.4, 0.5}, {2}}};
    EXPECT_THROW(fitEngineThresholds(scene, outOfRange, {}), std::invalid_argument);
}

// Two three-level boxes: "seen" in three views, "rare" in one.
scenes::Scene twoChains() {
    scenes::Scene scene;
    scene.name = "chains";
    const std::vector<glm::vec3> levels = {{1, 0.5f, 0.5f}, {1, 0.5f, 0.5f}, {1, 0.5f, 0.5f}};
    scene.objects = {test_scenes::boxObject("seen", {0, 0, 0}, levels, -1),
                     test_scenes::boxObject("rare", {5, 0, 0}, levels, -1)};
    scenes::updateStatistics(scene);
    return scene;
}

TEST(EngineThresholds, ObjectsFewViewsSawLeanOnTheRuleTheirPeersShare) {
    const scenes::Scene scene = twoChains();
    // "seen": level 0 at 0.8 in three views, level 1 at 0.3. "rare": once, level 2 at 0.8.
    const std::vector<ViewChoices> views = {{{0, 2}, {0.8, 0.5}, {0}},
                                            {{0, 2}, {0.8, 0.5}, {0}},
                                            {{0, 2}, {0.8, 0.5}, {0}},
                                            {{1, 2}, {0.3, 0.8}, {0, 1}}};
    ThresholdSettings settings;
    settings.holdoutEvery = 0;
    settings.priorSamples = 0.0;
    const std::vector<ObjectThresholds> alone = fitEngineThresholds(scene, views, settings);
    EXPECT_EQ(scheduler::levelForScreenSize(alone[1].screenSize, 0.8), 2);
    EXPECT_DOUBLE_EQ(alone[1].fitAgreement, 1.0);
    // The pool (level errors weighted by size squared: 1.28 for each sample at 0.8 three of them
    // "seen"'s, 0.09 at 0.3) weighs 4 of rare's own sample: at 0.8 level 0 costs 1.28 + 0.98 x
    // 1.28, level 2 0.98 x 3 x 1.28.
    settings.priorSamples = 4.0;
    const std::vector<ObjectThresholds> pooled = fitEngineThresholds(scene, views, settings);
    EXPECT_EQ(scheduler::levelForScreenSize(pooled[1].screenSize, 0.8), 0);
    EXPECT_TRUE(pooled[1].fitted);
    EXPECT_DOUBLE_EQ(pooled[1].fitAgreement, 0.0);  // its own choice is outvoted
    // An object with levels that no view searched takes the shared rule.
    const std::vector<ViewChoices> seenOnly = {views[0], views[1], views[2], {{1, 2}, {0.3, 0.8}, {0}}};
    for (double prior : {4.0, 0.0}) {
        settings.priorSamples = prior;
        const std::vector<ObjectThresholds> unseen = fitEngineThresholds(scene, seenOnly, settings);
        EXPECT_FALSE(unseen[1].fitted);
        EXPECT_EQ(unseen[1].screenSize, unseen[0].screenSize) << prior;
    }
}

TEST(EngineThresholds, MeasuredCostsPriceEachLevel) {
    const scenes::Scene scene = twoChains();
    // The optimizer drew level 1 at 0.5, but its costs say level 0 was nearly as good and level 2
    // far worse; at 0.2 level 2 is cheapest.
    const std::vector<ViewChoices> views = {{{1, 2}, {0.5, 0.5}, {0}}, {{2, 2}, {0.2, 0.5}, {0}}};
    const std::vector<ViewLevelCosts> costs = {{0.1, {{0.01, 0.0, 0.5}}}, {0.1, {{0.3, 0.2, 0.0}}}};
    ThresholdSettings settings;
    settings.holdoutEvery = 0;
    settings.priorSamples = 0.0;
    const std::vector<ObjectThresholds> results = fitEngineThresholds(scene, views, settings, costs);
    EXPECT_EQ(scheduler::levelForScreenSize(results[0].screenSize, 0.5), 1);
    EXPECT_EQ(scheduler::levelForScreenSize(results[0].screenSize, 0.2), 2);
    EXPECT_NEAR(results[0].screenSize[1], std::sqrt(0.5 * 0.2), 1e-12);
    // Costs for a view must cover its searched objects, each with one value per level.
    const std::vector<ViewLevelCosts> missing = {{0.1, {}}, {0.1, {{0.3, 0.2, 0.0}}}};
    EXPECT_THROW(fitEngineThresholds(scene, views, settings, missing), std::invalid_argument);
    const std::vector<ViewLevelCosts> shortCosts = {{0.1, {{0.0, 0.1}}}, {0.1, {{0.3, 0.2, 0.0}}}};
    EXPECT_THROW(fitEngineThresholds(scene, views, settings, shortCosts), std::invalid_argument);
    EXPECT_THROW(fitEngineThresholds(scene, views, settings, std::span<const ViewLevelCosts>(costs).first(1)),
                 std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::evaluation
