#include "evaluation/switch_rules.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "box_objects.hpp"
#include "scenes/engine_lod.hpp"
#include "scenes/viewpoints.hpp"

namespace lodopt::evaluation {
namespace {

// A four-level box shrinking level by level (level-0 half extents 1, 0.5, 0.5: largest extent 2,
// sphere radius sqrt(6)/2) and a one-level box.
scenes::Scene shrinkingBoxes() {
    scenes::Scene scene;
    scene.name = "boxes";
    scene.objects = {test_scenes::boxObject("chain", {0, 0, 0},
                                            {{1, 0.5f, 0.5f}, {0.8f, 0.4f, 0.4f}, {0.6f, 0.3f, 0.3f}, {0.4f, 0.2f, 0.2f}}, -1),
                     test_scenes::boxObject("single", {3, 0, 0}, {{0.5f, 0.5f, 0.5f}}, -1)};
    scenes::updateStatistics(scene);
    return scene;
}

TEST(SwitchRules, DefaultRulesInScreenSizeHandWorked) {
    scenes::Scene scene = shrinkingBoxes();
    std::vector<SwitchRuleThresholds> rules = defaultSwitchRules(scene);
    // No coverage in the scene: no "file" rule.
    ASSERT_EQ(rules.size(), 3u);
    EXPECT_EQ(rules[0].name, "msft_default");
    EXPECT_EQ(rules[1].name, "unitygltf_halving");
    EXPECT_EQ(rules[2].name, "unreal_075");
    // Unity relative height h is s e / (2 r): s = h 2r / e = h sqrt(6) / 2 for the chain.
    const double toSize = std::sqrt(6.0) / 2.0;
    ASSERT_EQ(rules[0].thresholds[0].size(), 3u);
    EXPECT_NEAR(rules[0].thresholds[0][0], 0.5 * toSize, 1e-6);
    EXPECT_NEAR(rules[0].thresholds[0][1], 0.2 * toSize, 1e-6);
    EXPECT_NEAR(rules[0].thresholds[0][2], 0.01 * toSize, 1e-6);
    EXPECT_NEAR(rules[1].thresholds[0][2], 0.125 * toSize, 1e-6);
    EXPECT_NEAR(rules[2].thresholds[0][0], 0.75, 1e-12);
    EXPECT_NEAR(rules[2].thresholds[0][2], 0.421875, 1e-12);
    EXPECT_TRUE(rules[0].thresholds[1].empty());  // one level: nothing to switch

    // Five levels: the 0.5/0.2/0.01 list continues with its last ratio (0.05).
    scene.objects[0].levels.push_back(scene.objects[0].levels.back());
    rules = defaultSwitchRules(scene);
    ASSERT_EQ(rules[0].thresholds[0].size(), 4u);
    EXPECT_NEAR(rules[0].thresholds[0][3], 0.0005 * toSize, 1e-9);

    // Coverage on every level but the last of every object with levels: a "file" rule first.
    for (std::size_t k = 0; k + 1 < scene.objects[0].levels.size(); ++k) {
        scene.objects[0].levels[k].screenCoverage = float(0.4 / double(k + 1));
    }
    rules = defaultSwitchRules(scene);
    ASSERT_EQ(rules[0].name, "file");
    EXPECT_NEAR(rules[0].thresholds[0][1], 0.2, 1e-6);
    scene.objects[0].levels[2].screenCoverage.reset();
    EXPECT_NE(defaultSwitchRules(scene)[0].name, "file");
}

// The engines' geometric-error rules, from errors set by hand on the chain (radius sqrt(6)/2):
// pixelerror's level k opens at 2 R / (D_k H) on a 512-pixel viewport; Unreal's at
// 2 (0.5 1920/1080) R / (960 D_k + R); each threshold the largest size of the coarser levels.
TEST(SwitchRules, EngineGeometricRulesFromEachLevelsDeviation) {
    scenes::Scene scene = shrinkingBoxes();
    EXPECT_EQ(defaultSwitchRules(scene, 512).size(), 3u);  // no geometric errors: left out
    const double deviation[] = {0.0, 0.01, 0.04, 0.02};    // level 3 less off than level 2
    for (int k = 0; k < 4; ++k) scene.objects[0].levels[std::size_t(k)].geometricError = float(deviation[k]);
    scene.objects[1].levels[0].geometricError = 0.0f;
    EXPECT_EQ(defaultSwitchRules(scene).size(), 3u);  // no viewport height: left out
    const std::vector<SwitchRuleThresholds> rules = defaultSwitchRules(scene, 512);
    ASSERT_EQ(rules.size(), 5u);
    ASSERT_EQ(rules[3].name, "pixelerror");
    ASSERT_EQ(rules[4].name, "unreal_auto");
    const double radius = double(scenes::worldBounds(scene.objects[0], 0).sphereRadius);
    auto pixel = [&](int k) { return 2.0 * radius / (double(float(deviation[k])) * 512.0); };
    ASSERT_EQ(rules[3].thresholds[0].size(), 3u);
    EXPECT_NEAR(rules[3].thresholds[0][2], pixel(3), 1e-9);                  // t_2: level 3's own
    EXPECT_NEAR(rules[3].thresholds[0][1], pixel(3), 1e-9);                  // level 3 opens before level 2
    EXPECT_NEAR(rules[3].thresholds[0][0], std::max(pixel(2), pixel(1)), 1e-9);
    EXPECT_NEAR(rules[3].thresholds[0][0], pixel(1), 1e-9);
    auto unreal = [&](int k) {
        return 2.0 * (0.5 * 1920.0 / 1080.0) * radius / (double(float(deviation[k])) * 960.0 + radius);
    };
    EXPECT_NEAR(rules[4].thresholds[0][0], unreal(1), 1e-9);
    EXPECT_NEAR(rules[4].thresholds[0][2], unreal(3), 1e-9);
    EXPECT_TRUE(rules[3].thresholds[1].empty());
    // Where level 1's deviation spans 0.6 px (level 2's 2.4, level 3's 1.2) the rule draws level 1;
    // where it spans 0.45 px, level 3 (0.9 px) is allowed though level 2 (1.8 px) is not.
    const ViewChoices view{{0, 0}, {0.6 * pixel(1), 0.5}, {0}};
    EXPECT_EQ(ruleCombination(scene, rules[3].thresholds, view, 1.0)[0], 1);
    const ViewChoices far{{0, 0}, {0.9 * pixel(3), 0.5}, {0}};
    EXPECT_EQ(ruleCombination(scene, rules[3].thresholds, far, 1.0)[0], 3);
}

TEST(SwitchRules, RuleCombinationBiasesSearchedObjectsAndDrawsTheOthersCoarsest) {
    const scenes::Scene scene = shrinkingBoxes();
    const ObjectThresholdList thresholds = {{0.4, 0.2, 0.1}, {}};
    ViewChoices view{{0, 0}, {0.3, 0.5}, {0}};
    EXPECT_EQ(ruleCombination(scene, thresholds, view, 1.0), (scenes::Combination{1, 0}));
    EXPECT_EQ(ruleCombination(scene, thresholds, view, 2.0), (scenes::Combination{0, 0}));  // 0.6 >= 0.4
    EXPECT_EQ(ruleCombination(scene, thresholds, view, 0.5), (scenes::Combination{2, 0}));  // 0.15
    EXPECT_EQ(ruleCombination(scene, thresholds, view, 0.1), (scenes::Combination{3, 0}));
    view.searched.clear();
    EXPECT_EQ(ruleCombination(scene, thresholds, view, 100.0), (scenes::Combination{3, 0}));
}

// Predicted time: 1 ms per level finer than the coarsest, per searched object.
double finenessMs(const scenes::Combination& levels) { return double(3 - levels[0]); }

TEST(SwitchRules, LodBiasIsTheLargestWithinTheBudgetAgainstASweepOfBiases) {
    const scenes::Scene scene = shrinkingBoxes();
    const ObjectThresholdList thresholds = {{0.4, 0.2, 0.1}, {}};
    const std::vector<ViewChoices> views = {{{0, 0}, {0.3, 0.5}, {0}},
                                            {{0, 0}, {0.05, 0.5}, {0}},
                                            {{0, 0}, {0.9, 0.5}, {0}}};
    const ViewTimeMs predict = [](std::size_t, const scenes::Combination& levels) { return finenessMs(levels); };
    auto meanAt = [&](double bias) {
        double sum = 0.0;
        for (const ViewChoices& view : views) sum += finenessMs(ruleCombination(scene, thresholds, view, bias));
        return sum / double(views.size());
    };
    for (double budget : {0.2, 1.0, 1.5, 2.0, 2.5, 3.0}) {
        const LodBias fit = fitLodBias(scene, thresholds, views, predict, budget);
        EXPECT_TRUE(fit.meetsBudget) << budget;
        EXPECT_LE(fit.meanPredictedMs, budget);
        EXPECT_DOUBLE_EQ(fit.meanPredictedMs, meanAt(fit.bias));
        // No larger bias on a fine grid keeps the mean within the budget... unless it draws the same.
        for (double b = fit.bias * 1.001; b < 1000.0; b *= 1.01) {
            if (meanAt(b) <= budget) {
                EXPECT_EQ(meanAt(b), fit.meanPredictedMs) << budget << " at " << b;
            }
        }
    }
    // A budget even the coarsest levels exceed: not met, every needed object coarsest.
    const ViewTimeMs costly = [](std::size_t, const scenes::Combination& levels) { return 5.0 + finenessMs(levels); };
    const LodBias over = fitLodBias(scene, thresholds, views, costly, 1.0);
    EXPECT_FALSE(over.meetsBudget);
    EXPECT_DOUBLE_EQ(over.meanPredictedMs, 5.0);
    EXPECT_THROW(fitLodBias(scene, thresholds, {}, predict, 1.0), std::invalid_argument);
    EXPECT_THROW(fitLodBias(scene, thresholds, views, predict, 0.0), std::invalid_argument);
    const std::vector<ViewChoices> bad = {{{0, 0}, {0.3}, {0}}};
    EXPECT_THROW(fitLodBias(scene, thresholds, bad, predict, 1.0), std::invalid_argument);
}

TEST(SwitchRules, ComparisonScoresTheExtremeRulesAsTheReferenceAndTheCoarsest) {
    const scenes::Scene scene = shrinkingBoxes();
    renderer::RenderSettings settings;
    settings.width = settings.height = 64;
    renderer::Renderer renderer(scene, settings);
    // Four views around the chain; the optimizer "chose" level 0 (the reference: fitness 1).
    std::vector<ScoredView> views;
    for (int k = 0; k < 4; ++k) {
        scenes::Camera camera;
        camera.position = {4.0f * std::cos(0.4f * float(k)), 1.0f, 4.0f * std::sin(0.4f * float(k))};
        camera.target = {0, 0, 0};
        ScoredView view{{{0, 0}, {}, {0}}, camera, 1.0};
        for (const scenes::Object& object : scene.objects) {
            view.choices.screenSizes.push_back(scenes::screenSize(scenes::worldBounds(object, 0), camera));
        }
        views.push_back(view);
    }
    // Two rules of very different scales: at equal cost the bias makes them draw alike.
    const std::vector<SwitchRuleThresholds> rules = {{"small", {{1e-3, 1e-4, 1e-5}, {}}},
                                                     {"large", {{1e3, 1e2, 10.0}, {}}}};
    const FrameTimeEstimator estimator = [](const timemodel::FrameFeatures& f) {
        return 1.0 + 1e-3 * f[timemodel::Feature::kRasterPixels];
    };
    RuleComparisonSettings compare;
    compare.width = compare.height = 64;
    // The fitting views' mean time with the chain at level k.
    auto meanMsAt = [&](int level) {
        double sum = 0.0;
        for (int v : {0, 1, 2}) {
            const timemodel::FeatureTable table(scene, views[std::size_t(v)].camera, 64, 64);
            sum += estimator(table.features({level, 0}));
        }
        return sum / 3.0;
    };
    ASSERT_GT(meanMsAt(0), meanMsAt(3));  // finer boxes cover more pixels

    // A budget that holds every level: both rules draw level 0, the reference (fitness 1).
    compare.budgetMs = meanMsAt(0) * 2.0;
    const RuleComparison finest =
        compareSwitchRules(scene, views, rules, renderer, {}, estimator, timemodel::everyFeature(), compare);
    EXPECT_EQ(finest.fittingViews, 3);
    EXPECT_EQ(finest.heldOutViews, 1);
    EXPECT_EQ(finest.gainViews, 1);
    EXPECT_LT(finest.coarsestMeanFitness, 0.999);  // the coarsest box differs from the reference
    ASSERT_EQ(finest.rules.size(), 2u);
    for (const RuleOutcome& rule : finest.rules) {
        EXPECT_TRUE(rule.bias.meetsBudget) << rule.rule;
        EXPECT_NEAR(rule.meanFitness, 1.0, 1e-12) << rule.rule;
        EXPECT_NEAR(rule.gainFraction, 1.0, 1e-12) << rule.rule;
        EXPECT_DOUBLE_EQ(rule.overBudgetShare, 0.0) << rule.rule;
    }
    // A budget only the coarsest level meets: both rules draw it (gain 0).
    compare.budgetMs = meanMsAt(3) * 1.0001;
    const RuleComparison coarsest =
        compareSwitchRules(scene, views, rules, renderer, {}, estimator, timemodel::everyFeature(), compare);
    for (const RuleOutcome& rule : coarsest.rules) {
        EXPECT_TRUE(rule.bias.meetsBudget) << rule.rule;
        EXPECT_DOUBLE_EQ(rule.meanFitness, coarsest.coarsestMeanFitness) << rule.rule;
        EXPECT_DOUBLE_EQ(rule.gainFraction, 0.0) << rule.rule;
    }

    // A budget below every rule's time: no bias meets it and every held-out view is over.
    compare.budgetMs = 0.5;
    const RuleComparison over =
        compareSwitchRules(scene, views, rules, renderer, {}, estimator, timemodel::everyFeature(), compare);
    for (const RuleOutcome& rule : over.rules) {
        EXPECT_FALSE(rule.bias.meetsBudget) << rule.rule;
        EXPECT_DOUBLE_EQ(rule.overBudgetShare, 1.0) << rule.rule;
    }
    compare.holdoutEvery = 1;  // every view held out: no fitting view
    EXPECT_THROW(compareSwitchRules(scene, views, rules, renderer, {}, estimator, timemodel::everyFeature(), compare),
                 std::invalid_argument);
    // Nothing held out: biases only.
    compare.holdoutEvery = 0;
    const RuleComparison biasesOnly =
        compareSwitchRules(scene, views, rules, renderer, {}, estimator, timemodel::everyFeature(), compare);
    EXPECT_EQ(biasesOnly.heldOutViews, 0);
    EXPECT_TRUE(std::isnan(biasesOnly.rules[0].meanFitness));
}

TEST(SwitchRules, LodBiasIsBakedIntoTheEngineValues) {
    const scenes::Scene scene = shrinkingBoxes();
    const std::vector<ViewChoices> views = {{{1, 0}, {0.3, 0.5}, {0}}, {{0, 0}, {0.9, 0.5}, {0}}};
    ThresholdSettings settings;
    settings.holdoutEvery = 0;
    settings.hysteresis = 0.2;
    std::vector<ObjectThresholds> results = fitEngineThresholds(scene, views, settings);
    const double fitted = results[0].fittedScreenSize[0];
    applyLodBias(scene, results, 2.0, settings);
    EXPECT_DOUBLE_EQ(results[0].screenSize[0], fitted / 2.0);
    EXPECT_DOUBLE_EQ(results[0].fittedScreenSize[0], fitted);
    EXPECT_DOUBLE_EQ(results[0].lodBias, 2.0);
    const scenes::Bounds bounds = scenes::worldBounds(scene.objects[0], 0);
    EXPECT_NEAR(results[0].switchDistance[0], scenes::switchDistance(fitted / 2.0, bounds, settings.fovYDegrees), 1e-9);
    // Unreal's hysteresis: the band t h / (1 - h) above the threshold, here t / 4.
    EXPECT_NEAR(results[0].unrealHysteresis[0], fitted / 2.0 / 4.0, 1e-12);
    EXPECT_THROW(applyLodBias(scene, results, 0.0, settings), std::invalid_argument);
}

TEST(SwitchRules, HysteresisHoldsTheCoarserLevelUntilTheBandIsCrossed) {
    scenes::Scene scene;
    scene.name = "box";
    scene.objects = {test_scenes::boxObject("chain", {0, 0, 0}, {{1, 0.5f, 0.5f}, {0.5f, 0.25f, 0.25f}}, -1),
                     test_scenes::boxObject("single", {0, 0, -50}, {{1, 1, 1}}, -1)};
    scenes::updateStatistics(scene);
    const double radius = double(scenes::worldBounds(scene.objects[0], 0).sphereRadius);
    // Under a 90-degree field of view the screen size is r / d: cameras at d = r / s.
    std::vector<scenes::Camera> path;
    for (double size : {0.52, 0.49, 0.51, 0.48, 0.6, 0.3}) {
        scenes::Camera camera;
        camera.fovYDegrees = 90.0f;
        camera.position = {0.0f, 0.0f, float(radius / size)};
        camera.target = {0.0f, 0.0f, 0.0f};
        ASSERT_NEAR(scenes::screenSize(scenes::worldBounds(scene.objects[0], 0), camera), size, 1e-5);
        path.push_back(camera);
    }
    const ObjectThresholdList thresholds = {{0.5}, {}};
    // Levels 0 1 0 1 0 1: five switches.
    const RuleSwitches plain = countRuleSwitches(scene, thresholds, path, 0.0);
    EXPECT_EQ(plain.switches, 5);
    EXPECT_EQ(plain.objectFrames, 5);  // one object with levels, five frame pairs
    // With 0.1, level 1 goes finer only from 0.5 / 0.9 = 0.556: levels 0 1 1 1 0 1, three.
    EXPECT_EQ(countRuleSwitches(scene, thresholds, path, 0.1).switches, 3);
    EXPECT_THROW(countRuleSwitches(scene, thresholds, path, 1.0), std::invalid_argument);
    EXPECT_THROW(countRuleSwitches(scene, {{0.5}}, path, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::evaluation
