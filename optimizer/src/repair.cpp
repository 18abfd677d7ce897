// Feasibility repair; the rule is documented in repair.hpp and docs/optimizer.md.
#include "optimizer/repair.hpp"

#include <cassert>
#include <cmath>
#include <limits>
#include <vector>

namespace lodopt::optimizer {

double repairToBudget(const Problem& problem, Combination& combination) {
    assert(combination.size() == problem.levelCounts.size());
    const Cost& cost = *problem.cost;
    const bool haveSurrogate = !problem.surrogateLoss.empty();
    double ms = cost.predictMs(combination);
    while (true) {
        if (!std::isfinite(ms)) {
            throw ProblemError("the cost model predicted " + std::to_string(ms) + " ms for combination " +
                               formatCombination(combination));
        }
        if (ms <= problem.budgetMs) return ms;

        // Best step that saves time, by the rule; and the fallback for a non-monotone model.
        int bestSaving = -1;
        double bestKey = 0.0;
        double bestSaved = 0.0;
        int bestAny = -1;
        double bestAnySaved = 0.0;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            const int level = combination[i];
            if (level + 1 >= problem.levelCounts[i]) continue;
            const double saved = -cost.deltaMs(combination, static_cast<int>(i), level + 1);
            if (bestAny < 0 || saved > bestAnySaved) {
                bestAny = static_cast<int>(i);
                bestAnySaved = saved;
            }
            if (!(saved > 0.0)) continue;
            // Smaller key = less fitness lost per millisecond saved.
            const double key = haveSurrogate ? (problem.surrogateLoss[i][static_cast<std::size_t>(level) + 1] -
                                                problem.surrogateLoss[i][static_cast<std::size_t>(level)]) /
                                                   saved
                                             : -saved;
            if (bestSaving < 0 || key < bestKey || (key == bestKey && saved > bestSaved)) {
                bestSaving = static_cast<int>(i);
                bestKey = key;
                bestSaved = saved;
            }
        }
        const int variable = bestSaving >= 0 ? bestSaving : bestAny;
        // validateProblem() guarantees all-coarsest fits, so an over-budget combination always
        // has a variable left to lower.
        assert(variable >= 0 && "repairToBudget: over budget at all-coarsest; was the problem validated?");
        if (variable < 0) {
            throw BudgetError(problem.budgetMs, ms);
        }
        ++combination[static_cast<std::size_t>(variable)];
        ms = cost.predictMs(combination);
    }
}

double fillToBudget(const Problem& problem, Combination& combination) {
    assert(combination.size() == problem.levelCounts.size());
    const Cost& cost = *problem.cost;
    const bool haveSurrogate = !problem.surrogateLoss.empty();
    double ms = cost.predictMs(combination);
    assert(ms <= problem.budgetMs);
    // A step the additive prediction let in but the whole prediction did not is not retried.
    std::vector<bool> blocked(combination.size(), false);
    while (true) {
        int best = -1;
        double bestKey = 0.0;
        double bestAdded = 0.0;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            const int level = combination[i];
            if (level == 0 || blocked[i]) continue;
            const double added = cost.deltaMs(combination, static_cast<int>(i), level - 1);
            if (!(ms + added <= problem.budgetMs)) continue;
            const double gain = haveSurrogate ? problem.surrogateLoss[i][static_cast<std::size_t>(level)] -
                                                    problem.surrogateLoss[i][static_cast<std::size_t>(level) - 1]
                                              : 1.0;
            if (!(gain > 0.0)) continue;
            // Larger key = more fitness gained per millisecond spent; a free step first; on a
            // tie the larger step, as repair takes the larger saving.
            const double key = added > 0.0 ? gain / added : std::numeric_limits<double>::infinity();
            if (best < 0 || key > bestKey || (key == bestKey && added > bestAdded)) {
                best = static_cast<int>(i);
                bestKey = key;
                bestAdded = added;
            }
        }
        if (best < 0) return ms;
        --combination[static_cast<std::size_t>(best)];
        const double next = cost.predictMs(combination);
        if (!(next <= problem.budgetMs)) {
            ++combination[static_cast<std::size_t>(best)];
            blocked[static_cast<std::size_t>(best)] = true;
            continue;
        }
        ms = next;
    }
}

}  // namespace lodopt::optimizer
