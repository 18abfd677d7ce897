// Feasibility repair; the rule is documented in repair.hpp and docs/optimizer.md.
#include "optimizer/repair.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace lodopt::optimizer {

namespace {

// Surrogate fitness lost by the step of `variable` from level `finer` to finer + 1.
double surrogateStepLoss(const Problem& problem, std::size_t variable, std::size_t finer) {
    return problem.surrogateLoss[variable][finer + 1] - problem.surrogateLoss[variable][finer];
}

}  // namespace

double repairToBudget(const Problem& problem, Combination& combination) {
    assert(combination.size() == problem.levelCounts.size());
    const Cost& cost = *problem.cost;
    const bool haveSurrogate = !problem.surrogateLoss.empty();
    double ms = cost.predictMs(combination);
    Combination coarser;
    std::vector<double> deltas;
    while (true) {
        if (!std::isfinite(ms)) {
            throw ProblemError("the cost model predicted " + std::to_string(ms) + " ms for combination " +
                               formatCombination(combination));
        }
        if (ms <= problem.budgetMs) return ms;

        // Every variable's step one level coarser, asked at once (the coarsest stay put).
        coarser.resize(combination.size());
        deltas.resize(combination.size());
        for (std::size_t i = 0; i < combination.size(); ++i) {
            coarser[i] = combination[i] + 1 < problem.levelCounts[i] ? combination[i] + 1 : combination[i];
        }
        cost.deltasMs(combination, coarser, deltas);

        // Best step that saves time, by the rule; and the fallback for a non-monotone model.
        int bestSaving = -1;
        double bestKey = 0.0;
        double bestSaved = 0.0;
        int bestAny = -1;
        double bestAnySaved = 0.0;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            if (coarser[i] == combination[i]) continue;
            const double saved = -deltas[i];
            if (bestAny < 0 || saved > bestAnySaved) {
                bestAny = static_cast<int>(i);
                bestAnySaved = saved;
            }
            if (!(saved > 0.0)) continue;
            // Smaller key = less fitness lost per millisecond saved.
            const double key =
                haveSurrogate ? surrogateStepLoss(problem, i, static_cast<std::size_t>(combination[i])) / saved : -saved;
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

// One round per step: every variable's step one level finer asked at once (Cost::deltasMs),
// the best that fits taken. O(variables) per step for a cost that sums per-variable features.
double fillToBudget(const Problem& problem, Combination& combination) {
    assert(combination.size() == problem.levelCounts.size());
    const Cost& cost = *problem.cost;
    const bool haveSurrogate = !problem.surrogateLoss.empty();
    double ms = cost.predictMs(combination);
    assert(ms <= problem.budgetMs);

    std::vector<std::uint8_t> leftAlone(combination.size(), 0);  // a step the whole prediction refused
    std::vector<double> gains(combination.size());
    Combination finer(combination.size());
    std::vector<double> deltas(combination.size());
    while (true) {
        bool anyStep = false;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            const auto level = static_cast<std::size_t>(combination[i]);
            finer[i] = combination[i];
            if (level == 0 || leftAlone[i]) continue;
            gains[i] = haveSurrogate ? surrogateStepLoss(problem, i, level - 1) : 1.0;
            if (!(gains[i] > 0.0)) continue;
            finer[i] = combination[i] - 1;
            anyStep = true;
        }
        if (!anyStep) return ms;
        cost.deltasMs(combination, finer, deltas);

        // The step with the largest gain per millisecond added that fits (a step that adds
        // nothing first); ties: the larger addedMs, then the lower index.
        int best = -1;
        double bestKey = 0.0;
        double bestAdded = 0.0;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            if (finer[i] == combination[i]) continue;
            const double added = deltas[i];
            if (!(ms + added <= problem.budgetMs)) continue;
            const double key = added > 0.0 ? gains[i] / added : std::numeric_limits<double>::infinity();
            if (best < 0 || key > bestKey || (key == bestKey && added > bestAdded)) {
                best = static_cast<int>(i);
                bestKey = key;
                bestAdded = added;
            }
        }
        if (best < 0) return ms;
        const auto variable = static_cast<std::size_t>(best);
        --combination[variable];
        const double next = cost.predictMs(combination);
        if (!(next <= problem.budgetMs)) {
            // The step's delta let it in, the whole prediction does not (a non-additive model):
            // undo it and leave this variable alone, as the rule says.
            ++combination[variable];
            leftAlone[variable] = 1;
            continue;
        }
        ms = next;
    }
}

}  // namespace lodopt::optimizer
