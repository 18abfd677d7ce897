// The fast path's dependency analysis knows what is always hidden: where an object covers a
// pixel at every level it can take, whatever lies behind all of it there cannot change the
// pixel, so the windows there do not depend on the hidden object's level (docs/optimizer.md
// "What is always hidden").
#include <gtest/gtest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "evaluation/evaluation.hpp"
#include "scenes/builtin.hpp"
#include "scenes/mesh_builder.hpp"
#include "box_objects.hpp"

using namespace lodopt;
using lodopt::test_scenes::boxObject;

namespace {

// Camera at z = 10 looking at the origin. `front` (two levels, the coarser a little smaller)
// stands before `back`, which is wider, so `back` shows left and right of it.
scenes::Scene panelScene() {
    scenes::Scene scene;
    scene.name = "panels";
    scene.materials.push_back(scenes::diffuseMaterial("red", {0.8f, 0.2f, 0.2f}));
    scene.materials.push_back(scenes::diffuseMaterial("grey", {0.5f, 0.5f, 0.5f}));
    scene.objects.push_back(boxObject("front", {0, 0, 0}, {{2.0f, 2.0f, 0.2f}, {1.9f, 1.9f, 0.2f}}, 0));
    scene.objects.push_back(boxObject("back", {0, 0, -3}, {{3.2f, 1.0f, 0.2f}, {3.0f, 0.9f, 0.2f}}, 1));
    scenes::Camera camera;
    camera.name = "front";
    camera.position = {0, 0, 10};
    camera.target = {0, 0, 0};
    camera.nearPlane = 0.1f;
    camera.farPlane = 100.0f;
    scene.views.push_back(camera);
    scenes::updateStatistics(scene);
    return scene;
}

// The panel scene's one view prepared at 96 x 96.
struct PanelView {
    scenes::Scene scene = panelScene();
    renderer::Renderer renderer{scene, renderer::RenderSettings{.width = 96, .height = 96}};
    evaluation::ViewSetup setup{scene, scene.views[0], renderer};
};

// Per pixel: 1 where some option level of scene object `object` covers it, 2 where all do.
std::vector<int> coverage(const evaluation::ViewSetup& setup, int object) {
    const int width = setup.width(), height = setup.height();
    std::vector<int> counts(std::size_t(width) * height, 0);
    const std::vector<int>& levels = setup.objects()[object].optionLevels;
    for (int level : levels) {
        const renderer::Layer& layer = setup.layer(object, level);
        for (int y = layer.rect.y0; y < layer.rect.y1; ++y) {
            for (int x = layer.rect.x0; x < layer.rect.x1; ++x) {
                const float depth = layer.depth[std::size_t(y - layer.rect.y0) * layer.rect.width() + (x - layer.rect.x0)];
                if (depth < 1.0f) ++counts[std::size_t(y) * width + x];
            }
        }
    }
    for (int& count : counts) count = count == 0 ? 0 : count == int(levels.size()) ? 2 : 1;
    return counts;
}

// SSIM windows (window x window pixels, top-left at every valid position) holding a pixel
// where `a` holds and one where `b` holds.
std::uint64_t windowsWithBoth(const std::vector<bool>& a, const std::vector<bool>& b, int width, int height, int window) {
    std::uint64_t count = 0;
    for (int y = 0; y + window <= height; ++y) {
        for (int x = 0; x + window <= width; ++x) {
            bool hasA = false, hasB = false;
            for (int dy = 0; dy < window; ++dy) {
                for (int dx = 0; dx < window; ++dx) {
                    const std::size_t p = std::size_t(y + dy) * width + (x + dx);
                    hasA = hasA || a[p];
                    hasB = hasB || b[p];
                }
            }
            count += hasA && hasB;
        }
    }
    return count;
}

// The fast path with each caching: window groups, owned windows, and neither (the reference).
struct Evaluators {
    evaluation::LayerEvaluator grouped, owned, uncached;
    Evaluators(const evaluation::ViewSetup& setup, const metrics::MetricParameters& parameters)
        : grouped(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                  evaluation::LayerEvaluator::kDefaultStates, evaluation::PartCaching::Groups),
          owned(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                evaluation::LayerEvaluator::kDefaultStates, evaluation::PartCaching::On),
          uncached(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                   evaluation::LayerEvaluator::kDefaultStates, evaluation::PartCaching::Off) {}
};

}  // namespace

TEST(Occlusion, WindowsBehindWhatAlwaysCoversThemDependOnTheFrontObjectAlone) {
    PanelView panels;
    const evaluation::ViewSetup& setup = panels.setup;
    ASSERT_EQ(setup.variableObjects(), (std::vector<int>{0, 1}));
    ASSERT_EQ(setup.levelCounts(), (std::vector<int>{2, 2}));
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    const int window = metrics::RegionScorer(metrics::makeImageView(setup.reference().rgba.data(), setup.width(),
                                                                    setup.height(), 4),
                                             parameters)
                           .ssimMapSize()
                           .window;

    // `front` lies nearer than `back` on every pixel, so `back` shows only where some level
    // of `front` leaves the pixel uncovered.
    const std::vector<int> front = coverage(setup, 0), back = coverage(setup, 1);
    std::vector<bool> frontShows(front.size()), backCovers(front.size()), backShows(front.size());
    for (std::size_t p = 0; p < front.size(); ++p) {
        frontShows[p] = front[p] > 0;
        backCovers[p] = back[p] > 0;
        backShows[p] = back[p] > 0 && front[p] < 2;
    }
    const std::uint64_t expected = windowsWithBoth(frontShows, backShows, setup.width(), setup.height(), window);
    const std::uint64_t coveredByBoth = windowsWithBoth(frontShows, backCovers, setup.width(), setup.height(), window);
    ASSERT_GT(expected, 0u);
    ASSERT_LT(2 * expected, coveredByBoth);  // the scene hides most of `back` behind `front`

    Evaluators evaluators(setup, parameters);
    auto& [grouped, owned, uncached] = evaluators;
    // Every combination, twice over in an order that changes one or both objects per step.
    for (const optimizer::Combination& combination :
         {optimizer::Combination{1, 0}, {1, 1}, {0, 1}, {0, 0}, {1, 1}, {0, 0}, {0, 1}, {1, 0}}) {
        const optimizer::Score score = uncached.evaluate(combination);
        EXPECT_EQ(grouped.evaluate(combination).fitness, score.fitness);
        EXPECT_EQ(owned.evaluate(combination).fitness, score.fitness);
    }
    EXPECT_EQ(grouped.groupCacheStats().multiObjectSsimWindows, expected);
    // The owned windows see the same: those of `front`'s always-covered middle are its own.
    const metrics::PartCacheStats parts = owned.partCacheStats();
    const std::uint64_t ssimWindows =
        std::uint64_t(setup.width() - window + 1) * std::uint64_t(setup.height() - window + 1);
    EXPECT_GT(parts.ownedSsimWindows, 0u);
    EXPECT_EQ(parts.liveSsimWindows, expected);
    EXPECT_LE(parts.ownedSsimWindows + parts.liveSsimWindows, ssimWindows);
}

TEST(Occlusion, CityStreetScoresMatchFromScratchWithEveryCaching) {
    // Buildings hide much of what stands behind them: the case the analysis changes most.
    scenes::Scene scene = scenes::loadScene("city");
    renderer::RenderSettings settings;
    settings.width = settings.height = 96;
    renderer::Renderer renderer(scene, settings);
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    for (const char* viewName : {"street", "skyline"}) {
        const scenes::Camera* camera = nullptr;
        for (const scenes::Camera& view : scene.views) {
            if (view.name == viewName) camera = &view;
        }
        ASSERT_NE(camera, nullptr) << viewName;
        evaluation::ViewSetup setup(scene, *camera, renderer);
        const std::vector<int> counts = setup.levelCounts();
        ASSERT_GE(counts.size(), 10u) << viewName;
        Evaluators evaluators(setup, parameters);
        auto& [grouped, owned, uncached] = evaluators;
        std::mt19937 random(17);
        optimizer::Combination current(counts.size(), 0);
        for (int step = 0; step < 60; ++step) {
            // 1–3 objects per step, and every 20th step half of them.
            const int changes = step % 20 == 19 ? int(counts.size()) / 2 : 1 + int(random() % 3);
            for (int c = 0; c < changes; ++c) {
                const std::size_t v = random() % counts.size();
                current[v] = int(random() % counts[v]);
            }
            const std::string what = std::string(viewName) + " step " + std::to_string(step);
            const optimizer::Score expected = uncached.evaluate(current);
            EXPECT_EQ(grouped.evaluate(current).fitness, expected.fitness) << what;
            EXPECT_EQ(owned.evaluate(current).fitness, expected.fitness) << what;
            if (step % 15 == 0) {
                const scenes::Combination levels = setup.toScene(current);
                std::vector<const renderer::Layer*> layers;
                for (std::size_t o = 0; o < levels.size(); ++o) layers.push_back(&setup.layer(int(o), levels[o]));
                renderer::Frame fresh;
                renderer::composite(layers, setup.width(), setup.height(), setup.clearColor(), fresh);
                const metrics::MetricResult scratch =
                    metrics::evaluate(metrics::makeImageView(fresh.rgba.data(), fresh.width, fresh.height, 4),
                                      metrics::makeImageView(setup.reference().rgba.data(), setup.width(),
                                                             setup.height(), 4),
                                      parameters);
                EXPECT_EQ(evaluation::toScore(scratch).fitness, expected.fitness) << what;
            }
        }
        EXPECT_GT(grouped.groupCacheStats().hits, 0u) << viewName;
    }
}

TEST(AutoCaching, LevelStepPixelsCountWhatALevelChangeTouches) {
    // Each panel's coarser level is the same flat face a little smaller and centred on the
    // same point: its pixels are a subset of the finer level's, in the same color, so a level
    // step touches exactly the pixels the finer level covers and the coarser does not.
    PanelView panels;
    const evaluation::ViewSetup& setup = panels.setup;
    ASSERT_EQ(setup.levelCounts(), (std::vector<int>{2, 2}));
    double expected = 0.0;
    for (int object : {0, 1}) {
        const renderer::Layer& fine = setup.layer(object, 0);
        const renderer::Layer& coarse = setup.layer(object, 1);
        ASSERT_GT(fine.coveredPixels, coarse.coveredPixels);
        expected += double(fine.coveredPixels - coarse.coveredPixels) / 2.0;
    }
    EXPECT_GT(expected, 0.0);
    EXPECT_DOUBLE_EQ(evaluation::meanLevelStepPixels(setup), expected);

    // The automatic choice follows the rule stated with kMinStepPixelsPerGroup.
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    evaluation::LayerEvaluator grouped(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                       evaluation::LayerEvaluator::kDefaultStates, evaluation::PartCaching::Groups);
    evaluation::LayerEvaluator automatic(setup, parameters);
    const double groupsPerObject = grouped.groupCacheStats().groups / 2.0;
    const bool groups = expected >= evaluation::LayerEvaluator::kMinStepPixelsPerGroup * groupsPerObject;
    EXPECT_EQ(automatic.groupCacheStats().groups > 0, groups);
    EXPECT_EQ(automatic.partCacheStats().parts > 0, !groups);
}
