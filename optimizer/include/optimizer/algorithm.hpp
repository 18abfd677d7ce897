// The one interface every search algorithm implements, its stopping rules and its result.
//
// Algorithm::run(problem, termination) validates the problem, searches, and returns the best
// feasible combination it evaluated together with a per-iteration log. Algorithms are
// constructed with validated parameters including an explicit seed; run() is const and
// starts its own Random from that seed, so two runs of one object give the same result and
// the same log (except the wall-clock column).
//
// Candidates are ordered deterministically by isBetter(): higher fitness, then lower
// predicted time, then the lexicographically smaller combination.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "optimizer/problem.hpp"

namespace lodopt::optimizer {

// When an iterative search stops: whichever enabled rule fires first. A field of 0 disables
// its rule. The constructive algorithms (greedy, heuristics, mckp, exhaustive) end on their
// own and honour only maxEvaluations and maxSeconds.
struct Termination {
    int maxIterations = 50;           // >= 0, iterations after the initial evaluation
    int stableIterations = 15;        // >= 0, K: stop when the best fitness has improved by no
                                      // more than stableTolerance over the last K iterations
    double stableTolerance = 1e-6;    // >= 0, fitness units
    std::int64_t maxEvaluations = 0;  // >= 0, cache misses (renders) allowed
    double maxSeconds = 0.0;          // >= 0, wall-clock seconds, checked between iterations

    // The paper's experiment (GAPSO15): 20 iterations, no other rule.
    static Termination paper();
    // No rule at all; only for algorithms that end on their own.
    static Termination none();

    // Throws std::invalid_argument naming the first negative or non-finite field.
    void validate() const;
    // A rule that always fires is enabled: maxIterations, stableIterations or maxSeconds
    // (required by gapso, pso, ga and random). maxEvaluations alone does not count: a swarm
    // that has converged only hits the cache and would never spend its evaluations. The stable
    // rule always fires because the best can improve only finitely often in a finite space.
    bool guaranteesStop() const;
};

enum class StopReason { Completed, MaxIterations, Stable, MaxEvaluations, WallTime };
std::string_view toString(StopReason reason);

// One row of the convergence curve (curve.csv). Iteration 0 is the initial evaluation.
struct IterationLog {
    int iteration = 0;
    double bestFitness = 0.0;      // best fitness seen so far
    double meanFitness = 0.0;      // mean fitness of this iteration's candidates
    double bestPredictedMs = 0.0;  // predicted time of the best so far
    std::int64_t evaluations = 0;  // cache misses so far
    std::int64_t cacheHits = 0;    // cache hits so far
    double elapsedSeconds = 0.0;   // wall clock since run() started (not deterministic)
};

struct Result {
    std::string algorithm;
    Combination best;          // feasible: predictedMs <= problem.budgetMs
    Score bestScore;           // its evaluator score
    double predictedMs = 0.0;  // Cost::predictMs(best)
    std::int64_t evaluations = 0;
    std::int64_t cacheHits = 0;
    int iterations = 0;  // iterations after the initial evaluation
    StopReason stopReason = StopReason::Completed;
    std::vector<IterationLog> log;
};

// A scored candidate, for comparisons.
struct Candidate {
    Combination combination;
    Score score;
    double predictedMs = 0.0;
};

// Higher fitness; on equal fitness lower predicted ms; then lexicographically smaller.
bool isBetter(double fitnessA, double msA, const Combination& a, double fitnessB, double msB, const Combination& b);
inline bool isBetter(const Candidate& a, const Candidate& b) {
    return isBetter(a.score.fitness, a.predictedMs, a.combination, b.score.fitness, b.predictedMs, b.combination);
}

class Algorithm {
public:
    virtual ~Algorithm() = default;
    // The registered name ("gapso", "mckp", ...).
    virtual std::string_view name() const = 0;
    // Throws ProblemError/BudgetError for a bad problem, std::invalid_argument for a bad
    // termination, EvaluationError when the evaluator breaks its contract.
    virtual Result run(const Problem& problem, const Termination& termination) const = 0;
};

// Every registered name, in a stable order: gapso, pso, ga, greedy, distance, importance,
// screensize, mckp, exhaustive, random, then those added by registerAlgorithm in the order
// they were added.
const std::vector<std::string>& algorithmNames();

// The named algorithm with its default parameters and `seed`. Throws std::invalid_argument
// listing the valid names when `name` is unknown.
std::unique_ptr<Algorithm> makeAlgorithm(std::string_view name, std::uint64_t seed = 1);

// Whether the named algorithm's answer depends on its seed (gapso, pso, ga, random and the
// registered ones said so); false for an unknown name.
bool isSeededAlgorithm(std::string_view name);

// Adds an algorithm from another library (the optional pagmo2 adapter, optimizer/pagmo) to
// algorithmNames, makeAlgorithm and isSeededAlgorithm, so every command and benchmark runs it
// like lodopt's own. Call at start-up, before any search: the registry is not guarded against
// concurrent searches. Throws std::invalid_argument for an empty name or one already known.
using AlgorithmMaker = std::function<std::unique_ptr<Algorithm>(std::uint64_t seed)>;
void registerAlgorithm(const std::string& name, AlgorithmMaker make, bool seeded);

}  // namespace lodopt::optimizer
