// One view prepared for the search, as optimize, compare, tune and bench use it: the view's
// layers (ViewSetup), its evaluator (the fast path, or the full render to compare against), the
// time model's cost, and the problem with its hints and the surrogate loss table, measured once
// per view and shared by every algorithm (the mckp baseline's objective and the repair rule's
// "fitness lost per millisecond saved").
#pragma once

#include <memory>
#include <optional>

#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "optimizer/problem.hpp"
#include "optimizer/search.hpp"

namespace lodopt::evaluation {

enum class EvaluationPath { Fast, Full };

struct SearchViewSettings {
    EvaluationPath path = EvaluationPath::Fast;
    int threads = 1;                              // fast path: evaluation threads, >= 1
    int states = LayerEvaluator::kDefaultStates;  // fast path: evaluation states
    double budgetMs = 0.0;                        // > 0
    // optimizeView: the judge of the answer's image (ViewAnswer::judge); unset, not judged. The
    // search never reads it.
    std::optional<metrics::JudgeParameters> judge;
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

// One view searched, as `lodopt optimize` does it: prepareSearchView, optimizer::runSearch, then
// the answer's full metrics (raw entropies and precision/recall too, with the user's `metrics`)
// and its image through a full render, so the reported figures never rest on the layer
// approximation alone.
struct ViewAnswer {
    SearchView view;
    optimizer::Result result;
    scenes::Combination levels;     // the answer, one level per scene object
    metrics::MetricResult metrics;  // of the answer's full render
    renderer::Frame image;          // the answer's full render
    std::optional<metrics::JudgeResult> judge;  // `image` against the reference, with settings.judge
    double setupSeconds = 0.0;      // prepareSearchView's wall time
    double searchSeconds = 0.0;     // runSearch's wall time
};
ViewAnswer optimizeView(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer,
                        const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                        const timemodel::FeatureSet& readFeatures, const SearchViewSettings& settings,
                        const optimizer::SearchOptions& search);

}  // namespace lodopt::evaluation
