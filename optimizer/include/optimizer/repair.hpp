// Feasibility repair: make an over-budget combination fit by coarsening levels; and the budget
// fill, which spends what a combination leaves unused by refining them.
//
// Rule (docs/optimizer.md, "Repair"): while predictMs > budgetMs, lower by one step (coarser,
// level + 1) the variable whose step loses least fitness per millisecond saved:
//   - with a surrogate table, the loss of a step is surrogateLoss[i][l+1] - surrogateLoss[i][l]
//     and the variable with the smallest loss / savedMs is lowered;
//   - without one, every step is assumed to lose the same fitness, so loss per millisecond is
//     proportional to 1 / savedMs and the variable whose step saves the most is lowered.
// savedMs = -Cost::deltaMs (asked for every variable at once: Cost::deltasMs). Steps that save nothing are taken only when no step saves time (a
// non-monotone cost model), the one with the largest savedMs first. Ties go to the lower
// variable index. Levels only ever increase, so repair ends after at most sum(levelCounts - 1)
// steps, and it ends feasible because validateProblem() checked that all-coarsest fits.
#pragma once

#include "optimizer/problem.hpp"

namespace lodopt::optimizer {

// Repairs `combination` in place and returns its predicted milliseconds (<= budgetMs).
// A feasible combination is left unchanged. `combination` must be valid and `problem` validated.
double repairToBudget(const Problem& problem, Combination& combination);

// Budget fill, the opposite of repair (the ADD phase of Chu & Beasley's repair operator for
// knapsack GAs, J. Heuristics 4, 1998): while some variable can be refined by one step
// (level - 1) within the budget, refine the one that gains most fitness per millisecond spent:
//   - with a surrogate table the gain is surrogateLoss[i][l] - surrogateLoss[i][l-1], and a
//     step whose gain is not > 0 is never taken;
//   - without one every step gains the same, so the cheapest step goes first.
// addedMs = Cost::deltaMs; a step that adds nothing goes first. Ties: the larger addedMs, then
// the lower index. A step that the delta lets in but the whole prediction puts over the budget
// (a non-additive model) is undone and that variable left alone. Levels only decrease, so it
// ends. Both ask every variable's step from one combination in one Cost::deltasMs call per
// step, so they make exactly these choices for any cost. `combination` must be valid and fit
// the budget; returns its predicted milliseconds (<= budgetMs).
double fillToBudget(const Problem& problem, Combination& combination);

}  // namespace lodopt::optimizer
