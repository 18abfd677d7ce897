// Fitting the real-time scheduler's coefficients to the optimizer: what `lodopt tune` runs once
// every view has the optimizer's answer.
//
// A view's score is the fitness of the scheduler's choice there as a fraction of the optimizer's
// answer's, both scored by the view's own evaluator (the scheduler's scene levels mapped by
// ViewSetup::fromScene), so the two compare like with like. Per importance form, a compass
// search (scheduler/tuning.hpp) from the published defaults maximises the mean fraction over the
// tuning views; optionally k-fold cross-validation over the tuning views scores each form with
// coefficients searched on the other folds. The written set is the form with the best tuning
// score, or with cross-validation the defaults unless a form beats them out of fold
// (scheduler::firstBestAbove: ties keep the simpler set). The held-out views are reported and
// play no part in any choice.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "scheduler/scheduler.hpp"
#include "scheduler/tuning.hpp"

namespace lodopt::evaluation {

// One tuning or held-out view and the optimizer's answer there.
struct TuningView {
    scenes::Camera camera;
    bool heldOut = false;
    int fold = -1;  // cross-validation fold of a tuning view (scheduler::tuningFolds)
    std::unique_ptr<ViewSetup> setup;
    std::unique_ptr<optimizer::Evaluator> evaluator;
    std::unique_ptr<TimeModelCost> cost;
    scenes::Combination optimizerLevels;
    double optimizerFitness = 0.0;  // by `evaluator`
    double optimizerSeconds = 0.0;
    std::map<optimizer::Combination, double> scored;  // fitness of the scheduler's choices so far
};

// The scheduler's choice on one view with some coefficients.
struct SchedulerScore {
    double fraction = 0.0;  // fitness / the optimizer's (0 when the optimizer's is not > 0)
    double fitness = 0.0;
    double predictedMs = 0.0;  // the view's exact-feature cost of the choice
};
// Decides the view's frame afresh (switch-control state reset) with `coefficients`.
SchedulerScore scoreScheduler(TuningView& view, scheduler::FrameScheduler& frameScheduler,
                              const scheduler::SchedulerCoefficients& coefficients);

struct TuningSettings {
    std::vector<scheduler::ImportanceForm> forms;  // searched, in this order
    scheduler::TermScales scales;
    int thresholdCount = 1;
    scheduler::PatternSearchOptions search;
    int folds = 0;  // >= 2: cross-validate over the tuning views and choose by it
};

struct FormTuning {
    scheduler::ImportanceForm form = scheduler::ImportanceForm::Published;
    scheduler::SchedulerCoefficients coefficients;
    scheduler::PatternSearchResult search;  // bestValue: the mean tuning fraction
    double heldOutFraction = 0.0;
    double crossValidatedFraction = NAN;  // mean out-of-fold fraction over the tuning views
};

struct TuningOutcome {
    std::vector<FormTuning> forms;
    double defaultTuningFraction = 0.0;
    double defaultHeldOutFraction = 0.0;
    bool crossValidated = false;
    int chosen = -1;  // index into `forms`; -1: the published defaults are written
    scheduler::SchedulerCoefficients written;
    double writtenTuningFraction = 0.0;
    double writtenHeldOutFraction = 0.0;
};

// `frameScheduler`'s coefficients are changed along the way. Views need setup, evaluator and
// cost, and at least one tuning view.
TuningOutcome tuneSchedulerCoefficients(std::vector<TuningView>& views, scheduler::FrameScheduler& frameScheduler,
                                        const TuningSettings& settings);

}  // namespace lodopt::evaluation
