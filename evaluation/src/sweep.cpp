#include "evaluation/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>
#include <utility>

#include "scenes/viewpoints.hpp"

namespace lodopt::evaluation {

SweepViewOutcome sweepView(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer,
                           const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                           const timemodel::FeatureSet& readFeatures, const SearchViewSettings& settings,
                           const optimizer::SearchOptions& search) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    SweepViewOutcome outcome;
    try {
        ViewAnswer answer = optimizeView(scene, camera, renderer, metrics, estimator, readFeatures, settings, search);
        outcome.levels = std::move(answer.levels);
        outcome.fitness = answer.metrics.fitness;
        outcome.predictedMs = answer.result.predictedMs;
        if (answer.judge) outcome.judgeDistance = answer.judge->distance;
        outcome.searchedObjects = int(answer.view.problem.levelCounts.size());
        outcome.searched = answer.view.setup->variableObjects();
        outcome.evaluations = answer.result.evaluations;
        outcome.setupSeconds = answer.setupSeconds;
        // The search and the answer's full render and scoring.
        outcome.searchSeconds = std::chrono::duration<double>(Clock::now() - start).count() - answer.setupSeconds;
    } catch (const optimizer::BudgetError& error) {
        const ViewSetup setup(scene, camera, renderer);
        outcome.feasible = false;
        outcome.levels = scenes::coarsestCombination(scene);
        outcome.predictedMs = error.minimumMs();
        outcome.searchedObjects = int(setup.variableObjects().size());
        outcome.searched = setup.variableObjects();
        FullRenderEvaluator full(setup, renderer, metrics);
        outcome.fitness = full.metricsOf(setup.fromScene(outcome.levels)).fitness;
        if (settings.judge) {
            const renderer::Frame image = renderer.render(outcome.levels, camera);
            outcome.judgeDistance = judgeFrame(image, setup.reference(), *settings.judge).distance;
        }
        outcome.setupSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    }
    outcome.screenSizes.reserve(scene.objects.size());
    for (const scenes::Object& object : scene.objects) {
        outcome.screenSizes.push_back(scenes::screenSize(scenes::worldBounds(object, 0), camera));
    }
    return outcome;
}

QueueSimulation simulateWorkQueue(std::span<const double> viewSeconds, int ranks, double startSeconds,
                                  double perViewOverheadSeconds, double mergeSeconds) {
    auto usable = [](double seconds) { return std::isfinite(seconds) && seconds >= 0.0; };
    if (ranks < 1) throw std::invalid_argument("simulateWorkQueue: ranks must be >= 1");
    if (!usable(startSeconds) || !usable(perViewOverheadSeconds) || !usable(mergeSeconds)) {
        throw std::invalid_argument("simulateWorkQueue: times must be finite and >= 0");
    }
    QueueSimulation simulation;
    simulation.ranks = ranks;
    std::vector<double> busy(std::size_t(ranks), 0.0);
    // (time the rank becomes free, rank): the earliest free rank takes the next view.
    using Slot = std::pair<double, int>;
    std::priority_queue<Slot, std::vector<Slot>, std::greater<>> free;
    for (int rank = 0; rank < ranks; ++rank) free.emplace(startSeconds, rank);
    double lastEnd = startSeconds;
    for (double seconds : viewSeconds) {
        if (!usable(seconds)) throw std::invalid_argument("simulateWorkQueue: a view time is not finite and >= 0");
        const auto [at, rank] = free.top();
        free.pop();
        const double cost = seconds + perViewOverheadSeconds;
        busy[std::size_t(rank)] += cost;
        simulation.workSeconds += seconds;
        lastEnd = std::max(lastEnd, at + cost);
        free.emplace(at + cost, rank);
    }
    simulation.makespanSeconds = lastEnd + mergeSeconds;
    simulation.idleSeconds.resize(std::size_t(ranks));
    for (int rank = 0; rank < ranks; ++rank) {
        simulation.idleSeconds[std::size_t(rank)] = simulation.makespanSeconds - busy[std::size_t(rank)];
    }
    const double oneRank = startSeconds + simulation.workSeconds +
                           perViewOverheadSeconds * double(viewSeconds.size()) + mergeSeconds;
    simulation.efficiency =
        simulation.makespanSeconds > 0.0 ? oneRank / (double(ranks) * simulation.makespanSeconds) : 1.0;
    return simulation;
}

}  // namespace lodopt::evaluation
