// The checking, counting wrapper every algorithm evaluates through (pagmo2's problem wrapper).
//
// It validates each combination, refuses a non-finite score, counts evaluations and cache
// hits, and caches scores keyed by the combination, so a combination already evaluated is
// never evaluated again (a swarm that converges revisits the same few combinations; each
// evaluation is a render plus image metrics). It can also enforce an evaluation budget: once
// `maxEvaluations` cache misses have been spent, no new combination is evaluated.
//
// A batch is answered as a prefix: candidates are walked in order, cached ones (and repeats
// within the batch) are hits, new ones are misses until the budget runs out; the scored prefix
// length is returned. The misses go to Evaluator::evaluateBatch in one call, in order of first
// appearance, so an implementation may evaluate them in parallel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "optimizer/problem.hpp"

namespace lodopt::optimizer {

// The evaluator broke its contract (a NaN or infinite fitness or component, a component count
// out of range); the message names the combination.
class EvaluationError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct CombinationHash {
    std::size_t operator()(const Combination& combination) const noexcept;
};

class CheckedEvaluator {
public:
    // `evaluator` must outlive this object. `levelCounts` as in Problem. `maxEvaluations` >= 0,
    // the most cache misses this wrapper will pay for; 0 means no limit.
    CheckedEvaluator(Evaluator& evaluator, std::vector<int> levelCounts, std::int64_t maxEvaluations = 0);
    // Wraps problem.evaluator with problem.levelCounts.
    explicit CheckedEvaluator(const Problem& problem, std::int64_t maxEvaluations = 0);

    // Scores a prefix of `combinations` into `scores` and returns its length: all of them unless
    // the evaluation budget ran out at an uncached candidate. `scores.size()` ==
    // `combinations.size()`. Throws ProblemError for an invalid combination (before evaluating
    // anything) and EvaluationError for a non-finite score.
    std::size_t evaluateBatch(std::span<const Combination> combinations, std::span<Score> scores);

    // One combination; std::nullopt when it is not cached and the budget is spent.
    std::optional<Score> evaluate(const Combination& combination);

    // The cached score, without counting a hit; std::nullopt when never evaluated.
    std::optional<Score> cached(const Combination& combination) const;

    std::int64_t evaluations() const { return mEvaluations; }  // cache misses paid for
    std::int64_t cacheHits() const { return mCacheHits; }      // answers served from the cache
    std::int64_t maxEvaluations() const { return mMaxEvaluations; }
    // Evaluations left under the budget; INT64_MAX when unlimited.
    std::int64_t remainingEvaluations() const;
    bool budgetSpent() const { return remainingEvaluations() == 0; }

    const std::vector<int>& levelCounts() const { return mLevelCounts; }
    Evaluator& evaluator() const { return mEvaluator; }

private:
    Evaluator& mEvaluator;
    std::vector<int> mLevelCounts;
    std::int64_t mMaxEvaluations;
    std::int64_t mEvaluations = 0;
    std::int64_t mCacheHits = 0;
    std::unordered_map<Combination, Score, CombinationHash> mCache;
    // Scratch reused across batches.
    std::vector<Combination> mMisses;
    std::vector<Score> mMissScores;
    std::vector<std::size_t> mSource;  // per scored candidate: index into mMisses, or npos if cached
    std::unordered_map<Combination, std::size_t, CombinationHash> mPending;  // miss → index in mMisses
};

}  // namespace lodopt::optimizer
