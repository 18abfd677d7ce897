// The bookkeeping every algorithm shares: checked evaluation (CheckedEvaluator's counting and
// cache), the best feasible candidate so far, the per-iteration log and the termination rules.
// Public so that an algorithm from another library (the pagmo2 adapter, optimizer/pagmo) counts,
// logs and stops exactly as lodopt's own do.
#pragma once

#include <chrono>
#include <span>
#include <string_view>

#include "optimizer/algorithm.hpp"
#include "optimizer/checked_evaluator.hpp"

namespace lodopt::optimizer {

class SearchState {
public:
    // Validates `problem` and `termination` (throws). `iterative`: the algorithm loops until a
    // termination rule fires, so it needs one and honours maxIterations and the stable rule.
    SearchState(const Problem& problem, const Termination& termination, std::string_view algorithm, bool iterative);

    const Problem& problem() const { return mProblem; }
    CheckedEvaluator& evaluator() { return mEvaluator; }

    // Evaluates a prefix of `combinations` (CheckedEvaluator::evaluateBatch), writes their scores
    // and predicted ms, records feasible ones against the best, and returns the prefix length.
    // `scores` and `predictedMs` have combinations.size() entries. Every combination should be
    // feasible (asserted); an infeasible one is never recorded as the best.
    std::size_t evaluate(std::span<const Combination> combinations, std::span<Score> scores,
                         std::span<double> predictedMs);

    bool hasBest() const { return mHasBest; }
    const Candidate& best() const { return mBest; }

    // Appends the log row of the iteration just evaluated and applies the termination rules;
    // true when the search must stop (stopReason() says why).
    bool endIteration(double meanFitness);
    // The algorithm ran to its natural end.
    void complete() { mStopReason = StopReason::Completed; }
    // Whether the evaluation budget is spent (no new combination can be evaluated).
    bool evaluationsSpent() const { return mEvaluator.budgetSpent(); }
    StopReason stopReason() const { return mStopReason; }
    // A batch was cut short because the evaluation budget ran out.
    bool truncated() const { return mTruncated; }
    double elapsedSeconds() const;

    // The result: the best feasible candidate evaluated, counts and the log.
    Result finish();

private:
    const Problem& mProblem;
    Termination mTermination;
    std::string mAlgorithm;
    bool mIterative;
    CheckedEvaluator mEvaluator;
    std::chrono::steady_clock::time_point mStart;
    bool mHasBest = false;
    Candidate mBest;
    bool mTruncated = false;  // a batch was cut short by the evaluation budget
    StopReason mStopReason = StopReason::Completed;
    std::vector<IterationLog> mLog;
};

// For the constructive algorithms: evaluates their one answer (feasible), logs it as iteration 0
// and returns the completed result. Throws std::invalid_argument when the evaluation budget is
// already spent.
Result evaluateAndFinish(SearchState& state, const Combination& combination);

// Mean of the first `count` fitnesses of `scores` (0 when count is 0).
double meanFitness(std::span<const Score> scores, std::size_t count);

}  // namespace lodopt::optimizer
