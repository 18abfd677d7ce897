// Tuning the scheduler's coefficients against the optimizer's answers
// (evaluation/scheduler_tuning.hpp): the scores it reports and the set it writes.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "evaluation/scheduler_tuning.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/profile.hpp"

using namespace lodopt;

TEST(SchedulerTuning, ScoresAgainstTheOptimizerAndWritesTheChosenSet) {
    const scenes::Scene scene = scenes::makeBuiltinScene("forest");
    renderer::RenderSettings settings;
    settings.width = settings.height = 96;
    renderer::Renderer renderer(scene, settings);
    const std::unique_ptr<timemodel::TimeModel> model =
        timemodel::modelFromProfile(timemodel::shippedProfile("forest"));
    const timemodel::TimeModel& fitted = *model;
    const evaluation::FrameTimeEstimator estimate = [&fitted](const timemodel::FrameFeatures& f) {
        return fitted.estimateMs(f);
    };
    const scheduler::SceneIndex index(scene, 96, 96, scheduler::FeatureMode::Bounds, 0, model->readFeatures());
    scheduler::SchedulerParameters parameters;
    parameters.budgetMs = 1.0;
    parameters.switchControl.enabled = false;
    scheduler::FrameScheduler frameScheduler(index, model->clone(), parameters);

    // Four views; the "optimizer's answer" is every searched object at its finest level, so
    // every fraction is at most 1 and the finest view scores exactly 1.
    std::vector<evaluation::TuningView> views(4);
    const metrics::MetricParameters metricParameters = evaluation::searchParameters({});
    for (std::size_t k = 0; k < views.size(); ++k) {
        evaluation::TuningView& view = views[k];
        view.camera = scene.views[k % scene.views.size()];
        view.heldOut = k == 3;
        view.fold = k == 3 ? -1 : int(k % 2);
        view.setup = std::make_unique<evaluation::ViewSetup>(scene, view.camera, renderer);
        view.evaluator = std::make_unique<evaluation::LayerEvaluator>(*view.setup, metricParameters);
        view.cost = std::make_unique<evaluation::TimeModelCost>(*view.setup, estimate, model->readFeatures());
        view.optimizerLevels = view.setup->toScene(optimizer::Combination(view.setup->levelCounts().size(), 0));
        view.optimizerFitness = view.evaluator->evaluate(view.setup->fromScene(view.optimizerLevels)).fitness;
    }
    const evaluation::SchedulerScore defaults =
        evaluation::scoreScheduler(views[0], frameScheduler, scheduler::SchedulerCoefficients{});
    EXPECT_GT(defaults.fraction, 0.0);
    EXPECT_LE(defaults.fraction, 1.0 + 1e-12);
    EXPECT_DOUBLE_EQ(defaults.fraction, defaults.fitness / views[0].optimizerFitness);
    EXPECT_GT(defaults.predictedMs, 0.0);

    evaluation::TuningSettings tuning;
    tuning.forms = {scheduler::ImportanceForm::Published, scheduler::ImportanceForm::Extended};
    tuning.scales = scheduler::measureTermScales(index, {views[0].camera, views[1].camera, views[2].camera});
    tuning.thresholdCount = std::max(1, index.maxLevelCount() - 1);
    tuning.search.maxEvaluations = 12;
    tuning.folds = 2;
    const evaluation::TuningOutcome outcome = evaluation::tuneSchedulerCoefficients(views, frameScheduler, tuning);
    ASSERT_EQ(outcome.forms.size(), 2u);
    EXPECT_TRUE(outcome.crossValidated);
    for (const evaluation::FormTuning& form : outcome.forms) {
        // The search starts at the defaults and only moves on a strict improvement.
        EXPECT_GE(form.search.bestValue, outcome.defaultTuningFraction);
        EXPECT_LE(form.search.evaluations, 12);
        EXPECT_FALSE(std::isnan(form.crossValidatedFraction));
    }
    const int expected = scheduler::firstBestAbove(
        outcome.defaultTuningFraction,
        {outcome.forms[0].crossValidatedFraction, outcome.forms[1].crossValidatedFraction});
    EXPECT_EQ(outcome.chosen, expected);
    if (outcome.chosen < 0) {
        EXPECT_EQ(outcome.writtenTuningFraction, outcome.defaultTuningFraction);
        EXPECT_EQ(outcome.written.importance.alpha1, scheduler::SchedulerCoefficients{}.importance.alpha1);
    } else {
        const evaluation::FormTuning& chosen = outcome.forms[std::size_t(outcome.chosen)];
        EXPECT_EQ(outcome.writtenTuningFraction, chosen.search.bestValue);
        EXPECT_EQ(outcome.writtenHeldOutFraction, chosen.heldOutFraction);
    }
    // The held-out view's score is what the written set gives there.
    EXPECT_EQ(outcome.writtenHeldOutFraction, evaluation::scoreScheduler(views[3], frameScheduler, outcome.written).fraction);
}
