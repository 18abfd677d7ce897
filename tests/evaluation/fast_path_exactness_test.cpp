// The fast path re-scores only around changed pixels; its scores after random walks of level
// changes must equal, to the bit, a from-scratch evaluation of a fresh composite, the earlier
// whole-rectangle fast path, and (within the composite's tolerance) the full render path.
#include <gtest/gtest.h>

#include <random>

#include "evaluation/evaluation.hpp"
#include "scenes/builtin.hpp"
#include "walk_helpers.hpp"

using namespace lodopt;
using namespace lodopt::test_walks;


TEST(FastPathExactness, RandomWalksOnForestMatchFromScratchScoresToTheBit) {
    scenes::Scene scene = scenes::loadScene("forest");
    renderer::RenderSettings settings;
    settings.width = settings.height = 128;
    renderer::Renderer renderer(scene, settings);
    metrics::MetricParameters parameters;
    for (const scenes::Camera& camera : {scene.views[0], scene.views[2]}) {  // dense, edge
        evaluation::ViewSetup setup(scene, camera, renderer);
        const std::vector<int> counts = setup.levelCounts();
        ASSERT_GE(counts.size(), 5u) << camera.name;
        evaluation::LayerEvaluator fast(setup, parameters);
        evaluation::LayerEvaluator bounds(setup, parameters, 1, evaluation::DirtyRegions::ObjectBounds);
        evaluation::FullRenderEvaluator full(setup, renderer, parameters);
        double worstFull = 0.0;
        const std::vector<optimizer::Combination> walk = randomWalk(counts, 120, 21);
        for (std::size_t k = 0; k < walk.size(); ++k) {
            const std::string what = camera.name + " step " + std::to_string(k);
            const optimizer::Score score = fast.evaluate(walk[k]);
            const renderer::Frame expected = freshComposite(setup, walk[k]);
            ASSERT_EQ(fast.imageOf(walk[k]).rgba, expected.rgba) << what;
            expectSameScore(score, evaluation::toScore(metrics::evaluate(viewOf(expected), viewOf(setup.reference()), parameters)),
                            what + " vs from scratch");
            expectSameScore(score, bounds.evaluate(walk[k]), what + " vs whole rectangles");
            if (k % 10 == 0) {
                const double difference = std::abs(score.fitness - full.evaluate(walk[k]).fitness);
                worstFull = std::max(worstFull, difference);
                EXPECT_LT(difference, 1e-3) << what << " vs full render";
            }
        }
        std::cout << camera.name << ": max |fast - full render| = " << worstFull << "\n";
    }
}

TEST(FastPathExactness, ThreadedBatchesMatchTheSerialWalk) {
    scenes::Scene scene = scenes::loadScene("forest");
    renderer::RenderSettings settings;
    settings.width = settings.height = 96;
    renderer::Renderer renderer(scene, settings);
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    metrics::MetricParameters parameters;
    const std::vector<optimizer::Combination> walk = randomWalk(setup.levelCounts(), 60, 5);
    evaluation::LayerEvaluator serial(setup, parameters, 1);
    evaluation::LayerEvaluator threaded(setup, parameters, 3);
    std::vector<optimizer::Score> batch(walk.size());
    threaded.evaluateBatch(walk, batch);
    for (std::size_t k = 0; k < walk.size(); ++k) expectSameScore(serial.evaluate(walk[k]), batch[k], "step " + std::to_string(k));
}

TEST(FastPathExactness, OwnedWindowCacheChangesNoBitOnEveryHarborViewAndTheSparseForest) {
    // The owned-window cache (PartCaching::On, the default) against the fast path without it
    // and against from-scratch scores, on views where most windows are owned by one object.
    renderer::RenderSettings settings;
    settings.width = settings.height = 128;
    metrics::MetricParameters parameters;
    for (const char* sceneName : {"harbor", "forest"}) {
        scenes::Scene scene = scenes::loadScene(sceneName);
        renderer::Renderer renderer(scene, settings);
        for (const scenes::Camera& camera : scene.views) {
            if (std::string(sceneName) == "forest" && camera.name != "sparse") continue;
            evaluation::ViewSetup setup(scene, camera, renderer);
            const std::vector<int> counts = setup.levelCounts();
            ASSERT_GE(counts.size(), 2u) << camera.name;
            evaluation::LayerEvaluator cached(setup, parameters);
            evaluation::LayerEvaluator uncached(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                                evaluation::LayerEvaluator::kDefaultStates,
                                                evaluation::PartCaching::Off);
            const std::vector<optimizer::Combination> walk = randomWalk(counts, 60, 8);
            for (std::size_t k = 0; k < walk.size(); ++k) {
                const std::string what = std::string(sceneName) + "/" + camera.name + " step " + std::to_string(k);
                const optimizer::Score score = cached.evaluate(walk[k]);
                expectSameScore(score, uncached.evaluate(walk[k]), what + " vs without the cache");
                if (k % 6 == 0) {
                    const renderer::Frame expected = freshComposite(setup, walk[k]);
                    expectSameScore(score,
                                    evaluation::toScore(metrics::evaluate(viewOf(expected), viewOf(setup.reference()), parameters)),
                                    what + " vs from scratch");
                }
            }
            const metrics::PartCacheStats stats = cached.partCacheStats();
            EXPECT_EQ(stats.parts, int(counts.size())) << camera.name;
            EXPECT_GT(stats.ownedSsimWindows, 0u) << camera.name;
            EXPECT_GT(stats.filledEntries, std::uint64_t(counts.size())) << camera.name;
            EXPECT_EQ(uncached.partCacheStats().parts, 0) << camera.name;
        }
    }
}

TEST(FastPathExactness, WindowGroupsMatchFromScratchScoresToTheBit) {
    // The window groups (PartCaching::Groups, the default for a search's parameters) against a
    // from-scratch evaluation of a fresh composite, the owned-window path, the same groups with
    // no memory to keep scores in (every group scored anew), threaded batches, and the full render.
    renderer::RenderSettings settings;
    settings.width = settings.height = 128;
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    using evaluation::LayerEvaluator;
    for (const char* sceneName : {"harbor", "forest"}) {
        scenes::Scene scene = scenes::loadScene(sceneName);
        renderer::Renderer renderer(scene, settings);
        for (const scenes::Camera& camera : scene.views) {
            if (std::string(sceneName) == "forest" && camera.name != "dense" && camera.name != "sparse") continue;
            evaluation::ViewSetup setup(scene, camera, renderer);
            const std::vector<int> counts = setup.levelCounts();
            ASSERT_GE(counts.size(), 2u) << camera.name;
            LayerEvaluator grouped(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                   LayerEvaluator::kDefaultStates, evaluation::PartCaching::Groups);
            LayerEvaluator automatic(setup, parameters);
            LayerEvaluator owned(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                 LayerEvaluator::kDefaultStates, evaluation::PartCaching::On);
            LayerEvaluator unkept(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                  LayerEvaluator::kDefaultStates, evaluation::PartCaching::Groups, 0);
            LayerEvaluator threaded(setup, parameters, 3, evaluation::DirtyRegions::ChangedPixels,
                                    LayerEvaluator::kDefaultStates, evaluation::PartCaching::Groups);
            // Memory for a few scores only: kept and unkept scores follow each other in a group.
            const std::size_t tightBytes = 16 * 1024;
            LayerEvaluator tight(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                 LayerEvaluator::kDefaultStates, evaluation::PartCaching::Groups, tightBytes);
            evaluation::FullRenderEvaluator full(setup, renderer, parameters);
            const std::vector<optimizer::Combination> walk = randomWalk(counts, 80, 13);
            std::vector<optimizer::Score> batch(walk.size());
            threaded.evaluateBatch(walk, batch);
            for (std::size_t k = 0; k < walk.size(); ++k) {
                const std::string what = std::string(sceneName) + "/" + camera.name + " step " + std::to_string(k);
                const optimizer::Score score = grouped.evaluate(walk[k]);
                expectSameScore(score, owned.evaluate(walk[k]), what + " vs owned windows");
                expectSameScore(score, unkept.evaluate(walk[k]), what + " vs nothing kept");
                expectSameScore(score, tight.evaluate(walk[k]), what + " vs little kept");
                expectSameScore(score, batch[k], what + " vs threaded batch");
                expectSameScore(score, automatic.evaluate(walk[k]), what + " vs automatic choice");
                if (k % 8 == 0) {
                    const renderer::Frame expected = freshComposite(setup, walk[k]);
                    ASSERT_EQ(grouped.imageOf(walk[k]).rgba, expected.rgba) << what;
                    expectSameScore(score, evaluation::toScore(metrics::evaluate(viewOf(expected), viewOf(setup.reference()), parameters)),
                                    what + " vs from scratch");
                    EXPECT_LT(std::abs(score.fitness - full.evaluate(walk[k]).fitness), 1e-3) << what << " vs full render";
                }
            }
            const evaluation::GroupCacheStats stats = grouped.groupCacheStats();
            EXPECT_GT(stats.groups, int(counts.size())) << camera.name;  // one per object at least, and the empty set
            EXPECT_GE(stats.largestGroup, 1) << camera.name;
            EXPECT_GT(stats.ssimWindows, stats.multiObjectSsimWindows) << camera.name;
            EXPECT_GT(stats.hits, 0u) << camera.name;
            EXPECT_GT(stats.entries, std::uint64_t(stats.groups)) << camera.name;
            EXPECT_EQ(unkept.groupCacheStats().entries, 0u) << camera.name;
            EXPECT_GT(tight.groupCacheStats().entries, 0u) << camera.name;
            EXPECT_LT(tight.groupCacheStats().entries, stats.entries) << camera.name;
            EXPECT_LE(tight.groupCacheStats().bytes, tightBytes) << camera.name;
            EXPECT_EQ(owned.groupCacheStats().groups, 0) << camera.name;
            // Auto: groups where a level step changes enough pixels per group of each object.
            const bool fewGroups = evaluation::meanLevelStepPixels(setup) >=
                                   LayerEvaluator::kMinStepPixelsPerGroup * stats.groups / double(counts.size());
            EXPECT_EQ(automatic.groupCacheStats().groups > 0, fewGroups) << camera.name;
            EXPECT_EQ(automatic.partCacheStats().parts > 0, !fewGroups) << camera.name;
            if (camera.name == "dense") {
                EXPECT_GT(stats.multiObjectSsimWindows, 0u);
                EXPECT_GE(stats.largestGroup, 3);
            }
        }
    }
}

TEST(FastPathExactness, PrecisionRecallParametersKeepTheOwnedWindows) {
    // Precision/recall is not a sum of window scores: asked for it, the evaluator keeps the
    // owned-window path (no groups) and still reports it.
    scenes::Scene scene = scenes::loadScene("harbor");
    renderer::RenderSettings settings;
    settings.width = settings.height = 64;
    renderer::Renderer renderer(scene, settings);
    evaluation::ViewSetup setup(scene, scene.views[0], renderer);
    evaluation::LayerEvaluator evaluator(setup, metrics::MetricParameters{});
    const optimizer::Score score = evaluator.evaluate(optimizer::Combination(setup.levelCounts().size(), 1));
    EXPECT_EQ(score.componentCount, 5);
    EXPECT_EQ(evaluator.groupCacheStats().groups, 0);
    EXPECT_GT(evaluator.partCacheStats().parts, 0);
}
