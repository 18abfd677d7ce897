// Evaluation: skipping, level merging, fast path == full path, thread-count independence.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "scenes/builtin.hpp"
#include "scenes/mesh_builder.hpp"
#include "box_objects.hpp"

using namespace lodopt;
using lodopt::test_scenes::boxObject;

namespace {

// Camera at z = 10 looking at the origin.
//   visible:  a box at the origin whose levels 0 and 1 are identical (merged), level 2 smaller
//   behind:   a box behind the camera (outside the frustum)
//   speck:    a 1 mm box 500 units away (below one pixel)
//   wall:     a wide wall at z = -5 … and `hidden`, a box behind the wall at z = -10
scenes::Scene skipScene() {
    scenes::Scene scene;
    scene.name = "skips";
    scene.materials.push_back(scenes::diffuseMaterial("red", {0.8f, 0.2f, 0.2f}));
    scene.materials.push_back(scenes::diffuseMaterial("grey", {0.5f, 0.5f, 0.5f}));
    scene.objects.push_back(boxObject("visible", {0, 0, 0}, {{1, 1, 1}, {1, 1, 1}, {0.5f, 0.5f, 0.5f}}, 0));
    scene.objects.push_back(boxObject("behind", {0, 0, 30}, {{1, 1, 1}, {0.5f, 0.5f, 0.5f}}, 0));
    scene.objects.push_back(boxObject("speck", {0, 0, -490}, {{0.001f, 0.001f, 0.001f}, {0.0005f, 0.0005f, 0.0005f}}, 0));
    scene.objects.push_back(boxObject("wall", {0, 0, -5}, {{40, 40, 0.1f}, {40, 40, 0.1f}}, 1));
    scene.objects.push_back(boxObject("hidden", {3, 0, -10}, {{1, 1, 1}, {0.5f, 0.5f, 0.5f}}, 0));
    scenes::Camera camera;
    camera.name = "front";
    camera.position = {0, 0, 10};
    camera.target = {0, 0, 0};
    camera.nearPlane = 0.1f;
    camera.farPlane = 1000.0f;
    scene.views.push_back(camera);
    scenes::updateStatistics(scene);
    return scene;
}

renderer::RenderSettings settings(int size) {
    renderer::RenderSettings s;
    s.width = s.height = size;
    return s;
}

optimizer::Combination randomCombination(const std::vector<int>& counts, std::mt19937& random) {
    optimizer::Combination combination;
    for (int count : counts) combination.push_back(int(random() % count));
    return combination;
}

}  // namespace

TEST(ViewSetup, SkipsWhatTheViewDoesNotNeedAndSaysWhy) {
    scenes::Scene scene = skipScene();
    renderer::Renderer renderer(scene, settings(128));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    const auto& objects = setup.objects();
    EXPECT_EQ(objects[0].skip, evaluation::SkipReason::None);
    EXPECT_EQ(objects[1].skip, evaluation::SkipReason::OutsideFrustum);
    EXPECT_EQ(objects[2].skip, evaluation::SkipReason::BelowOnePixel);
    EXPECT_EQ(objects[3].skip, evaluation::SkipReason::None);
    EXPECT_EQ(objects[4].skip, evaluation::SkipReason::Hidden);
    // visible: levels 0 and 1 render identically → one option (level 1), plus level 2.
    EXPECT_EQ(objects[0].optionLevels, (std::vector<int>{1, 2}));
    EXPECT_EQ(objects[0].mergedLevels, 1);
    // The wall's two levels are identical too: a single option.
    EXPECT_EQ(objects[3].optionLevels, (std::vector<int>{1}));
    EXPECT_EQ(setup.variableObjects(), (std::vector<int>{0, 3}));
    EXPECT_EQ(setup.levelCounts(), (std::vector<int>{2, 1}));
    const evaluation::SkipSummary& skip = setup.skipSummary();
    EXPECT_EQ(skip.searchedObjects, 2);
    EXPECT_EQ(skip.outsideFrustum, 1);
    EXPECT_EQ(skip.belowOnePixel, 1);
    EXPECT_EQ(skip.hidden, 1);
    EXPECT_EQ(skip.mergedLevels, 2);
    // Mapping both ways; skipped objects sit at their coarsest level.
    EXPECT_EQ(setup.toScene({1, 0}), (scenes::Combination{2, 1, 1, 1, 1}));
    EXPECT_EQ(setup.fromScene({0, 0, 0, 0, 0}), (optimizer::Combination{0, 0}));
    EXPECT_EQ(setup.fromScene({2, 0, 0, 0, 0}), (optimizer::Combination{1, 0}));
}

TEST(ViewSetup, ReferenceOptionsReproduceTheReferenceImage) {
    scenes::Scene scene = skipScene();
    renderer::Renderer renderer(scene, settings(128));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    metrics::MetricParameters parameters;
    evaluation::LayerEvaluator fast(setup, parameters);
    optimizer::Score score = fast.evaluate({0, 0});
    EXPECT_DOUBLE_EQ(score.fitness, 1.0);
    EXPECT_EQ(fast.imageOf({0, 0}).rgba, setup.reference().rgba);
    EXPECT_LT(fast.evaluate({1, 0}).fitness, 1.0);
}

TEST(Evaluators, FastAndFullPathsAgreeOnEveryHarborView) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(256));
    metrics::MetricParameters parameters;
    std::mt19937 random(11);
    for (const scenes::Camera& camera : scene.views) {
        evaluation::ViewSetup setup(scene, camera, renderer);
        evaluation::LayerEvaluator fast(setup, parameters);
        evaluation::FullRenderEvaluator full(setup, renderer, parameters);
        const std::vector<int> counts = setup.levelCounts();
        ASSERT_FALSE(counts.empty()) << camera.name;
        double worst = 0.0;
        for (int trial = 0; trial < 12; ++trial) {
            optimizer::Combination combination = randomCombination(counts, random);
            const double a = fast.evaluate(combination).fitness;
            const double b = full.evaluate(combination).fitness;
            worst = std::max(worst, std::abs(a - b));
            EXPECT_NEAR(a, b, 1e-3) << camera.name << " " << optimizer::formatCombination(combination);
        }
        std::cout << camera.name << ": max |fast - full| = " << worst << "\n";
    }
}

TEST(Evaluators, FastAndFullPathsAgreeOnEveryForestAndCityView) {
    // The search's scoring (window groups or owned windows, chosen per view) against full
    // renders, on random combinations of every view of the other two built-in scenes.
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    std::mt19937 random(17);
    for (const char* sceneName : {"forest", "city"}) {
        scenes::Scene scene = scenes::loadScene(sceneName);
        renderer::Renderer renderer(scene, settings(96));
        for (const scenes::Camera& camera : scene.views) {
            evaluation::ViewSetup setup(scene, camera, renderer);
            evaluation::LayerEvaluator fast(setup, parameters);
            evaluation::FullRenderEvaluator full(setup, renderer, parameters);
            const std::vector<int> counts = setup.levelCounts();
            ASSERT_GE(counts.size(), 2u) << sceneName << "/" << camera.name;
            double worst = 0.0;
            for (int trial = 0; trial < 6; ++trial) {
                const optimizer::Combination combination = randomCombination(counts, random);
                const double a = fast.evaluate(combination).fitness, b = full.evaluate(combination).fitness;
                worst = std::max(worst, std::abs(a - b));
                EXPECT_NEAR(a, b, 1e-3) << sceneName << "/" << camera.name << " "
                                        << optimizer::formatCombination(combination);
            }
            std::cout << sceneName << "/" << camera.name << ": " << counts.size()
                      << " searched objects, max |fast - full| = " << worst << "\n";
        }
    }
}

TEST(Evaluators, FullPathKeepsNoStateBetweenCandidates) {
    // The full path reuses one metric state (its buffers) for every candidate: each score must
    // still be the from-scratch metrics of that candidate's render, bit for bit, whatever was
    // evaluated before it (with precision/recall, every component).
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(160));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    const metrics::MetricParameters parameters;  // precision/recall on
    evaluation::FullRenderEvaluator full(setup, renderer, parameters);
    const std::vector<int> counts = setup.levelCounts();
    std::mt19937 random(5);
    std::vector<optimizer::Combination> combinations = {optimizer::Combination(counts.size(), 0)};
    for (int k = 0; k < 6; ++k) combinations.push_back(randomCombination(counts, random));
    combinations.push_back(combinations[1]);  // again, after others
    int belowOne = 0;
    for (const optimizer::Combination& combination : combinations) {
        const metrics::MetricResult reused = full.metricsOf(combination);
        renderer::Frame frame;
        renderer.render(setup.toScene(combination), setup.camera(), frame);
        const metrics::MetricResult fresh =
            metrics::evaluate(metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4),
                              metrics::makeImageView(setup.reference().rgba.data(), frame.width, frame.height, 4),
                              parameters);
        const std::string name = optimizer::formatCombination(combination);
        EXPECT_EQ(reused.fitness, fresh.fitness) << name;
        EXPECT_EQ(reused.ssim, fresh.ssim) << name;
        EXPECT_EQ(reused.boundaryEntropy.candidate, fresh.boundaryEntropy.candidate) << name;
        EXPECT_EQ(reused.informationEntropy.candidate, fresh.informationEntropy.candidate) << name;
        EXPECT_EQ(reused.precision, fresh.precision) << name;
        EXPECT_EQ(reused.recall, fresh.recall) << name;
        if (fresh.fitness < 1.0) ++belowOne;
    }
    EXPECT_DOUBLE_EQ(full.metricsOf(combinations[0]).fitness, 1.0);  // the reference itself
    EXPECT_GT(belowOne, 0);  // the candidates really differ from the reference
}

TEST(Evaluators, BatchScoresDoNotDependOnThreadCountStatesOrOrder) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(192));
    evaluation::ViewSetup setup(scene, scene.views[1], renderer);
    metrics::MetricParameters parameters;
    std::mt19937 random(5);
    std::vector<optimizer::Combination> batch;
    for (int k = 0; k < 24; ++k) batch.push_back(randomCombination(setup.levelCounts(), random));
    std::vector<optimizer::Score> serial(batch.size()), parallel(batch.size()), reversed(batch.size());
    std::vector<optimizer::Score> oneState(batch.size()), manyStates(batch.size());
    evaluation::LayerEvaluator one(setup, parameters, 1);
    evaluation::LayerEvaluator three(setup, parameters, 3);
    evaluation::LayerEvaluator single(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels, 1);
    evaluation::LayerEvaluator many(setup, parameters, 2, evaluation::DirtyRegions::ChangedPixels, 7);
    one.evaluateBatch(batch, serial);
    three.evaluateBatch(batch, parallel);
    std::vector<optimizer::Combination> backwards(batch.rbegin(), batch.rend());
    one.evaluateBatch(backwards, reversed);
    // Split into uneven batches, so states are left at different candidates in between.
    for (std::size_t begin = 0; begin < batch.size();) {
        const std::size_t count = std::min<std::size_t>(1 + begin % 5, batch.size() - begin);
        const std::span<const optimizer::Combination> part(batch.data() + begin, count);
        single.evaluateBatch(part, std::span<optimizer::Score>(oneState.data() + begin, count));
        many.evaluateBatch(part, std::span<optimizer::Score>(manyStates.data() + begin, count));
        begin += count;
    }
    for (std::size_t k = 0; k < batch.size(); ++k) {
        EXPECT_EQ(serial[k].fitness, parallel[k].fitness) << k;
        EXPECT_EQ(serial[k].fitness, reversed[batch.size() - 1 - k].fitness) << k;
        EXPECT_EQ(serial[k].fitness, oneState[k].fitness) << k;
        EXPECT_EQ(serial[k].fitness, manyStates[k].fitness) << k;
        EXPECT_EQ(serial[k].fitness, one.evaluate(batch[k]).fitness) << k;
        for (int c = 0; c < serial[k].componentCount; ++c) EXPECT_EQ(serial[k].components[c], parallel[k].components[c]);
    }
}

// A search skips precision/recall (not fused): same fitness and fidelities, two fewer
// components, on both paths.
TEST(Evaluators, SearchParametersSkipOnlyPrecisionAndRecall) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(128));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    const metrics::MetricParameters all;
    const metrics::MetricParameters search = evaluation::searchParameters(all);
    EXPECT_FALSE(search.computePrecisionRecall);
    EXPECT_EQ(search.ssimWeight, all.ssimWeight);
    evaluation::LayerEvaluator fastAll(setup, all), fastSearch(setup, search);
    evaluation::FullRenderEvaluator fullSearch(setup, renderer, search);
    EXPECT_EQ(fastAll.componentNames().size(), 5u);
    EXPECT_EQ(fastSearch.componentNames(), (std::vector<std::string>{"ssim", "boundary_entropy", "information_entropy"}));
    std::mt19937 random(2);
    for (int trial = 0; trial < 6; ++trial) {
        const optimizer::Combination combination = randomCombination(setup.levelCounts(), random);
        const optimizer::Score a = fastAll.evaluate(combination), b = fastSearch.evaluate(combination);
        const optimizer::Score c = fullSearch.evaluate(combination);
        EXPECT_EQ(a.componentCount, 5);
        ASSERT_EQ(b.componentCount, 3);
        EXPECT_EQ(c.componentCount, 3);
        EXPECT_EQ(a.fitness, b.fitness);
        for (int k = 0; k < 3; ++k) EXPECT_EQ(a.components[k], b.components[k]) << k;
        EXPECT_NEAR(b.fitness, c.fitness, 1e-3);
    }
}

TEST(Hints, DistancesAndCoverageArePlausible) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(128));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    std::vector<optimizer::VariableHints> hints = evaluation::computeHints(setup);
    ASSERT_EQ(hints.size(), setup.variableObjects().size());
    for (std::size_t v = 0; v < hints.size(); ++v) {
        EXPECT_GT(hints[v].distance, 0.0);
        EXPECT_GT(hints[v].screenCoverage, 0.0);
        EXPECT_GT(hints[v].projectedArea, 0.0);
        ASSERT_EQ(hints[v].levelPixelError.size(), std::size_t(setup.levelCounts()[v]));
        for (std::size_t l = 1; l < hints[v].levelPixelError.size(); ++l) {
            EXPECT_GE(hints[v].levelPixelError[l], hints[v].levelPixelError[l - 1]);
        }
    }
}

// Skipped objects are summed once; the variables' sum must give the whole scene's features.
TEST(TimeModelCost, SkippedObjectsCountAtTheirFixedLevel) {
    scenes::Scene scene = skipScene();
    renderer::Renderer renderer(scene, settings(96));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    ASSERT_GT(setup.skipSummary().outsideFrustum + setup.skipSummary().hidden, 0);
    auto model = [](const timemodel::FrameFeatures& f) {
        return 1e-3 * f[timemodel::Feature::kTriangles] + 1e-2 * f[timemodel::Feature::kDrawnObjects] +
               1e-6 * f[timemodel::Feature::kPixels] + 1e-1 * f[timemodel::Feature::kBoundingBoxes];
    };
    evaluation::TimeModelCost cost(setup, model);
    const std::vector<int> counts = setup.levelCounts();
    std::mt19937 random(4);
    for (int trial = 0; trial < 8; ++trial) {
        const optimizer::Combination combination = randomCombination(counts, random);
        const scenes::Combination levels = setup.toScene(combination);
        const double whole = model(timemodel::computeFrameFeatures(scene, levels, scene.views[0], 96, 96));
        EXPECT_NEAR(cost.predictMs(combination), whole, 1e-9 * whole);
        EXPECT_NEAR(cost.predictMs(combination), cost.predictSceneMs(levels), 1e-12 * whole);
        for (std::size_t v = 0; v < counts.size(); ++v) {
            optimizer::Combination moved = combination;
            moved[v] = (moved[v] + 1) % counts[v];
            EXPECT_NEAR(cost.deltaMs(combination, int(v), moved[v]), cost.predictMs(moved) - cost.predictMs(combination),
                        1e-12 * whole);
        }
    }
}

TEST(TimeModelCost, PredictsThroughTheFeatureTable) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(128));
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    // 1 µs per triangle: predictions are the drawn triangle counts in ms / 1000.
    evaluation::TimeModelCost cost(setup, [](const timemodel::FrameFeatures& f) {
        return f[timemodel::Feature::kTriangles] * 1e-3;
    });
    const optimizer::Combination fine(setup.levelCounts().size(), 0);
    const scenes::Combination levels = setup.toScene(fine);
    double triangles = 0;
    for (std::size_t o = 0; o < levels.size(); ++o) triangles += double(scene.objects[o].levels[levels[o]].stats.triangles);
    EXPECT_NEAR(cost.predictMs(fine), triangles * 1e-3, 1e-9);
    optimizer::Combination coarser = fine;
    coarser[0] = setup.levelCounts()[0] - 1;
    EXPECT_NEAR(cost.deltaMs(fine, 0, coarser[0]), cost.predictMs(coarser) - cost.predictMs(fine), 1e-9);
    EXPECT_LT(cost.deltaMs(fine, 0, coarser[0]), 0.0);
}

TEST(TimeModelCost, AllStepsAtOnceEqualEachStepAsked) {
    // deltasMs sums the combination's features once for every step asked; each answer must be
    // what deltaMs gives for that step alone, to the bit, and the difference of two predictions.
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, settings(96));
    std::mt19937 random(3);
    int compared = 0;
    for (const scenes::Camera& camera : scene.views) {
        evaluation::ViewSetup setup(scene, camera, renderer);
        const std::vector<int> counts = setup.levelCounts();
        if (counts.empty()) continue;
        // Not linear, so a wrong "before" would show: (triangles / 1000)^1.5 + vertices / 5000.
        evaluation::TimeModelCost cost(setup, [](const timemodel::FrameFeatures& f) {
            return std::pow(f[timemodel::Feature::kTriangles] * 1e-3, 1.5) + f[timemodel::Feature::kVertices] / 5000.0;
        });
        for (int k = 0; k < 20; ++k) {
            const optimizer::Combination combination = randomCombination(counts, random);
            const optimizer::Combination newLevels = randomCombination(counts, random);
            std::vector<double> deltas(counts.size(), -1.0);
            cost.deltasMs(combination, newLevels, deltas);
            for (std::size_t v = 0; v < counts.size(); ++v) {
                optimizer::Combination moved = combination;
                moved[v] = newLevels[v];
                const double expected = cost.predictMs(moved) - cost.predictMs(combination);
                EXPECT_EQ(deltas[v], cost.deltaMs(combination, int(v), newLevels[v])) << camera.name;
                EXPECT_NEAR(deltas[v], expected, 1e-9 * std::max(1.0, std::abs(cost.predictMs(combination))))
                    << camera.name;
                if (newLevels[v] == combination[v]) {
                    EXPECT_EQ(deltas[v], 0.0);
                }
                ++compared;
            }
        }
    }
    EXPECT_GE(compared, 100);
}
