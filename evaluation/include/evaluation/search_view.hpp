// One view prepared for the search, as optimize, compare, tune and bench use it: the view's
// layers (ViewSetup), its evaluator (the fast path, or the full render to compare against), the
// time model's cost, and the problem with its hints and the surrogate loss table, measured once
// per view and shared by every algorithm (the mckp baseline's objective and the repair rule's
// "fitness lost per millisecond saved").
#pragma once

#include <memory>

#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "optimizer/problem.hpp"

namespace lodopt::evaluation {

enum class EvaluationPath { Fast, Full };

struct SearchViewSettings {
    EvaluationPath path = EvaluationPath::Fast;
    int threads = 1;                                      // fast path: evaluation threads, >= 1
    int states = LayerEvaluator::kDefaultStates;          // fast path: evaluation states
    double budgetMs = 0.0;                                // > 0
};

struct SearchView {
    std::unique_ptr<ViewSetup> setup;
    std::unique_ptr<optimizer::Evaluator> evaluator;
    std::unique_ptr<TimeModelCost> cost;
    optimizer::Problem problem;  // points at `evaluator` and `cost`
};

// `scene`, `renderer` (drawing `scene`) outlive the view. `metrics` are the user's parameters:
// the search scores fitness only (searchParameters). `estimator` reads only `readFeatures`.
SearchView prepareSearchView(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer,
                             const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                             const timemodel::FeatureSet& readFeatures, const SearchViewSettings& settings);

}  // namespace lodopt::evaluation
