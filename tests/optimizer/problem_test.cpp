// Problem validation, the additive cost, the checked evaluator and repair (the fill: fill_test.cpp).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fixtures.hpp"

namespace lodopt::optimizer {
namespace {

using testing::HandProblem;
using ::testing::HasSubstr;
using testing::MaxCost;
using testing::TableEvaluator;

template <typename Error, typename Function>
std::string messageOf(Function&& function) {
    try {
        function();
    } catch (const Error& error) {
        return error.what();
    }
    return "<no exception>";
}

TEST(Problem, ValidHandProblemPasses) {
    HandProblem hand;
    EXPECT_NO_THROW(validateProblem(hand.problem()));
    EXPECT_EQ(finestCombination(hand.problem()), (Combination{0, 0, 0}));
    EXPECT_EQ(coarsestCombination(hand.problem()), (Combination{2, 1, 2}));
    EXPECT_DOUBLE_EQ(combinationCount(hand.problem().levelCounts), 18.0);
}

TEST(Problem, RejectsBadShapesNamingTheElement) {
    HandProblem hand;
    Problem problem = hand.problem();
    problem.levelCounts = {3, 0, 3};
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("levelCounts[1] = 0"));
    problem = hand.problem();
    problem.levelCounts.clear();
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("no variables"));
    problem = hand.problem();
    problem.budgetMs = std::nan("");
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("budgetMs"));
    problem = hand.problem();
    problem.hints.resize(2);
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("hints has 2 entries"));
    problem = hand.problem();
    problem.hints.resize(3);
    problem.hints[2].levelPixelError = {0.0, 1.0};
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("hints[2].levelPixelError"));
    problem = hand.problem();
    problem.hints.resize(3);
    problem.hints[1].levelScreenCoverage = {0.1, 0.5};
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("non-increasing"));
    problem = hand.problem();
    problem.hints.resize(3);
    problem.hints[0].distance = -2.0;
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("hints[0].distance"));
    problem = hand.problem();
    problem.surrogateLoss = {{0, 1, 2}, {0, 1}, {0, 1}};
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }),
                HasSubstr("surrogateLoss[2] has 2 entries"));
    problem.surrogateLoss = {{0, 1, 2}, {0, std::nan("")}, {0, 1, 2}};
    EXPECT_THAT(messageOf<ProblemError>([&] { validateProblem(problem); }), HasSubstr("surrogateLoss[1][1]"));
}

TEST(Problem, BudgetBelowTheCheapestCombinationStatesTheMinimum) {
    HandProblem hand;
    Problem problem = hand.problem(3.5);  // all coarsest costs 1 + 2 + 1 = 4 ms
    try {
        validateProblem(problem);
        FAIL() << "expected BudgetError";
    } catch (const BudgetError& error) {
        EXPECT_DOUBLE_EQ(error.minimumMs(), 4.0);
        EXPECT_DOUBLE_EQ(error.budgetMs(), 3.5);
        EXPECT_THAT(error.what(), HasSubstr("4 ms"));
        EXPECT_THAT(error.what(), HasSubstr("3.5 ms"));
    }
    // Exactly the minimum is feasible, and so is a budget above the maximum.
    EXPECT_NO_THROW(validateProblem(hand.problem(4.0)));
    EXPECT_NO_THROW(validateProblem(hand.problem(1e9)));
    EXPECT_NO_THROW(validateProblem(hand.problem(std::numeric_limits<double>::infinity())));
}

TEST(Problem, CombinationValidationNamesTheVariable) {
    HandProblem hand;
    const Problem problem = hand.problem();
    EXPECT_NO_THROW(validateCombination(problem, {2, 1, 0}));
    EXPECT_THAT(messageOf<ProblemError>([&] {
                    validateCombination(problem, {0, 2, 0});
                }),
                HasSubstr("combination[1] = 2, variable 1 has 2 levels"));
    EXPECT_THAT(messageOf<ProblemError>([&] {
                    validateCombination(problem, {0, -1, 0});
                }),
                HasSubstr("combination[1] = -1"));
    EXPECT_THAT(messageOf<ProblemError>([&] {
                    validateCombination(problem, {0, 0});
                }),
                HasSubstr("has 2 levels, the problem has 3"));
    EXPECT_EQ(formatCombination({0, 2, 1}), "[0, 2, 1]");
}

TEST(AdditiveCost, PredictsAndDeltasAgreeWithTheDefault) {
    const AdditiveCost cost(0.5, {{4.0, 2.0}, {3.0, 1.0, 0.25}});
    EXPECT_DOUBLE_EQ(cost.predictMs({0, 0}), 7.5);
    EXPECT_DOUBLE_EQ(cost.predictMs({1, 2}), 2.75);
    EXPECT_DOUBLE_EQ(cost.deltaMs({0, 0}, 1, 2), -2.75);
    EXPECT_DOUBLE_EQ(cost.Cost::deltaMs({0, 0}, 1, 2), -2.75);  // the generic two-prediction form
    EXPECT_THROW(AdditiveCost(-1.0, {{1.0}}), ProblemError);
    EXPECT_THAT(messageOf<ProblemError>([] { AdditiveCost(0.0, {{1.0}, {2.0, -3.0}}); }), HasSubstr("levelMs[1][1]"));
}

TEST(CheckedEvaluator, CachesAndCountsHitsIncludingRepeatsWithinABatch) {
    HandProblem hand;
    CheckedEvaluator checked(hand.problem());
    const std::vector<Combination> batch{{0, 1, 1}, {2, 1, 2}, {0, 1, 1}};
    std::vector<Score> scores(batch.size());
    ASSERT_EQ(checked.evaluateBatch(batch, scores), 3u);
    EXPECT_EQ(hand.evaluator.calls(), 2);
    EXPECT_EQ(checked.evaluations(), 2);
    EXPECT_EQ(checked.cacheHits(), 1);
    EXPECT_DOUBLE_EQ(scores[0].fitness, 0.6875);
    EXPECT_DOUBLE_EQ(scores[2].fitness, 0.6875);
    EXPECT_DOUBLE_EQ(scores[1].fitness, 0.125);

    // A combination already evaluated is never evaluated again.
    const auto again = checked.evaluate({2, 1, 2});
    ASSERT_TRUE(again.has_value());
    EXPECT_DOUBLE_EQ(again->fitness, 0.125);
    EXPECT_EQ(hand.evaluator.calls(), 2);
    EXPECT_EQ(checked.cacheHits(), 2);
    EXPECT_TRUE(checked.cached({0, 1, 1}).has_value());
    EXPECT_FALSE(checked.cached({0, 0, 0}).has_value());
}

TEST(CheckedEvaluator, EvaluationBudgetAnswersAPrefix) {
    HandProblem hand;
    CheckedEvaluator checked(hand.problem(), 2);
    const std::vector<Combination> batch{{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}};
    std::vector<Score> scores(batch.size());
    EXPECT_EQ(checked.evaluateBatch(batch, scores), 3u);  // the third new one does not fit
    EXPECT_EQ(checked.evaluations(), 2);
    EXPECT_TRUE(checked.budgetSpent());
    EXPECT_EQ(checked.remainingEvaluations(), 0);
    EXPECT_FALSE(checked.evaluate({2, 1, 2}).has_value());
    EXPECT_TRUE(checked.evaluate({1, 0, 0}).has_value());  // cached answers stay free
    EXPECT_EQ(hand.evaluator.calls(), 2);
}

TEST(CheckedEvaluator, RejectsInvalidCombinationsAndNonFiniteScores) {
    HandProblem hand;
    CheckedEvaluator checked(hand.problem());
    EXPECT_THROW(checked.evaluate({0, 5, 0}), ProblemError);
    EXPECT_EQ(hand.evaluator.calls(), 0);

    testing::FormulaEvaluator broken([](const Combination& c) { return c[0] == 1 ? std::nan("") : 0.5; });
    CheckedEvaluator checkedBroken(broken, {2, 2});
    EXPECT_TRUE(checkedBroken.evaluate({0, 1}).has_value());
    try {
        checkedBroken.evaluate({1, 1});
        FAIL() << "expected EvaluationError";
    } catch (const EvaluationError& error) {
        EXPECT_THAT(error.what(), HasSubstr("[1, 1]"));
    }
}

TEST(Repair, LeavesFeasibleCombinationsAlone) {
    HandProblem hand;
    const Problem problem = hand.problem();
    Combination combination{0, 1, 1};
    EXPECT_DOUBLE_EQ(repairToBudget(problem, combination), 8.0);
    EXPECT_EQ(combination, (Combination{0, 1, 1}));
}

TEST(Repair, WithoutSurrogateLowersTheLargestSaving) {
    HandProblem hand;
    const Problem problem = hand.problem(9.0);
    // All finest: 12 ms. Savings of one step: A 2, B 3, C 1 → B first (9 ms fits).
    Combination combination{0, 0, 0};
    EXPECT_DOUBLE_EQ(repairToBudget(problem, combination), 9.0);
    EXPECT_EQ(combination, (Combination{0, 1, 0}));
}

TEST(Repair, WithSurrogateLowersTheLeastLossPerMillisecond) {
    HandProblem hand;
    Problem problem = hand.problem(9.0);
    problem.surrogateLoss = hand.evaluator.loss();
    // Loss per ms of one step from all finest: A .125/2, B .25/3, C .0625/1 → A and C tie at
    // .0625; the larger saving (A, 2 ms) wins: 10 ms. Then A .25/1, B .25/3, C .0625 → C: 9 ms.
    Combination combination{0, 0, 0};
    EXPECT_DOUBLE_EQ(repairToBudget(problem, combination), 9.0);
    EXPECT_EQ(combination, (Combination{1, 0, 1}));
}

TEST(Repair, NonAdditiveCostStillEndsFeasible) {
    TableEvaluator evaluator({{0, 0.1, 0.2}, {0, 0.1, 0.2}, {0, 0.1, 0.2}});
    // GPU-bound at fine levels, CPU-bound at coarse ones; B's CPU cost rises when it coarsens.
    const MaxCost cost(1.0, {{6, 3, 1}, {6, 3, 1}, {6, 3, 1}}, {{1, 1, 1}, {1, 2, 4}, {1, 1, 1}});
    Problem problem;
    problem.levelCounts = {3, 3, 3};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 7.0;
    ASSERT_NO_THROW(validateProblem(problem));
    for (const Combination& start : {Combination{0, 0, 0}, Combination{0, 2, 0}, Combination{1, 1, 1}}) {
        Combination combination = start;
        const double ms = repairToBudget(problem, combination);
        EXPECT_LE(ms, 7.0) << formatCombination(start);
        EXPECT_DOUBLE_EQ(ms, cost.predictMs(combination));
        for (std::size_t i = 0; i < 3; ++i) EXPECT_GE(combination[i], start[i]);  // levels only coarsen
    }
}

}  // namespace
}  // namespace lodopt::optimizer
