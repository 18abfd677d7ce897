// lodopt optimizer: the search problem, kept apart from the algorithms (pagmo2 style).
//
// A problem is a box of discrete variables, one per searchable object: variable i takes a
// level in [0, levelCounts[i]), level 0 the finest. An Evaluator scores a combination (fused
// perceptual fitness in [0, 1], higher is better); a Cost predicts its render time in
// milliseconds. A combination is feasible when its predicted time is <= budgetMs. The
// algorithms only ever return feasible combinations; they see the scene through nothing but
// these two interfaces and the optional plain-number hints below, so this module depends on
// the C++ standard library alone.
//
// The evaluation module implements Evaluator (render, composite, compare with the reference)
// and Cost (the time model); tests implement them with formulas.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace lodopt::optimizer {

// One level per variable (object), in variable order; 0 is the finest level, higher is coarser.
using Combination = std::vector<int>;

// Bad problem data from outside (files, command lines, an evaluator's output): the message
// names the element, e.g. "levelCounts[2] = 0, must be >= 1".
class ProblemError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The budget is below the predicted time of the cheapest combination (every variable at its
// coarsest level), so no combination is feasible. The message states both figures.
class BudgetError : public ProblemError {
public:
    BudgetError(double budgetMs, double minimumMs);
    double budgetMs() const { return mBudgetMs; }
    double minimumMs() const { return mMinimumMs; }

private:
    double mBudgetMs;
    double mMinimumMs;
};

// The evaluator's verdict on one combination. Only `fitness` drives the search; the
// components are carried along for reports (e.g. ssim, boundary, information fidelities),
// named by Evaluator::componentNames(). Fixed size so a score never allocates.
struct Score {
    static constexpr std::size_t kMaxComponents = 6;
    double fitness = 0.0;  // fused fitness, [0, 1] by contract, higher is better; must be finite
    std::array<double, kMaxComponents> components{};  // the first componentCount are meaningful
    int componentCount = 0;                           // [0, kMaxComponents]
};

// Combination → Score. Implementations must be deterministic: the same combination gives the
// same score whatever the batch it comes in, its position in the batch, and the thread count.
class Evaluator {
public:
    virtual ~Evaluator() = default;

    // Scores one combination. `combination` has one valid level per variable (the optimizer's
    // CheckedEvaluator guarantees it).
    virtual Score evaluate(const Combination& combination) = 0;

    // Scores the candidates of one iteration: scores[k] for combinations[k]. The default loops
    // over evaluate(); an implementation may spread the batch over threads or render several
    // candidates at once. The candidates of one call are distinct.
    // `scores.size()` == `combinations.size()`.
    virtual void evaluateBatch(std::span<const Combination> combinations, std::span<Score> scores);

    // Names of the score components, in order (empty when the evaluator reports none).
    virtual std::vector<std::string> componentNames() const { return {}; }
};

// Combination → predicted render time. Implementations must be pure (same input, same
// output) and cheap: the algorithms call them for every candidate and during repair.
class Cost {
public:
    virtual ~Cost() = default;

    // Predicted milliseconds of render time, finite and >= 0.
    virtual double predictMs(const Combination& combination) const = 0;

    // predictMs(combination with `variable` at `newLevel`) - predictMs(combination), in
    // milliseconds (negative when the change saves time). The default copies the combination
    // and predicts twice; override it with an O(1) formula when the model is additive.
    // `variable` < combination.size(); `newLevel` a valid level of that variable.
    virtual double deltaMs(const Combination& combination, int variable, int newLevel) const;

    // Every variable's step from one combination at once: deltas[i] = deltaMs(combination, i,
    // newLevels[i]), exactly 0 where newLevels[i] == combination[i]. `newLevels` and `deltas`
    // have combination.size() entries. Repair, fill and the MCKP baseline ask this way, so a
    // cost that sums per-variable features sums them once per combination rather than once per
    // question. The default asks deltaMs per variable.
    virtual void deltasMs(const Combination& combination, std::span<const int> newLevels,
                          std::span<double> deltas) const;
};

// The simplest Cost: a fixed frame cost plus one figure per variable and level. Useful for
// tests and as the additive approximation of any model.
class AdditiveCost final : public Cost {
public:
    // `baseMs` >= 0, milliseconds every frame costs; `levelMs[i][l]` >= 0, milliseconds variable
    // i adds at level l. Throws ProblemError naming the first negative or non-finite entry.
    AdditiveCost(double baseMs, std::vector<std::vector<double>> levelMs);

    double predictMs(const Combination& combination) const override;
    double deltaMs(const Combination& combination, int variable, int newLevel) const override;
    void deltasMs(const Combination& combination, std::span<const int> newLevels,
                  std::span<double> deltas) const override;

    const std::vector<std::vector<double>>& levelMs() const { return mLevelMs; }

private:
    double mBaseMs;
    std::vector<std::vector<double>> mLevelMs;
};

// "Not known" for a hint: the heuristics that need the hint refuse to run without it.
inline constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
inline bool isKnown(double hint) {
    return !std::isnan(hint);
}

// What the baselines know about one variable at the current view, as plain numbers so that
// they run without geometry. Every field is optional (kUnknown or empty).
struct VariableHints {
    double distance = kUnknown;        // >= 0, world units from the camera to the object's centre
    double viewAngleRadians = 0.0;     // [0, pi/2), angle between view direction and the object
    double projectedArea = kUnknown;   // > 0, Dong et al. 2015's s (projected crown area); any
                                       // unit, the same for every variable and the benchmark
    double screenCoverage = kUnknown;  // >= 0, the object's height on screen / viewport height
    // One per level or empty: the screen-coverage threshold (fraction of viewport height) above
    // which the level is used, non-increasing from level 0 (glTF MSFT_screencoverage).
    std::vector<double> levelScreenCoverage;
    // One per level or empty: projected geometric error of the level at this view, in pixels,
    // >= 0 (0 for level 0).
    std::vector<double> levelPixelError;
    // One per level or empty: the level's measured surface deviation from level 0 (two-sided,
    // sampled; scenes::Level::geometricError), world units, >= 0 (0 for level 0). What the
    // engines' automatic rules (engine_rules.hpp) project to pixels.
    std::vector<double> levelDeviation;
    // > 0, world units: the radius of the object's bounding sphere (Unreal's auto screen size).
    double boundingRadius = kUnknown;
    // > 0: pixels one world unit spans at the object's nearest point at this view (the viewport
    // height over 2 d tan(fovY / 2), d the distance to the nearest point of its box, at least
    // the near plane).
    double pixelsPerWorldUnit = kUnknown;
};

// Everything an algorithm may know. The evaluator and cost are borrowed: they must outlive
// every run that uses the problem.
struct Problem {
    std::vector<int> levelCounts;    // levelCounts[i] >= 1 levels for variable i; at least 1 variable
    Evaluator* evaluator = nullptr;  // not null
    const Cost* cost = nullptr;      // not null
    // > 0, milliseconds of predicted render time; +infinity for no budget.
    double budgetMs = std::numeric_limits<double>::infinity();
    std::vector<VariableHints> hints;  // empty, or one per variable
    // Empty, or surrogateLoss[i][l] = fitness(reference) - fitness(reference with variable i
    // at level l), finite, one row per variable with levelCounts[i] entries (the additive
    // surrogate of the mckp baseline and of repair).
    std::vector<std::vector<double>> surrogateLoss;
};

// Throws ProblemError naming the first inconsistent element (level counts, hint or surrogate
// sizes, a NaN budget), then BudgetError when budgetMs < predictMs(all coarsest).
// `problem.evaluator` and `problem.cost` must not be null (asserted).
void validateProblem(const Problem& problem);

// Throws ProblemError unless `combination` has one valid level per variable; the message names
// the element ("combination[1] = 7, variable 1 has 5 levels").
void validateCombination(const Problem& problem, const Combination& combination);
void validateCombination(std::span<const int> levelCounts, const Combination& combination);

// Every variable at level 0: the reference.
Combination finestCombination(const Problem& problem);
// Every variable at its coarsest level: the cheapest combination the budget must admit.
Combination coarsestCombination(const Problem& problem);

// Number of combinations in the space, as a double (it overflows 64 bits past ~20 variables).
double combinationCount(std::span<const int> levelCounts);

// predictMs(combination) <= budgetMs.
bool isFeasible(const Problem& problem, const Combination& combination);

// "[0, 2, 1]" for messages and logs.
std::string formatCombination(const Combination& combination);

}  // namespace lodopt::optimizer
