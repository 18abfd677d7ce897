// Tuning the scheduler's coefficients: the search space and a deterministic derivative-free
// search. The objective (how close the scheduler's choices come to the optimizer's on some
// views) is the caller's: `lodopt tune` scores with the evaluation module, which the scheduler
// may not depend on.
//
// Search space (all coordinates logarithmic, each with bounds and an initial step):
//   area_share     log of α2·S_area / (α1·S_dist): the area term's weight against the distance
//                  term, both measured at their typical size S (the median of the term over the
//                  tuning views' visible objects), so one step means the same in every scene;
//   pixels_share   log of α3·S_pixels / (α1·S_dist)   (extended form only);
//   center_share   log of α4·S_center / (α1·S_dist)   (extended form only);
//   first_threshold, threshold_ratio   log t1 and log r of geometric thresholds t_k = t1 r^(k-1);
//   benchmark_scale  log of the median-benchmark scale (which objects count as I > 1).
// The α are reported normalised to sum 1, the published convention (0.6 + 0.4); their overall
// scale never matters because I = B / D with B a denominator too.
//
// Pattern (compass) search: from the start, try each coordinate ± its step (the order of the
// coordinates shuffled per sweep by SplitMix64(seed)), move to the first strict improvement;
// after a sweep without one, halve every step; stop at the evaluation budget or when every
// step is below 1/64 of its initial value. Deterministic for a seed and a deterministic
// objective. Only strict improvements move, so a plateau keeps the start.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scenes/scene.hpp"
#include "scheduler/scene_index.hpp"
#include "scheduler/scheduler.hpp"

namespace lodopt::scheduler {

enum class ImportanceForm { Published, Extended };
// "published", "extended".
const char* toString(ImportanceForm form);

// Typical (median) size of each importance term over visible objects, each > 0.
struct TermScales {
    double distance = 1.0;
    double area = 1.0;
    double pixels = 1.0;
    double center = 1.0;
};
// Medians over every object visible from any of `cameras` (terms of importance.hpp); a term that
// is 0 everywhere gets 1.
TermScales measureTermScales(const SceneIndex& index, const std::vector<scenes::Camera>& cameras);

class TuningSpace {
public:
    // `thresholdCount` >= 1 thresholds in the geometric family.
    TuningSpace(ImportanceForm form, TermScales scales, int thresholdCount);

    int dimension() const { return int(mNames.size()); }
    const std::vector<std::string>& names() const { return mNames; }
    const std::vector<double>& lower() const { return mLower; }
    const std::vector<double>& upper() const { return mUpper; }
    const std::vector<double>& steps() const { return mSteps; }

    // The point closest to `coefficients` (α ratios, the first threshold, the mean ratio of
    // consecutive thresholds, the benchmark scale), clamped to the bounds. Extended shares
    // that are 0 start at their lower bound.
    std::vector<double> pointOf(const SchedulerCoefficients& coefficients) const;
    // The coefficients at `x` (dimension() values). Median benchmark, relative thresholds.
    SchedulerCoefficients coefficientsAt(const std::vector<double>& x) const;

private:
    ImportanceForm mForm;
    TermScales mScales;
    int mThresholdCount;
    std::vector<std::string> mNames;
    std::vector<double> mLower, mUpper, mSteps;
};

struct PatternSearchOptions {
    int maxEvaluations = 200;  // >= 1, objective calls including the start
    std::uint64_t seed = 1;
};

struct PatternSearchResult {
    std::vector<double> best;
    double bestValue = 0.0;
    int evaluations = 0;
    std::vector<double> bestByEvaluation;  // best value after each call (the search's curve)
};

// Maximises `objective` from `start` within [lower, upper] (equal sizes, start inside,
// steps > 0). The objective must return a finite value.
PatternSearchResult patternSearch(const std::function<double(const std::vector<double>&)>& objective,
                                  std::vector<double> start, const std::vector<double>& lower,
                                  const std::vector<double>& upper, std::vector<double> steps,
                                  const PatternSearchOptions& options);

// ---- Which views tune on, which are held out, which coefficient set is written ----------
// The selection policy of `lodopt tune` (docs/scheduler.md "Tuning"), apart from scoring.

// Which of `count` views a tuning run holds out (1 <= holdout < count): one in each run of
// count / holdout views, at a position that steps back by one from run to run, so that views
// sampled in turn around V named views are not all held out around the same one when the
// run length is a multiple of V.
std::vector<bool> heldOutViews(int count, int holdout);
// Cross-validation folds of a tuning run: fold k % folds for the k-th view not held out (in
// list order, so that each fold spreads along a path), -1 for held-out views; folds >= 1.
std::vector<int> tuningFolds(const std::vector<bool>& heldOut, int folds);
// The index of the first best score that beats `floor` and every earlier score by more than
// `margin`, -1 when none beats `floor` (a NaN never does): ties keep the earlier, simpler set.
// `lodopt tune` writes the form it picks among the forms' tuning scores (floor -infinity) or, with
// cross-validation, among their out-of-fold scores over the defaults' (-1: the defaults).
int firstBestAbove(double floor, const std::vector<double>& scores, double margin = 1e-12);

}  // namespace lodopt::scheduler
