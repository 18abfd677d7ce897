// Viewpoint sweeps: the optimizer's answer at many viewpoints (`lodopt sweep`), one view at a
// time, and a model of how a work queue spreads such views over ranks.
//
// A view's outcome depends only on the scene, its camera and the settings (the search seed is
// the same for every view), never on which process or rank ran it or in what order, so a sweep
// split over ranks, shards or interrupted runs merges into the same table.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "evaluation/search_view.hpp"

namespace lodopt::evaluation {

struct SweepViewOutcome {
    // False when even every object at its coarsest level is predicted over the budget: the
    // answer is then that combination (what is drawn when nothing fits), predictedMs its time.
    bool feasible = true;
    scenes::Combination levels;       // the answer, one level per scene object
    double fitness = 0.0;             // of the answer's full render, the user's metric weights
    double predictedMs = 0.0;         // the time model's prediction for the answer
    // The judge's distance (butteraugli p-norm) of the answer's image, with settings.judge.
    std::optional<double> judgeDistance;
    std::vector<double> screenSizes;  // per scene object: scenes::screenSize of its level 0
    int searchedObjects = 0;
    // The scene objects the search chose for (the view's variables), ascending; the others were
    // out of the frustum, below a pixel or hidden, and sit at their coarsest level.
    std::vector<int> searched;
    std::int64_t evaluations = 0;
    double setupSeconds = 0.0;   // wall time preparing the view (layers, surrogate table)
    double searchSeconds = 0.0;  // wall time of the search and the answer's full render
};

// optimizeView, kept to what a sweep records; a view whose budget cannot be met is recorded as
// infeasible rather than thrown (one such view must not end a sweep of thousands).
SweepViewOutcome sweepView(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer,
                           const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                           const timemodel::FeatureSet& readFeatures, const SearchViewSettings& settings,
                           const optimizer::SearchOptions& search);

// A work queue replayed: views are handed out in index order, each to the rank that becomes free
// first (ties: the lower rank), after every rank spent `startSeconds` (scene load) once; each
// view costs viewSeconds[k] plus `perViewOverheadSeconds` (taking it from the queue, writing its
// file); rank 0 then merges for `mergeSeconds`.
struct QueueSimulation {
    int ranks = 1;
    double makespanSeconds = 0.0;  // first start to the merge's end
    double workSeconds = 0.0;      // the views' own seconds, summed
    // Parallel efficiency T1 / (ranks * Tp): the one-rank makespan (one scene load, every view
    // and its overhead, the merge) over ranks times this makespan. 1 at one rank; below 1 by
    // what the extra scene loads, the idle tail (the last views) and the serial merge cost.
    double efficiency = 0.0;
    std::vector<double> idleSeconds;  // per rank: makespan minus its busy time
};
// ranks >= 1; every time finite and >= 0.
QueueSimulation simulateWorkQueue(std::span<const double> viewSeconds, int ranks, double startSeconds,
                                  double perViewOverheadSeconds, double mergeSeconds);

}  // namespace lodopt::evaluation
