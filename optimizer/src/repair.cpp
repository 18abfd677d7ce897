// Feasibility repair; the rule is documented in repair.hpp and docs/optimizer.md.
#include "optimizer/repair.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
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
            const double key =
                haveSurrogate ? surrogateStepLoss(problem, i, static_cast<std::size_t>(level)) / saved : -saved;
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

namespace {

struct FillStep {
    double key = 0.0;    // surrogate gain per millisecond added; +inf for a step that adds nothing
    double added = 0.0;  // Cost::deltaMs of the step
    int variable = 0;
};

// Heap order (the best step on top): larger key, then larger added, then lower variable index.
bool worseStep(const FillStep& a, const FillStep& b) {
    if (a.key != b.key) return a.key < b.key;
    if (a.added != b.added) return a.added < b.added;
    return a.variable > b.variable;
}

}  // namespace

// The rule is a loop that, each round, asks every variable for its step and takes the best that
// fits: O(n) cost questions per step, and each question is O(n) for a cost that keys a memo by
// the whole combination (the evaluation module's). This is the same greedy with a heap of steps
// checked lazily: a popped step is asked again and put back when its answer changed (a cost
// whose steps depend on other variables); a step that does not fit is set aside until a taken
// step lowers the prediction. For a cost whose steps do not depend on the other variables
// (AdditiveCost; the time model's linear features) the choices are those of the loop, which
// the tests check against a copy of it.
double fillToBudget(const Problem& problem, Combination& combination) {
    assert(combination.size() == problem.levelCounts.size());
    const Cost& cost = *problem.cost;
    const bool haveSurrogate = !problem.surrogateLoss.empty();
    double ms = cost.predictMs(combination);
    assert(ms <= problem.budgetMs);

    // The step of `variable` from the current combination; false when it has none that gains.
    auto stepOf = [&](int variable, FillStep& step) {
        const auto level = static_cast<std::size_t>(combination[static_cast<std::size_t>(variable)]);
        if (level == 0) return false;
        const double gain =
            haveSurrogate ? surrogateStepLoss(problem, static_cast<std::size_t>(variable), level - 1) : 1.0;
        if (!(gain > 0.0)) return false;
        step.added = cost.deltaMs(combination, variable, static_cast<int>(level) - 1);
        step.key = step.added > 0.0 ? gain / step.added : std::numeric_limits<double>::infinity();
        step.variable = variable;
        return true;
    };

    std::vector<FillStep> heap;
    std::vector<FillStep> setAside;  // did not fit at the prediction they were asked at
    heap.reserve(combination.size());
    for (std::size_t i = 0; i < combination.size(); ++i) {
        FillStep step;
        if (stepOf(static_cast<int>(i), step)) heap.push_back(step);
    }
    std::make_heap(heap.begin(), heap.end(), worseStep);
    while (!heap.empty()) {
        std::pop_heap(heap.begin(), heap.end(), worseStep);
        const FillStep popped = heap.back();
        heap.pop_back();
        FillStep step;
        if (!stepOf(popped.variable, step)) continue;
        if (step.key != popped.key || step.added != popped.added) {
            heap.push_back(step);  // asked at another combination: back with today's answer
            std::push_heap(heap.begin(), heap.end(), worseStep);
            continue;
        }
        if (!(ms + step.added <= problem.budgetMs)) {
            setAside.push_back(step);
            continue;
        }
        const auto variable = static_cast<std::size_t>(step.variable);
        --combination[variable];
        const double next = cost.predictMs(combination);
        if (!(next <= problem.budgetMs)) {
            // The step's delta let it in, the whole prediction does not (a non-additive model):
            // undo it and leave this variable alone, as the rule says.
            ++combination[variable];
            continue;
        }
        const bool lowered = next < ms;
        ms = next;
        if (stepOf(step.variable, step)) {
            heap.push_back(step);
            std::push_heap(heap.begin(), heap.end(), worseStep);
        }
        if (lowered && !setAside.empty()) {
            for (const FillStep& waiting : setAside) heap.push_back(waiting);
            setAside.clear();
            std::make_heap(heap.begin(), heap.end(), worseStep);
        }
    }
    return ms;
}

}  // namespace lodopt::optimizer
