// Multiple-choice knapsack by dynamic programming over a discretised capacity (the textbook
// MCKP recurrence, e.g. Kellerer, Pferschy & Pisinger, "Knapsack Problems", 2004, §11), on
// the additive surrogate of the LOD selection problem (CITY17 names the problem an MCKP).
#include "optimizer/mckp.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include "optimizer/repair.hpp"
#include "optimizer/search_state.hpp"

namespace lodopt::optimizer {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Per variable, the level of least loss (the finer one on ties).
Combination leastLoss(std::span<const std::vector<double>> loss) {
    Combination combination(loss.size(), 0);
    for (std::size_t i = 0; i < loss.size(); ++i) {
        for (std::size_t l = 1; l < loss[i].size(); ++l) {
            if (loss[i][l] < loss[i][static_cast<std::size_t>(combination[i])]) combination[i] = static_cast<int>(l);
        }
    }
    return combination;
}

}  // namespace

Combination solveMckp(std::span<const std::vector<double>> loss, std::span<const std::vector<double>> costMs,
                      double capacityMs, int buckets) {
    assert(loss.size() == costMs.size() && buckets >= 1 && !std::isnan(capacityMs));
    const std::size_t variables = loss.size();
    // Shift each variable's costs so its cheapest level costs 0: the DP needs weights >= 0.
    std::vector<double> cheapest(variables);
    double capacity = capacityMs;
    double mostShifted = 0.0;
    for (std::size_t i = 0; i < variables; ++i) {
        assert(loss[i].size() == costMs[i].size() && !loss[i].empty());
        double low = costMs[i][0];
        double high = costMs[i][0];
        for (double ms : costMs[i]) {
            low = std::min(low, ms);
            high = std::max(high, ms);
        }
        cheapest[i] = low;
        capacity -= low;
        mostShifted += high - low;
    }
    if (capacity < 0.0) return {};
    if (mostShifted <= capacity) return leastLoss(loss);  // the budget binds nothing

    const auto bucketCount = static_cast<std::size_t>(buckets);
    const double width = capacity / static_cast<double>(buckets);
    for (std::size_t i = 0; i < variables; ++i) {
        if (loss[i].size() > std::numeric_limits<std::uint16_t>::max()) {
            throw ProblemError("mckp: variable " + std::to_string(i) + " has " + std::to_string(loss[i].size()) +
                               " levels, at most 65535 are supported");
        }
    }
    // Weights in whole buckets, rounded up (conservative); SIZE_MAX when a level cannot fit.
    constexpr std::size_t kNoFit = std::numeric_limits<std::size_t>::max();
    std::vector<std::vector<std::size_t>> weight(variables);
    for (std::size_t i = 0; i < variables; ++i) {
        weight[i].resize(costMs[i].size());
        for (std::size_t l = 0; l < costMs[i].size(); ++l) {
            const double shifted = costMs[i][l] - cheapest[i];
            if (shifted <= 0.0) {
                weight[i][l] = 0;
            } else if (width <= 0.0) {
                weight[i][l] = kNoFit;
            } else {
                // The small relative slack keeps exact multiples from rounding up a whole bucket.
                const double steps = shifted / width;
                const double rounded = std::ceil(steps - 1e-9 * std::max(1.0, steps));
                weight[i][l] = rounded > static_cast<double>(bucketCount) ? kNoFit : static_cast<std::size_t>(rounded);
            }
        }
    }

    // best[b]: least loss of the variables so far with total weight <= b.
    std::vector<double> best(bucketCount + 1, 0.0);
    std::vector<double> next(bucketCount + 1);
    std::vector<std::uint16_t> choice(variables * (bucketCount + 1));
    for (std::size_t i = 0; i < variables; ++i) {
        std::uint16_t* row = &choice[i * (bucketCount + 1)];
        for (std::size_t b = 0; b <= bucketCount; ++b) {
            double value = kInfinity;
            std::uint16_t level = 0;
            for (std::size_t l = 0; l < loss[i].size(); ++l) {
                const std::size_t w = weight[i][l];
                if (w > b) continue;
                const double candidate = best[b - w] + loss[i][l];
                if (candidate < value) {
                    value = candidate;
                    level = static_cast<std::uint16_t>(l);
                }
            }
            next[b] = value;
            row[b] = level;
        }
        best.swap(next);
    }
    if (best[bucketCount] == kInfinity) return {};

    Combination combination(variables);
    std::size_t b = bucketCount;
    for (std::size_t i = variables; i-- > 0;) {
        const std::uint16_t level = choice[i * (bucketCount + 1) + b];
        combination[i] = level;
        b -= weight[i][level];
    }
    return combination;
}

std::int64_t surrogateEvaluations(std::span<const int> levelCounts) {
    std::int64_t count = 1;
    for (int levels : levelCounts) count += levels - 1;
    return count;
}

std::vector<std::vector<double>> measureSurrogateLoss(const Problem& problem, CheckedEvaluator& evaluator) {
    const std::int64_t needed = surrogateEvaluations(problem.levelCounts);
    if (evaluator.remainingEvaluations() < needed) {
        throw ProblemError("measuring the surrogate loss needs " + std::to_string(needed) + " evaluations, only " +
                           std::to_string(evaluator.remainingEvaluations()) + " are left");
    }
    const Combination reference = finestCombination(problem);
    std::vector<Combination> batch{reference};
    for (std::size_t i = 0; i < reference.size(); ++i) {
        for (int l = 1; l < problem.levelCounts[i]; ++l) {
            batch.push_back(reference);
            batch.back()[i] = l;
        }
    }
    std::vector<Score> scores(batch.size());
    const std::size_t scored = evaluator.evaluateBatch(batch, scores);
    assert(scored == batch.size());
    (void)scored;

    std::vector<std::vector<double>> loss(reference.size());
    std::size_t k = 1;
    for (std::size_t i = 0; i < reference.size(); ++i) {
        loss[i].assign(static_cast<std::size_t>(problem.levelCounts[i]), 0.0);
        for (std::size_t l = 1; l < loss[i].size(); ++l) loss[i][l] = scores[0].fitness - scores[k++].fitness;
    }
    return loss;
}

Mckp::Mckp(MckpParameters parameters) : mParameters(parameters) {
    if (mParameters.buckets < 1) {
        throw std::invalid_argument("mckp: buckets = " + std::to_string(mParameters.buckets) + ", must be >= 1");
    }
}

Result Mckp::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), false);
    std::vector<std::vector<double>> measured;
    if (problem.surrogateLoss.empty()) {
        const std::int64_t needed = surrogateEvaluations(problem.levelCounts) + 1;
        if (state.evaluator().remainingEvaluations() < needed) {
            throw std::invalid_argument("mckp: maxEvaluations = " + std::to_string(termination.maxEvaluations) +
                                        " is below the " + std::to_string(needed) +
                                        " evaluations needed to measure the surrogate loss and score the result");
        }
        measured = measureSurrogateLoss(problem, state.evaluator());
    }
    const auto& loss = problem.surrogateLoss.empty() ? measured : problem.surrogateLoss;

    // Additive cost approximation: each variable alone, from the all-coarsest base.
    const Combination base = coarsestCombination(problem);
    const double baseMs = problem.cost->predictMs(base);
    std::vector<std::vector<double>> costMs(base.size());
    int maxLevels = 0;
    for (std::size_t i = 0; i < base.size(); ++i) {
        costMs[i].resize(static_cast<std::size_t>(problem.levelCounts[i]));
        maxLevels = std::max(maxLevels, problem.levelCounts[i]);
    }
    // Level l of every variable that has one, asked at once (the others stay at the base).
    Combination newLevels(base.size());
    std::vector<double> deltas(base.size());
    for (int l = 0; l < maxLevels; ++l) {
        for (std::size_t i = 0; i < base.size(); ++i) newLevels[i] = l < problem.levelCounts[i] ? l : base[i];
        problem.cost->deltasMs(base, newLevels, deltas);
        for (std::size_t i = 0; i < base.size(); ++i) {
            if (l < problem.levelCounts[i]) costMs[i][static_cast<std::size_t>(l)] = deltas[i];
        }
    }
    Combination combination = solveMckp(loss, costMs, problem.budgetMs - baseMs, mParameters.buckets);
    // Rounding can leave no DP solution when some level is cheaper than the coarsest.
    if (combination.empty()) combination = base;
    repairToBudget(problem, combination);  // the true cost may not be additive

    return evaluateAndFinish(state, combination);
}

}  // namespace lodopt::optimizer
