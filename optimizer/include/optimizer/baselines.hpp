// Search baselines that need no hints: benefit/cost greedy, exhaustive enumeration and
// random sampling.
#pragma once

#include <cstdint>
#include <string_view>

#include "optimizer/algorithm.hpp"

namespace lodopt::optimizer {

// Where the greedy's benefit of a level step comes from.
enum class BenefitSource {
    Evaluator,  // fitness(after step) - fitness(before), one evaluation per candidate step
    Surrogate,  // surrogateLoss[i][l] - surrogateLoss[i][l-1] (measured first if the problem
                // has no table: sum(levelCounts - 1) + 1 evaluations)
};

struct GreedyParameters {
    BenefitSource benefit = BenefitSource::Evaluator;
};

// Benefit/cost greedy after Funkhouser & Séquin 1993 ("FS93", docs/method.md §6): start with
// every variable at its coarsest level; repeatedly consider raising each variable one level
// (finer) among the steps that keep predictMs <= budgetMs, and take the step with the highest
// fitness gain per extra millisecond (a step that costs <= 0 ms ranks above all others, by
// gain); stop when no step fits or none gains fitness. One iteration = one step; with the
// evaluator, its candidate steps are one batch. Ties: larger gain, then lower variable index.
// Like every algorithm it returns the best combination it evaluated, which with evaluator
// benefits can be a candidate step off its path. Ignores maxIterations and the stable rule.
class Greedy final : public Algorithm {
public:
    explicit Greedy(GreedyParameters parameters = {});
    std::string_view name() const override { return "greedy"; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    GreedyParameters mParameters;
};

struct ExhaustiveParameters {
    double maxCombinations = 1e6;  // >= 1: larger spaces are refused
    int batchSize = 256;           // >= 1, feasible combinations per evaluateBatch call
};

// Ground truth: enumerates every combination (mixed radix, last variable fastest), evaluates
// the feasible ones and returns the best (isBetter order). Throws ProblemError when the space
// has more than maxCombinations members. Stops early (stopReason says so) only under
// maxEvaluations or maxSeconds; one iteration = one batch.
class Exhaustive final : public Algorithm {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit Exhaustive(ExhaustiveParameters parameters = {});
    std::string_view name() const override { return "exhaustive"; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    ExhaustiveParameters mParameters;
};

struct RandomSearchParameters {
    int samplesPerIteration = 12;  // >= 1, combinations drawn per iteration (one batch)
    std::uint64_t seed = 1;
};

// Random sampling: each iteration draws samplesPerIteration combinations uniformly (each
// level independently uniform), repairs them to the budget and evaluates them. Compare it with
// the swarm at equal maxEvaluations.
class RandomSearch final : public Algorithm {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit RandomSearch(RandomSearchParameters parameters = {});
    std::string_view name() const override { return "random"; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    RandomSearchParameters mParameters;
};

}  // namespace lodopt::optimizer
