// Exact multiple-choice knapsack (MCKP) on the additive surrogate (docs/method.md §6).
//
// The LOD selection problem is an MCKP when both fitness and cost are additive over variables:
// pick one level per variable to minimise sum_i loss[i][l_i] subject to
// sum_i cost[i][l_i] <= capacity. The surrogate loss is problem.surrogateLoss (or measured by
// measureSurrogateLoss); the cost of variable i at level l is the Cost interface evaluated one
// variable at a time from the all-coarsest base: cost[i][l] = deltaMs(coarsest, i, l), with
// capacity = budgetMs - predictMs(coarsest).
//
// Solver: dynamic programming over the capacity discretised into `buckets` equal steps, costs
// rounded up to whole steps, O(variables * levels * buckets) time (100 x 6 x 10000 is a few
// milliseconds) and 2 * variables * (buckets + 1) bytes of choices. Exactness: the answer is the
// optimum of the surrogate problem when every cost (after subtracting each variable's cheapest
// level) is a whole multiple of the step; otherwise it is the optimum with costs rounded up,
// which is always feasible under the additive model but may miss solutions that need the last
// (variables * step) milliseconds of capacity. On equal loss the recurrence keeps the finer
// level, so the answer is deterministic.
// The true Cost is then checked; if it is not additive and the answer is over budget, it is
// repaired (repair.hpp). Only the final combination is evaluated.
#pragma once

#include <span>
#include <string_view>
#include <vector>

#include "optimizer/algorithm.hpp"
#include "optimizer/checked_evaluator.hpp"

namespace lodopt::optimizer {

struct MckpParameters {
    int buckets = 10000;  // >= 1, capacity discretisation steps
};

// Solves the MCKP above. `loss[i]` and `costMs[i]` have one finite entry per level of variable
// i (costs may be negative); `capacityMs` finite (may be +infinity: every variable then takes
// its least-loss level). Returns one level per variable, or an empty combination when even the
// cheapest choice exceeds the capacity.
Combination solveMckp(std::span<const std::vector<double>> loss, std::span<const std::vector<double>> costMs,
                      double capacityMs, int buckets);

// The additive surrogate by measurement: loss[i][l] = fitness(finest) - fitness(finest with
// variable i at l), from sum(levelCounts - 1) + 1 evaluations in one batch. Throws
// ProblemError when `evaluator` has fewer evaluations left than that.
std::vector<std::vector<double>> measureSurrogateLoss(const Problem& problem, CheckedEvaluator& evaluator);

// Number of evaluations measureSurrogateLoss needs (at most; cached ones are free).
std::int64_t surrogateEvaluations(std::span<const int> levelCounts);

class Mckp final : public Algorithm {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit Mckp(MckpParameters parameters = {});
    std::string_view name() const override { return "mckp"; }
    // Uses problem.surrogateLoss, or measures it first (counted in the result's evaluations).
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    MckpParameters mParameters;
};

}  // namespace lodopt::optimizer
