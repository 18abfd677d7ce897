#include "evaluation/search_view.hpp"

#include <chrono>

#include "optimizer/checked_evaluator.hpp"
#include "optimizer/mckp.hpp"

namespace lodopt::evaluation {

SearchView prepareSearchView(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer,
                             const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                             const timemodel::FeatureSet& readFeatures, const SearchViewSettings& settings) {
    SearchView view;
    view.setup = std::make_unique<ViewSetup>(scene, camera, renderer);
    const metrics::MetricParameters search = searchParameters(metrics);
    if (settings.path == EvaluationPath::Full) {
        view.evaluator = std::make_unique<FullRenderEvaluator>(*view.setup, renderer, search);
    } else {
        view.evaluator = std::make_unique<LayerEvaluator>(*view.setup, search, settings.threads,
                                                          DirtyRegions::ChangedPixels, settings.states);
    }
    view.cost = std::make_unique<TimeModelCost>(*view.setup, estimator, readFeatures);
    view.problem.levelCounts = view.setup->levelCounts();
    view.problem.evaluator = view.evaluator.get();
    view.problem.cost = view.cost.get();
    view.problem.budgetMs = settings.budgetMs;
    if (!view.problem.levelCounts.empty()) {
        view.problem.hints = computeHints(*view.setup);
        optimizer::CheckedEvaluator checked(view.problem);
        view.problem.surrogateLoss = optimizer::measureSurrogateLoss(view.problem, checked);
    }
    return view;
}

ViewAnswer optimizeView(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer,
                        const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                        const timemodel::FeatureSet& readFeatures, const SearchViewSettings& settings,
                        const optimizer::SearchOptions& search) {
    using Clock = std::chrono::steady_clock;
    ViewAnswer answer;
    const auto start = Clock::now();
    answer.view = prepareSearchView(scene, camera, renderer, metrics, estimator, readFeatures, settings);
    const auto searchStart = Clock::now();
    answer.result = optimizer::runSearch(answer.view.problem, search);
    answer.searchSeconds = std::chrono::duration<double>(Clock::now() - searchStart).count();
    answer.setupSeconds = std::chrono::duration<double>(searchStart - start).count();

    const ViewSetup& setup = *answer.view.setup;
    answer.levels = setup.toScene(answer.result.best);
    FullRenderEvaluator full(setup, renderer, metrics);
    answer.metrics = full.metricsOf(answer.result.best);
    answer.image = renderer.render(answer.levels, setup.camera());
    if (settings.judge) answer.judge = judgeFrame(answer.image, setup.reference(), *settings.judge);
    return answer;
}

}  // namespace lodopt::evaluation
