#include "optimizer/search_state.hpp"

#include <cassert>
#include <stdexcept>

namespace lodopt::optimizer {

namespace {

// Validates before the members that use the problem are built.
const Problem& validated(const Problem& problem, const Termination& termination) {
    validateProblem(problem);
    termination.validate();
    return problem;
}

}  // namespace

SearchState::SearchState(const Problem& problem, const Termination& termination, std::string_view algorithm,
                         bool iterative)
    : mProblem(problem),
      mTermination(termination),
      mAlgorithm(algorithm),
      mIterative(iterative),
      mEvaluator(validated(problem, termination), termination.maxEvaluations),
      mStart(std::chrono::steady_clock::now()) {
    if (iterative && !termination.guaranteesStop()) {
        throw std::invalid_argument(
            mAlgorithm +
            ": the termination needs maxIterations, stableIterations or maxSeconds (maxEvaluations "
            "alone may never be reached: a converged search only hits the cache)");
    }
}

double SearchState::elapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
}

std::size_t SearchState::evaluate(std::span<const Combination> combinations, std::span<Score> scores,
                                  std::span<double> predictedMs) {
    assert(scores.size() == combinations.size() && predictedMs.size() == combinations.size());
    const std::size_t scored = mEvaluator.evaluateBatch(combinations, scores);
    if (scored < combinations.size()) mTruncated = true;
    for (std::size_t k = 0; k < scored; ++k) {
        predictedMs[k] = mProblem.cost->predictMs(combinations[k]);
        const bool feasible = predictedMs[k] <= mProblem.budgetMs;
        assert(feasible && "algorithms evaluate feasible combinations only");
        if (!feasible) continue;
        if (!mHasBest || isBetter(scores[k].fitness, predictedMs[k], combinations[k], mBest.score.fitness,
                                  mBest.predictedMs, mBest.combination)) {
            mBest.combination = combinations[k];
            mBest.score = scores[k];
            mBest.predictedMs = predictedMs[k];
            mHasBest = true;
        }
    }
    return scored;
}

bool SearchState::endIteration(double meanFitness) {
    IterationLog row;
    row.iteration = static_cast<int>(mLog.size());
    row.bestFitness = mHasBest ? mBest.score.fitness : 0.0;
    row.meanFitness = meanFitness;
    row.bestPredictedMs = mHasBest ? mBest.predictedMs : 0.0;
    row.evaluations = mEvaluator.evaluations();
    row.cacheHits = mEvaluator.cacheHits();
    row.elapsedSeconds = elapsedSeconds();
    mLog.push_back(row);

    if (mTruncated || (mTermination.maxEvaluations > 0 && mEvaluator.budgetSpent())) {
        mStopReason = StopReason::MaxEvaluations;
        return true;
    }
    if (mTermination.maxSeconds > 0.0 && row.elapsedSeconds >= mTermination.maxSeconds) {
        mStopReason = StopReason::WallTime;
        return true;
    }
    if (!mIterative) return false;
    if (mTermination.maxIterations > 0 && row.iteration >= mTermination.maxIterations) {
        mStopReason = StopReason::MaxIterations;
        return true;
    }
    const auto window = static_cast<std::size_t>(mTermination.stableIterations);
    if (window > 0 && mLog.size() > window) {
        const double improvement = row.bestFitness - mLog[mLog.size() - 1 - window].bestFitness;
        if (improvement <= mTermination.stableTolerance) {
            mStopReason = StopReason::Stable;
            return true;
        }
    }
    return false;
}

Result SearchState::finish() {
    if (!mHasBest) {
        // Every algorithm evaluates at least one feasible combination before it can stop.
        throw std::logic_error(mAlgorithm + ": no feasible combination was evaluated");
    }
    Result result;
    result.algorithm = mAlgorithm;
    result.best = mBest.combination;
    result.bestScore = mBest.score;
    result.predictedMs = mBest.predictedMs;
    result.evaluations = mEvaluator.evaluations();
    result.cacheHits = mEvaluator.cacheHits();
    result.iterations = mLog.empty() ? 0 : static_cast<int>(mLog.size()) - 1;
    result.stopReason = mStopReason;
    result.log = std::move(mLog);
    return result;
}

Result evaluateAndFinish(SearchState& state, const Combination& combination) {
    Score score;
    double predictedMs = 0.0;
    if (state.evaluate(std::span<const Combination>(&combination, 1), std::span<Score>(&score, 1),
                       std::span<double>(&predictedMs, 1)) == 0) {
        throw std::invalid_argument("the evaluation budget is spent before the result could be scored");
    }
    state.endIteration(score.fitness);
    state.complete();
    return state.finish();
}

double meanFitness(std::span<const Score> scores, std::size_t count) {
    if (count == 0) return 0.0;
    double sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) sum += scores[k].fitness;
    return sum / static_cast<double>(count);
}

}  // namespace lodopt::optimizer
