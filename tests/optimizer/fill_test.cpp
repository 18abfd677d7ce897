// The budget fill (fillToBudget): hand-worked steps, the rule's edge cases, and the heap
// implementation against a plain copy of the rule's loop on random problems.
#include <gtest/gtest.h>

#include <limits>

#include "fixtures.hpp"

namespace lodopt::optimizer {
namespace {

using testing::HandProblem;
using testing::MaxCost;
using testing::TableEvaluator;

TEST(Fill, LeavesACombinationWithNoRoomAlone) {
    HandProblem hand;
    const Problem problem = hand.problem();
    Combination combination{0, 1, 1};  // 8 ms of 8
    EXPECT_DOUBLE_EQ(fillToBudget(problem, combination), 8.0);
    EXPECT_EQ(combination, (Combination{0, 1, 1}));
}

TEST(Fill, WithoutSurrogateRefinesTheCheapestStep) {
    HandProblem hand;
    const Problem problem = hand.problem(8.0);
    // All coarsest: 4 ms. Steps cost A 1, B 3, C 1 → A (tie with C, lower index): 5 ms; then
    // A 2, B 3, C 1 → C: 6 ms; then A 2, B 3, C 1 → C: 7 ms; then A 2 and B 3 do not fit.
    Combination combination{2, 1, 2};
    EXPECT_DOUBLE_EQ(fillToBudget(problem, combination), 7.0);
    EXPECT_EQ(combination, (Combination{1, 1, 0}));
}

TEST(Fill, WithSurrogateRefinesTheMostGainPerMillisecond) {
    HandProblem hand;
    Problem problem = hand.problem(8.0);
    problem.surrogateLoss = hand.evaluator.loss();
    // Gain per ms from all coarsest (4 ms): A .25/1, B .25/3, C .1875/1 → A: 5 ms; then
    // A .125/2, B .25/3, C .1875/1 → C: 6 ms; then A .0625 (2 ms), B no room, C .0625 (1 ms):
    // a tie, the larger step A: 8 ms. The hand optimum, where cheapest-first stopped at 7 ms.
    Combination combination{2, 1, 2};
    EXPECT_DOUBLE_EQ(fillToBudget(problem, combination), 8.0);
    EXPECT_EQ(combination, (Combination{0, 1, 1}));
    EXPECT_DOUBLE_EQ(hand.evaluator.evaluate(combination).fitness, 0.6875);
}

TEST(Fill, NeverTakesAStepTheSurrogateSaysGainsNothing) {
    HandProblem hand;
    Problem problem = hand.problem(12.0);  // everything at level 0 fits
    problem.surrogateLoss = {{0.0, 0.0, 0.375}, {0.0, 0.25}, {0.0, 0.0625, 0.0625}};
    Combination combination{2, 1, 2};
    // A's 1 → 0 and C's 2 → 1 gain nothing by the table, so A stops at 1 and C stays coarsest
    // (its gaining step 1 → 0 lies behind the empty one); B's step is taken.
    EXPECT_DOUBLE_EQ(fillToBudget(problem, combination), 2.0 + 5.0 + 1.0);
    EXPECT_EQ(combination, (Combination{1, 0, 2}));
}

TEST(Fill, NonAdditiveCostNeverEndsOverBudget) {
    TableEvaluator evaluator({{0, 0.1, 0.2}, {0, 0.1, 0.2}, {0, 0.1, 0.2}});
    // GPU-bound at fine levels, CPU-bound at coarse ones: a step's delta is not what the
    // whole prediction adds once the other bound takes over.
    const MaxCost cost(1.0, {{6, 3, 1}, {6, 3, 1}, {6, 3, 1}}, {{1, 1, 1}, {1, 2, 4}, {1, 1, 1}});
    Problem problem;
    problem.levelCounts = {3, 3, 3};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    for (double budget : {7.0, 9.0, 12.0, 19.0}) {
        problem.budgetMs = budget;
        ASSERT_NO_THROW(validateProblem(problem));
        for (const Combination& start : {Combination{2, 2, 2}, Combination{2, 0, 2}, Combination{1, 2, 1}}) {
            Combination combination = start;
            if (cost.predictMs(combination) > budget) continue;
            const double ms = fillToBudget(problem, combination);
            EXPECT_LE(ms, budget) << formatCombination(start);
            EXPECT_DOUBLE_EQ(ms, cost.predictMs(combination));
            for (std::size_t i = 0; i < 3; ++i) EXPECT_LE(combination[i], start[i]);  // levels only refine
            // Nothing left that fits: every remaining single step would go over.
            for (std::size_t i = 0; i < 3; ++i) {
                if (combination[i] == 0) continue;
                Combination finer = combination;
                --finer[i];
                EXPECT_GT(cost.predictMs(finer), budget)
                    << formatCombination(start) << " → " << formatCombination(combination);
            }
        }
    }
}

// A non-monotone cost: A's finest level is cheaper than its middle one. B's step does not fit
// at first; A's two steps (+2 ms, then -3 ms) make room for it, so the step set aside must
// come back once the prediction falls.
TEST(Fill, AStepThatSavesTimeMakesRoomForOneThatDidNotFit) {
    TableEvaluator evaluator({{0.0, 0.1, 0.2}, {0.0, 1.0}});
    const AdditiveCost cost(0.0, {{1.0, 4.0, 2.0}, {5.0, 1.0}});
    Problem problem;
    problem.levelCounts = {3, 2};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 6.0;
    problem.surrogateLoss = evaluator.loss();
    Combination combination{2, 1};  // 3 ms; B's step (+4, gain 1) first by ratio, but 7 > 6
    EXPECT_DOUBLE_EQ(fillToBudget(problem, combination), 6.0);
    EXPECT_EQ(combination, (Combination{0, 0}));
}

// The rule as docs/optimizer.md states it, one round at a time: every variable asked one at a
// time (Cost::deltaMs), the best step that fits taken. fillToBudget asks them all at once
// (Cost::deltasMs) and must choose exactly the same.
double referenceFill(const Problem& problem, Combination& combination) {
    const Cost& cost = *problem.cost;
    const bool haveSurrogate = !problem.surrogateLoss.empty();
    double ms = cost.predictMs(combination);
    std::vector<bool> blocked(combination.size(), false);
    while (true) {
        int best = -1;
        double bestKey = 0.0;
        double bestAdded = 0.0;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            const int level = combination[i];
            if (level == 0 || blocked[i]) continue;
            const double added = cost.deltaMs(combination, static_cast<int>(i), level - 1);
            if (!(ms + added <= problem.budgetMs)) continue;
            const double gain = haveSurrogate ? problem.surrogateLoss[i][static_cast<std::size_t>(level)] -
                                                    problem.surrogateLoss[i][static_cast<std::size_t>(level) - 1]
                                              : 1.0;
            if (!(gain > 0.0)) continue;
            const double key = added > 0.0 ? gain / added : std::numeric_limits<double>::infinity();
            if (best < 0 || key > bestKey || (key == bestKey && added > bestAdded)) {
                best = static_cast<int>(i);
                bestKey = key;
                bestAdded = added;
            }
        }
        if (best < 0) return ms;
        --combination[static_cast<std::size_t>(best)];
        const double next = cost.predictMs(combination);
        if (!(next <= problem.budgetMs)) {
            ++combination[static_cast<std::size_t>(best)];
            blocked[static_cast<std::size_t>(best)] = true;
            continue;
        }
        ms = next;
    }
}

// Random problems with small integer costs and gains, so that ties are common; some finer
// levels are cheaper than coarser ones (steps that add nothing or save time), some surrogate
// steps gain nothing or lose. Every third problem's cost is not additive (MaxCost: a step's
// delta depends on the other levels, and the whole prediction may refuse a step its delta let
// in). Every start that fits the budget, filled both ways.
TEST(Fill, ChoosesExactlyWhatTheRulesLoopChoosesForAnyCost) {
    Random random(11);
    int compared = 0;
    int changed = 0;
    for (int trial = 0; trial < 3000; ++trial) {
        const int variables = 1 + random.belowInt(12);
        std::vector<int> levelCounts(static_cast<std::size_t>(variables));
        std::vector<std::vector<double>> levelMs(levelCounts.size());
        std::vector<std::vector<double>> cpuMs(levelCounts.size());
        std::vector<std::vector<double>> loss(levelCounts.size());
        for (std::size_t i = 0; i < levelCounts.size(); ++i) {
            levelCounts[i] = 1 + random.belowInt(6);
            double lost = 0.0;
            for (int l = 0; l < levelCounts[i]; ++l) {
                levelMs[i].push_back(static_cast<double>(random.belowInt(6)));  // not monotone on purpose
                cpuMs[i].push_back(static_cast<double>(random.belowInt(6)));
                loss[i].push_back(l == 0 ? 0.0 : lost);
                lost += static_cast<double>(random.belowInt(4) - 1) * 0.25;  // -0.25 .. 0.5 per step
            }
        }
        const AdditiveCost additive(1.0, levelMs);
        const MaxCost notAdditive(1.0, levelMs, cpuMs);
        const Cost& cost = trial % 3 == 2 ? static_cast<const Cost&>(notAdditive) : additive;
        TableEvaluator evaluator(loss);
        Problem problem;
        problem.levelCounts = levelCounts;
        problem.evaluator = &evaluator;
        problem.cost = &cost;
        const bool withSurrogate = trial % 2 == 0;
        if (withSurrogate) problem.surrogateLoss = loss;
        Combination coarsest(levelCounts.size());
        for (std::size_t i = 0; i < coarsest.size(); ++i) coarsest[i] = levelCounts[i] - 1;
        problem.budgetMs = cost.predictMs(coarsest) + static_cast<double>(random.belowInt(3 * variables + 1));
        for (int start = 0; start < 5; ++start) {
            Combination combination(levelCounts.size());
            for (std::size_t i = 0; i < combination.size(); ++i) combination[i] = random.belowInt(levelCounts[i]);
            if (!(cost.predictMs(combination) <= problem.budgetMs)) combination = coarsest;
            if (!(cost.predictMs(combination) <= problem.budgetMs)) continue;
            Combination expected = combination;
            const double expectedMs = referenceFill(problem, expected);
            Combination actual = combination;
            const double actualMs = fillToBudget(problem, actual);
            ASSERT_EQ(actual, expected) << "trial " << trial << " from " << formatCombination(combination)
                                        << (withSurrogate ? " with" : " without") << " surrogate";
            ASSERT_EQ(actualMs, expectedMs);
            ++compared;
            changed += actual != combination;
        }
    }
    EXPECT_GT(compared, 10000);
    EXPECT_GT(changed, compared / 4) << "the fills should mostly have had something to do";
}

}  // namespace
}  // namespace lodopt::optimizer
