#include "optimizer/checked_evaluator.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace lodopt::optimizer {

namespace {

constexpr std::size_t kFromCache = std::numeric_limits<std::size_t>::max();

void checkScore(const Score& score, const Combination& combination) {
    if (!std::isfinite(score.fitness)) {
        throw EvaluationError("the evaluator returned fitness " + std::to_string(score.fitness) + " for combination " +
                              formatCombination(combination) + " (must be finite)");
    }
    if (score.componentCount < 0 || score.componentCount > static_cast<int>(Score::kMaxComponents)) {
        throw EvaluationError("the evaluator returned " + std::to_string(score.componentCount) +
                              " score components for combination " + formatCombination(combination) + " (at most " +
                              std::to_string(Score::kMaxComponents) + ")");
    }
    for (int c = 0; c < score.componentCount; ++c) {
        if (!std::isfinite(score.components[static_cast<std::size_t>(c)])) {
            throw EvaluationError("the evaluator returned a non-finite component " + std::to_string(c) +
                                  " for combination " + formatCombination(combination));
        }
    }
}

}  // namespace

std::size_t CombinationHash::operator()(const Combination& combination) const noexcept {
    // FNV-1a over the levels: combinations are short and levels small.
    std::uint64_t hash = 14695981039346656037ull;
    for (int level : combination) {
        hash ^= static_cast<std::uint32_t>(level);
        hash *= 1099511628211ull;
    }
    return static_cast<std::size_t>(hash);
}

CheckedEvaluator::CheckedEvaluator(Evaluator& evaluator, std::vector<int> levelCounts, std::int64_t maxEvaluations)
    : mEvaluator(evaluator), mLevelCounts(std::move(levelCounts)), mMaxEvaluations(maxEvaluations) {
    assert(maxEvaluations >= 0);
}

CheckedEvaluator::CheckedEvaluator(const Problem& problem, std::int64_t maxEvaluations)
    : CheckedEvaluator(*problem.evaluator, problem.levelCounts, maxEvaluations) {
    assert(problem.evaluator != nullptr);
}

std::int64_t CheckedEvaluator::remainingEvaluations() const {
    if (mMaxEvaluations == 0) return std::numeric_limits<std::int64_t>::max();
    return mMaxEvaluations > mEvaluations ? mMaxEvaluations - mEvaluations : 0;
}

std::size_t CheckedEvaluator::evaluateBatch(std::span<const Combination> combinations, std::span<Score> scores) {
    assert(combinations.size() == scores.size());
    for (const Combination& combination : combinations) validateCombination(mLevelCounts, combination);

    mMisses.clear();
    mSource.clear();
    mPending.clear();
    std::int64_t remaining = remainingEvaluations();
    std::int64_t hits = 0;
    std::size_t scored = 0;
    for (; scored < combinations.size(); ++scored) {
        const Combination& combination = combinations[scored];
        if (auto found = mCache.find(combination); found != mCache.end()) {
            scores[scored] = found->second;
            mSource.push_back(kFromCache);
            ++hits;
            continue;
        }
        if (auto repeat = mPending.find(combination); repeat != mPending.end()) {
            mSource.push_back(repeat->second);
            ++hits;
            continue;
        }
        if (remaining == 0) break;
        --remaining;
        mSource.push_back(mMisses.size());
        mPending.emplace(combination, mMisses.size());
        mMisses.push_back(combination);
    }

    if (!mMisses.empty()) {
        mMissScores.assign(mMisses.size(), Score{});
        mEvaluator.evaluateBatch(std::span<const Combination>(mMisses), std::span<Score>(mMissScores));
        for (std::size_t m = 0; m < mMisses.size(); ++m) checkScore(mMissScores[m], mMisses[m]);
        for (std::size_t m = 0; m < mMisses.size(); ++m) mCache.emplace(mMisses[m], mMissScores[m]);
        mEvaluations += static_cast<std::int64_t>(mMisses.size());
    }
    for (std::size_t k = 0; k < scored; ++k) {
        if (mSource[k] != kFromCache) scores[k] = mMissScores[mSource[k]];
    }
    mCacheHits += hits;
    return scored;
}

std::optional<Score> CheckedEvaluator::evaluate(const Combination& combination) {
    Score score;
    if (evaluateBatch(std::span<const Combination>(&combination, 1), std::span<Score>(&score, 1)) == 0) {
        return std::nullopt;
    }
    return score;
}

std::optional<Score> CheckedEvaluator::cached(const Combination& combination) const {
    if (auto found = mCache.find(combination); found != mCache.end()) return found->second;
    return std::nullopt;
}

}  // namespace lodopt::optimizer
