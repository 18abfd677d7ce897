#include "evaluation/scheduler_tuning.hpp"

namespace lodopt::evaluation {

namespace {

// Mean fraction over the views `keep` accepts (0 with none).
template <class Keep>
double meanFractionOver(std::vector<TuningView>& views, scheduler::FrameScheduler& frameScheduler,
                        const scheduler::SchedulerCoefficients& coefficients, Keep keep) {
    double sum = 0.0;
    int count = 0;
    for (TuningView& view : views) {
        if (!keep(view)) continue;
        sum += scoreScheduler(view, frameScheduler, coefficients).fraction;
        ++count;
    }
    return count > 0 ? sum / count : 0.0;
}

double meanFraction(std::vector<TuningView>& views, bool heldOut, scheduler::FrameScheduler& frameScheduler,
                    const scheduler::SchedulerCoefficients& coefficients) {
    return meanFractionOver(views, frameScheduler, coefficients,
                            [heldOut](const TuningView& view) { return view.heldOut == heldOut; });
}

// The compass search from the published defaults, maximising the mean fraction over the views
// `keep` accepts.
template <class Keep>
scheduler::PatternSearchResult searchOver(std::vector<TuningView>& views, scheduler::FrameScheduler& frameScheduler,
                                          const scheduler::TuningSpace& space,
                                          const scheduler::PatternSearchOptions& searchOptions, Keep keep) {
    auto objective = [&](const std::vector<double>& x) {
        return meanFractionOver(views, frameScheduler, space.coefficientsAt(x), keep);
    };
    return scheduler::patternSearch(objective, space.pointOf(scheduler::SchedulerCoefficients{}), space.lower(),
                                    space.upper(), space.steps(), searchOptions);
}

// Each fold of the tuning views scored with the coefficients searched on the other folds; the
// mean over all tuning views.
double crossValidatedFraction(std::vector<TuningView>& views, scheduler::FrameScheduler& frameScheduler,
                              const scheduler::TuningSpace& space, const scheduler::PatternSearchOptions& searchOptions,
                              int folds) {
    double sum = 0.0;
    int count = 0;
    for (int f = 0; f < folds; ++f) {
        const scheduler::PatternSearchResult search =
            searchOver(views, frameScheduler, space, searchOptions,
                       [f](const TuningView& v) { return !v.heldOut && v.fold != f; });
        const scheduler::SchedulerCoefficients fitted = space.coefficientsAt(search.best);
        for (TuningView& view : views) {
            if (view.heldOut || view.fold != f) continue;
            sum += scoreScheduler(view, frameScheduler, fitted).fraction;
            ++count;
        }
    }
    return count > 0 ? sum / count : NAN;
}

}  // namespace

SchedulerScore scoreScheduler(TuningView& view, scheduler::FrameScheduler& frameScheduler,
                              const scheduler::SchedulerCoefficients& coefficients) {
    frameScheduler.setCoefficients(coefficients);
    frameScheduler.reset();
    const scheduler::FrameDecision& decision = frameScheduler.decide(view.camera, 0.0);
    const optimizer::Combination combination = view.setup->fromScene(decision.levels);
    auto it = view.scored.find(combination);
    if (it == view.scored.end()) it = view.scored.emplace(combination, view.evaluator->evaluate(combination).fitness).first;
    SchedulerScore score;
    score.fitness = it->second;
    score.predictedMs = view.cost->predictSceneMs(decision.levels);
    score.fraction = view.optimizerFitness > 0.0 ? it->second / view.optimizerFitness : 0.0;
    return score;
}

TuningOutcome tuneSchedulerCoefficients(std::vector<TuningView>& views, scheduler::FrameScheduler& frameScheduler,
                                        const TuningSettings& settings) {
    TuningOutcome outcome;
    outcome.crossValidated = settings.folds >= 2;
    for (scheduler::ImportanceForm form : settings.forms) {
        const scheduler::TuningSpace space(form, settings.scales, settings.thresholdCount);
        FormTuning tuning;
        tuning.form = form;
        tuning.search = searchOver(views, frameScheduler, space, settings.search,
                                   [](const TuningView& v) { return !v.heldOut; });
        tuning.coefficients = space.coefficientsAt(tuning.search.best);
        tuning.heldOutFraction = meanFraction(views, true, frameScheduler, tuning.coefficients);
        if (outcome.crossValidated) {
            tuning.crossValidatedFraction =
                crossValidatedFraction(views, frameScheduler, space, settings.search, settings.folds);
        }
        outcome.forms.push_back(tuning);
    }
    const scheduler::SchedulerCoefficients defaults;
    outcome.defaultTuningFraction = meanFraction(views, false, frameScheduler, defaults);
    outcome.defaultHeldOutFraction = meanFraction(views, true, frameScheduler, defaults);
    // With cross-validation: the defaults unless a tuned form scores better out of fold (nothing
    // is fitted for the defaults, so their out-of-fold score is their tuning score). Without: the
    // form with the better tuning score.
    std::vector<double> scores;
    for (const FormTuning& f : outcome.forms) {
        scores.push_back(outcome.crossValidated ? f.crossValidatedFraction : f.search.bestValue);
    }
    outcome.chosen = scheduler::firstBestAbove(outcome.crossValidated ? outcome.defaultTuningFraction : -INFINITY, scores);
    if (outcome.chosen < 0) {
        outcome.written = defaults;
        outcome.writtenTuningFraction = outcome.defaultTuningFraction;
        outcome.writtenHeldOutFraction = outcome.defaultHeldOutFraction;
    } else {
        const FormTuning& f = outcome.forms[std::size_t(outcome.chosen)];
        outcome.written = f.coefficients;
        outcome.writtenTuningFraction = f.search.bestValue;
        outcome.writtenHeldOutFraction = f.heldOutFraction;
    }
    return outcome;
}

}  // namespace lodopt::evaluation
