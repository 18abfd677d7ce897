// Rule-based baselines that choose levels from the per-variable hints alone, then fit the
// budget; each evaluates only its final combination. They throw ProblemError naming the
// variable when a hint they need is missing.
#pragma once

#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "optimizer/algorithm.hpp"

namespace lodopt::optimizer {

struct DistanceParameters {
    // Ascending distances d_1 < d_2 < ... (world units, > 0): level k is used when
    // d_k <= d < d_{k+1} (d_0 = 0), clamped to the variable's coarsest level. Empty: derived
    // per variable by splitting the hints' distance range [dMin, dMax] into levelCounts[i]
    // equal bands (all variables at one distance get level 0).
    std::vector<double> thresholds;
};

// Dong et al. 2015, eq. (4): one level per variable from hints[i].distance.
// Throws ProblemError when a distance is unknown or negative.
Combination distanceLevels(const Problem& problem, const DistanceParameters& parameters);

// Level by distance thresholds, then repairToBudget (repair.hpp). Needs hints[i].distance.
class DistanceHeuristic final : public Algorithm {
public:
    // Throws std::invalid_argument unless the thresholds are finite, > 0 and ascending.
    explicit DistanceHeuristic(DistanceParameters parameters = {});
    std::string_view name() const override { return "distance"; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    DistanceParameters mParameters;
};

// The view of an object in Dong et al. 2015, eq. (11).
struct ImportanceView {
    double distance = 0.0;          // d, >= 0
    double viewAngleRadians = 0.0;  // theta, [0, pi/2)
    double projectedArea = 1.0;     // s, > 0
};

struct ImportanceParameters {
    double alpha1 = 0.6;  // finite, >= 0, weight of the distance term
    double alpha2 = 0.4;  // finite, >= 0, weight of the area term (not both 0)
    // The benchmark object of eq. (12), whose importance is 1. Unset: the median denominator
    // of the problem's variables, so about half of them have I > 1.
    std::optional<ImportanceView> benchmark;
    DistanceParameters distance;  // the initial levels (eq. 4)
};

// alpha1 (1 + tan theta) d + alpha2 * 100 / s: the denominator of eq. (11)-(12).
double importanceDenominator(const ImportanceView& view, double alpha1, double alpha2);
// I = B / denominator(view), eq. (11); B = importanceDenominator(benchmark).
double importance(const ImportanceView& view, const ImportanceView& benchmark, double alpha1, double alpha2);

// Dong et al. 2015 §2.4, the importance-ordered scheduler: initial levels by distance
// thresholds; under budget, raise variables in decreasing importance, each as far toward level
// 0 as the budget allows (a variable whose next step does not fit is passed over); over budget,
// lower variables in increasing importance, each as far as needed, first those with I <= 1,
// and those with I > 1 only when the budget cannot be met otherwise.
// Needs hints[i].distance and .projectedArea (viewAngleRadians defaults to 0).
class ImportanceHeuristic final : public Algorithm {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit ImportanceHeuristic(ImportanceParameters parameters = {});
    std::string_view name() const override { return "importance"; }
    Result run(const Problem& problem, const Termination& termination) const override;

    // Importance of every variable, in variable order (throws ProblemError on missing hints).
    std::vector<double> importances(const Problem& problem) const;

private:
    ImportanceParameters mParameters;
};

struct ScreenSizeParameters {
    // > 0, pixels: without per-level coverage thresholds, the coarsest level whose projected
    // error (hints[i].levelPixelError) is within this tolerance is used.
    double pixelErrorTolerance = 1.0;
};

// What engines ship (Unreal/Unity screen size, glTF MSFT_screencoverage): variable i uses the
// first level k with hints[i].screenCoverage >= hints[i].levelScreenCoverage[k] (its coarsest
// when none), or, without thresholds, the coarsest level with levelPixelError <= tolerance.
// Throws ProblemError when a variable has neither, or no screenCoverage.
Combination screenSizeLevels(const Problem& problem, const ScreenSizeParameters& parameters);

// screenSizeLevels, then while over budget the variable smallest on screen that is not yet at
// its coarsest level is lowered one step (ties: lower index).
class ScreenSizeHeuristic final : public Algorithm {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit ScreenSizeHeuristic(ScreenSizeParameters parameters = {});
    std::string_view name() const override { return "screensize"; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    ScreenSizeParameters mParameters;
};

}  // namespace lodopt::optimizer
