// A synthetic LOD selection problem with a known formula, for tests, benchmarks and
// comparing algorithms without rendering (docs/optimizer.md, "Synthetic benchmark").
//
// Variable i has levelCounts[i] levels; its degradation at level l is
// q_i(l) = (l / (levelCounts[i] - 1))^p_i in [0, 1] (q = 0 at the finest level), and
//   fitness = clamp(1 - sum_i w_i q_i(l_i) - sum_{(i,j) in pairs} c_ij q_i(l_i) q_j(l_j), 0, 1).
// The weights w_i (sum 0.6) say how visible each object is; the pair terms make the problem
// non-additive: c_ij > 0 when two objects coarse together look worse than each alone (they
// overlap), c_ij < 0 when one hides the other's loss. The cost is additive: a frame base plus,
// per variable, a finest-level cost shrinking geometrically with the level, like triangle
// counts of a simplification chain. Hints (distance, coverage, area, pixel error) are derived
// from the weights, so that the heuristic baselines see informative but imperfect data.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "optimizer/problem.hpp"

namespace lodopt::optimizer {

struct SyntheticParameters {
    int variables = 30;              // >= 1
    int minLevels = 4;               // >= 1
    int maxLevels = 6;               // >= minLevels
    double pairDensity = 0.1;        // [0, 1], fraction of variable pairs with a c_ij term
    double interactionWeight = 0.4;  // >= 0, sum of |c_ij| over all pairs (0 = additive)
    double negativeFraction = 0.3;   // [0, 1], fraction of pair terms with c_ij < 0
    double budgetFraction = 0.3;     // [0, 1]: budget = min + fraction * (max - min) ms
    std::uint64_t seed = 1;
};

// The fitness formula above; deterministic and thread-safe (const state only).
class InteractionEvaluator final : public Evaluator {
public:
    struct Pair {
        std::size_t a = 0;
        std::size_t b = 0;
        double weight = 0.0;  // c_ab
    };
    // degradation[i][l] = q_i(l); weights[i] = w_i.
    InteractionEvaluator(std::vector<std::vector<double>> degradation, std::vector<double> weights,
                         std::vector<Pair> pairs);

    // Components: the additive loss sum w_i q_i, and the rest of the loss (pair terms and
    // clamping).
    Score evaluate(const Combination& combination) override;
    double fitness(const Combination& combination) const;
    double additiveLoss(const Combination& combination) const;
    std::vector<std::string> componentNames() const override { return {"additiveLoss", "interactionLoss"}; }

    const std::vector<std::vector<double>>& degradation() const { return mDegradation; }
    const std::vector<double>& weights() const { return mWeights; }
    const std::vector<Pair>& pairs() const { return mPairs; }

private:
    double degradationAt(std::size_t variable, const Combination& combination) const;

    std::vector<std::vector<double>> mDegradation;
    std::vector<double> mWeights;
    std::vector<Pair> mPairs;
};

// Owns the evaluator and cost; problem() borrows them, so keep this object alive while the
// problem is used (it is not copyable for that reason).
class SyntheticProblem {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit SyntheticProblem(const SyntheticParameters& parameters);
    SyntheticProblem(const SyntheticProblem&) = delete;
    SyntheticProblem& operator=(const SyntheticProblem&) = delete;

    // levelCounts, evaluator, cost, budgetMs and hints; no surrogate table.
    Problem problem() const;
    // The exact additive part w_i q_i(l), a valid Problem::surrogateLoss.
    std::vector<std::vector<double>> additiveLoss() const;

    InteractionEvaluator& evaluator() const { return *mEvaluator; }
    const AdditiveCost& cost() const { return *mCost; }
    double budgetMs() const { return mBudgetMs; }
    const std::vector<int>& levelCounts() const { return mLevelCounts; }

private:
    std::vector<int> mLevelCounts;
    std::unique_ptr<InteractionEvaluator> mEvaluator;
    std::unique_ptr<AdditiveCost> mCost;
    double mBudgetMs = 0.0;
    std::vector<VariableHints> mHints;
};

}  // namespace lodopt::optimizer
