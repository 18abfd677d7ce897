// Per-object screen-size switch thresholds, the rule engines use to pick a discrete LOD: level k
// while the object's screen size s is below t_(k-1) and at least t_k, that is the first k with
// s >= t_k, and the coarsest level when s is below every threshold. Screen size is
// scenes::screenSize (bounding-sphere diameter over the view height); thresholds are
// non-increasing, t_0 >= t_1 >= ... >= t_(L-2), one fewer than the levels (the coarsest level
// is never culled).
//
// Fitting them to an optimizer's choices (what `lodopt thresholds` runs per object): samples are
// (screen size, the level the optimizer chose, a weight), one per view that shows the object.
// The rule makes the level a non-increasing step function of screen size, so the best
// thresholds are the isotonic (monotone) fit of the chosen levels under a weighted absolute
// level error: minimise sum_j w_j |rule(s_j) - k_j|. It is solved exactly by dynamic programming
// over the samples sorted by decreasing screen size (equal sizes share a level): cost[g][k] =
// min over k' <= k of cost[g-1][k'] + sum over group g of w_j |k - k_j|, O(samples x levels).
// Each threshold is placed at the geometric mean of the two screen sizes its level change falls
// between (scale-free: screen sizes span decades), outside the samples when a level is never
// chosen: twice the largest size for levels finer than any chosen, half the smallest for
// coarser ones.
#pragma once

#include <span>
#include <vector>

namespace lodopt::scheduler {

struct ThresholdSample {
    double screenSize = 0.0;  // > 0, finite
    int level = 0;            // the optimizer's choice, [0, levelCount)
    double weight = 1.0;      // >= 0, finite: what a wrong level costs here, per level of error
};

struct ThresholdFit {
    std::vector<double> thresholds;  // levelCount - 1 values, non-increasing, > 0
    double cost = 0.0;               // sum of w_j |rule(s_j) - k_j| at the fitted thresholds
    double totalWeight = 0.0;        // sum of w_j
    double agreement = 0.0;          // weighted share of samples where the rule gives k_j
};

// The level the rule gives at screen size `screenSize` (see above).
int levelForScreenSize(std::span<const double> thresholds, double screenSize);

// Throws std::invalid_argument for levelCount < 1, or a sample with a non-finite or non-positive
// screen size, a level out of range, or a negative or non-finite weight. No samples: thresholds
// 1, 1/2, 1/4, ... (nothing to fit).
ThresholdFit fitScreenThresholds(std::span<const ThresholdSample> samples, int levelCount);

// The same fit with each sample's disagreements priced per level: levelCost[k] is what drawing
// level k at that screen size costs (any finite values; only differences between levels matter).
// Minimises the summed cost of the levels the rule draws; the level error above is the case
// levelCost[k] = weight |k - level|. `agreement` is the unweighted share of samples whose
// cheapest level the rule draws, `totalWeight` the sample count. Throws std::invalid_argument
// for levelCount < 1, or a sample with a non-finite or non-positive screen size, or without
// levelCount finite costs. No samples: the halving chain.
struct PricedSample {
    double screenSize = 0.0;
    std::vector<double> levelCost;
};
ThresholdFit fitScreenThresholdsToCosts(std::span<const PricedSample> samples, int levelCount);

}  // namespace lodopt::scheduler
