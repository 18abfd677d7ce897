// The measurements behind `lodopt bench` (evaluation/benchmark.hpp) and one view searched as
// `lodopt optimize` does it (evaluation/search_view.hpp, optimizeView), on the harbor at 64x64.
#include "evaluation/benchmark.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "evaluation/search_view.hpp"
#include "metrics/metrics.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/profile.hpp"

using namespace lodopt;

namespace {

struct HarborView {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::RenderSettings settings = [] {
        renderer::RenderSettings s;
        s.width = s.height = 64;
        return s;
    }();
    renderer::Renderer renderer{scene, settings};
    timemodel::DeviceProfile profile = timemodel::shippedProfile("harbor");
    std::unique_ptr<timemodel::TimeModel> model = timemodel::modelFromProfile(profile);
    evaluation::FrameTimeEstimator estimate = [this](const timemodel::FrameFeatures& f) {
        return model->estimateMs(f);
    };
    metrics::MetricParameters metrics;

    // A budget midway between the all-coarsest and the all-finest prediction, as bench picks it.
    evaluation::SearchViewSettings viewSettings() {
        evaluation::SearchViewSettings settings;
        evaluation::SearchView probe = prepare(1e9);
        const std::vector<int>& counts = probe.problem.levelCounts;
        optimizer::Combination coarsest(counts.size());
        for (std::size_t i = 0; i < counts.size(); ++i) coarsest[i] = counts[i] - 1;
        const double low = probe.cost->predictMs(coarsest);
        const double high = probe.cost->predictMs(optimizer::Combination(counts.size(), 0));
        settings.budgetMs = 0.5 * (low + high);
        return settings;
    }
    evaluation::SearchView prepare(double budgetMs) {
        evaluation::SearchViewSettings settings;
        settings.budgetMs = budgetMs;
        return evaluation::prepareSearchView(scene, scene.views[0], renderer, metrics, estimate, model->readFeatures(),
                                             settings);
    }
};

}  // namespace

TEST(Benchmark, GridRunsEveryUnitOnceAndReusesFinishedRuns) {
    HarborView harbor;
    const evaluation::SearchView view = harbor.prepare(harbor.viewSettings().budgetMs);
    const std::vector<std::string> algorithms = {"gapso", "mckp"};
    const std::vector<std::int64_t> budgets = {10, 40};
    std::vector<evaluation::AlgorithmRun> made;
    const std::vector<evaluation::AlgorithmRun> first = evaluation::runAlgorithmGrid(
        view, {}, algorithms, budgets, 2, {}, [&](const evaluation::AlgorithmRun& run) { made.push_back(run); });
    // gapso: 2 budgets x 2 seeds; mckp (deterministic): 2 budgets x 1.
    ASSERT_EQ(first.size(), 6u);
    EXPECT_EQ(made.size(), 6u);
    for (const evaluation::AlgorithmRun& run : first) {
        EXPECT_LE(run.evaluations, run.evaluationBudget) << run.algorithm << " " << run.evaluationBudget;
        EXPECT_LE(run.predictedMs, view.problem.budgetMs);
        EXPECT_GT(run.fitness, 0.0);
    }

    // Restored from a checkpoint: only the missing run is made, the others are taken as saved.
    std::vector<evaluation::AlgorithmRun> finished = first;
    finished.erase(finished.begin() + 1);  // gapso, budget 10, seed 2
    made.clear();
    const std::vector<evaluation::AlgorithmRun> second = evaluation::runAlgorithmGrid(
        view, {}, algorithms, budgets, 2, finished, [&](const evaluation::AlgorithmRun& run) { made.push_back(run); });
    ASSERT_EQ(made.size(), 1u);
    EXPECT_EQ(made[0].algorithm, "gapso");
    EXPECT_EQ(made[0].evaluationBudget, 10);
    EXPECT_EQ(made[0].seed, 2u);
    ASSERT_EQ(second.size(), first.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        EXPECT_EQ(second[i].algorithm, first[i].algorithm);
        EXPECT_EQ(second[i].seed, first[i].seed);
        EXPECT_EQ(second[i].fitness, first[i].fitness) << "seeded runs are deterministic";
    }
    EXPECT_EQ(evaluation::findRun(second, "mckp", 40, 1), &second[5]);
    EXPECT_EQ(evaluation::findRun(second, "mckp", 40, 2), nullptr);

    // The harbor's space is small: the exhaustive optimum bounds every run, and gaps are >= 0.
    evaluation::BestKnown best = evaluation::searchBestKnown(view, 1e6);
    EXPECT_EQ(best.source, "exhaustive");
    EXPECT_GT(best.evaluations, 0);
    const double optimum = best.fitness;
    std::vector<evaluation::AlgorithmRun> runs = second;
    evaluation::applyBestKnown(best, runs);
    EXPECT_EQ(best.fitness, optimum);
    for (const evaluation::AlgorithmRun& run : runs) {
        EXPECT_GE(run.gap, 0.0);
        EXPECT_NEAR(run.gap, optimum - run.fitness, 1e-12);
        // The curve: the first point is the first iteration, the best rises along it to the result's.
        ASSERT_FALSE(run.improvements.empty());
        EXPECT_EQ(run.improvements.back().second, run.fitness);
        for (std::size_t k = 1; k < run.improvements.size(); ++k) {
            EXPECT_GT(run.improvements[k].second, run.improvements[k - 1].second);
            EXPECT_GE(run.improvements[k].first, run.improvements[k - 1].first);
        }
        // Near the best known exactly when the gap is within the tolerance, and no later than the run ended.
        EXPECT_EQ(run.evaluationsToNearBest >= 0, run.gap <= evaluation::kNearBestKnown) << run.algorithm;
        if (run.evaluationsToNearBest >= 0) {
            EXPECT_LE(run.evaluationsToNearBest, run.evaluations);
        }
    }
    // Above the limit: the best any run found.
    evaluation::BestKnown found = evaluation::searchBestKnown(view, 1.0);
    EXPECT_EQ(found.source, "best found");
    evaluation::applyBestKnown(found, runs);
    double bestRun = 0.0;
    for (const evaluation::AlgorithmRun& run : runs) bestRun = std::max(bestRun, run.fitness);
    EXPECT_EQ(found.fitness, bestRun);
}

TEST(Benchmark, FastPathAgreesWithTheFullRenderAndMetricsWithTheReference) {
    HarborView harbor;
    const evaluation::SearchView view = harbor.prepare(harbor.viewSettings().budgetMs);
    const std::vector<evaluation::EvalPathRow> paths =
        evaluation::measureEvaluationPaths(view, harbor.renderer, harbor.metrics, 2, 8, 3);
    // Per workload: full single, fast batch, fast single.
    ASSERT_EQ(paths.size(), 6u);
    for (const evaluation::EvalPathRow& row : paths) {
        EXPECT_EQ(row.candidates, 8);
        EXPECT_GT(row.evaluationsPerSecond, 0.0);
        if (row.path == "fast") {
            EXPECT_LE(row.maxAbsFitnessDiff, 1e-3) << row.workload << " " << row.mode;
            EXPECT_LE(row.meanAbsFitnessDiff, row.maxAbsFitnessDiff);
        } else {
            EXPECT_TRUE(std::isnan(row.maxAbsFitnessDiff));
        }
    }
    const std::vector<evaluation::MetricsRow> metricsRows =
        evaluation::measureMetrics(view, harbor.renderer, harbor.metrics, 0.01);
    ASSERT_EQ(metricsRows.size(), 7u);
    for (const evaluation::MetricsRow& row : metricsRows) {
        EXPECT_EQ(row.width, 64);
        EXPECT_GT(row.calls, 0);
        EXPECT_GT(row.microsecondsPerCall, 0.0);
        if (!row.reference.empty()) {
            EXPECT_LE(row.absDeviation, 1e-9) << row.function;
        }
    }
}

TEST(Benchmark, TimeModelRowsCarryTheProfileAndThisViewsFrames) {
    HarborView harbor;
    const evaluation::SearchView view = harbor.prepare(harbor.viewSettings().budgetMs);
    const std::vector<evaluation::TimeModelRow> rows =
        evaluation::measureTimeModels(view, harbor.renderer, harbor.profile, 3, 2, 7);
    std::size_t fitted = 0;
    for (const timemodel::ModelResult& model : harbor.profile.models) fitted += model.fitted ? 1 : 0;
    ASSERT_GT(fitted, 0u);
    std::size_t timedNow = 0;
    for (const evaluation::TimeModelRow& row : rows) {
        if (row.source != "this view, timed now") continue;
        ++timedNow;
        EXPECT_EQ(row.samples, 3u);
        EXPECT_GE(row.mean, 0.0);
        EXPECT_LE(row.median, row.max);
    }
    EXPECT_EQ(timedNow, fitted);
    EXPECT_EQ(rows.front().source, "calibration held-out");
    EXPECT_EQ(rows.front().samples, harbor.profile.models.front().heldOutErrors.count);
}

TEST(Benchmark, OptimizeViewReportsTheFullRenderOfItsAnswer) {
    HarborView harbor;
    optimizer::SearchOptions search;
    search.seed = 4;
    search.termination.maxIterations = 10;
    const evaluation::ViewAnswer answer =
        evaluation::optimizeView(harbor.scene, harbor.scene.views[0], harbor.renderer, harbor.metrics, harbor.estimate,
                                 harbor.model->readFeatures(), harbor.viewSettings(), search);
    EXPECT_LE(answer.result.predictedMs, answer.view.problem.budgetMs);
    EXPECT_EQ(answer.levels, answer.view.setup->toScene(answer.result.best));
    const renderer::Frame rendered = harbor.renderer.render(answer.levels, harbor.scene.views[0]);
    EXPECT_EQ(answer.image.rgba, rendered.rgba);
    const renderer::Frame& reference = answer.view.setup->reference();
    const metrics::MetricResult full =
        metrics::evaluate(metrics::makeImageView(rendered.rgba.data(), 64, 64, 4),
                          metrics::makeImageView(reference.rgba.data(), 64, 64, 4), harbor.metrics);
    EXPECT_EQ(answer.metrics.fitness, full.fitness);
    EXPECT_EQ(answer.metrics.precision, full.precision);
    EXPECT_NEAR(answer.metrics.fitness, answer.result.bestScore.fitness, 1e-3);
    EXPECT_GE(answer.setupSeconds, 0.0);
    EXPECT_GT(answer.searchSeconds, 0.0);
}
