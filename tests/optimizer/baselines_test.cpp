// Greedy, exhaustive, random, mckp and the hint-driven heuristics on hand-made problems.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures.hpp"

namespace lodopt::optimizer {
namespace {

using testing::HandProblem;
using ::testing::HasSubstr;
using testing::HintProblem;
using testing::TableEvaluator;

constexpr double kDegree = 3.14159265358979323846 / 180.0;

TEST(Exhaustive, FindsTheHandComputedOptimum) {
    HandProblem hand;
    const Result result = Exhaustive().run(hand.problem(), Termination::none());
    EXPECT_EQ(result.best, (Combination{0, 1, 1}));
    EXPECT_DOUBLE_EQ(result.bestScore.fitness, 0.6875);
    EXPECT_DOUBLE_EQ(result.predictedMs, 8.0);
    EXPECT_EQ(result.stopReason, StopReason::Completed);
    // 18 combinations; those within 8 ms are evaluated, each once.
    int feasible = 0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 3; ++c) feasible += hand.cost.predictMs({a, b, c}) <= 8.0;
    EXPECT_EQ(result.evaluations, feasible);
    EXPECT_EQ(hand.evaluator.calls(), feasible);
}

TEST(Exhaustive, RefusesLargeSpacesAndHonoursTheEvaluationBudget) {
    HandProblem hand;
    ExhaustiveParameters small;
    small.maxCombinations = 10;
    try {
        Exhaustive(small).run(hand.problem(), Termination::none());
        FAIL() << "expected ProblemError";
    } catch (const ProblemError& error) {
        EXPECT_THAT(error.what(), HasSubstr("18"));
    }
    EXPECT_EQ(hand.evaluator.calls(), 0);
    ExhaustiveParameters batched;
    batched.batchSize = 2;
    Termination termination = Termination::none();
    termination.maxEvaluations = 3;
    const Result result = Exhaustive(batched).run(hand.problem(), termination);
    EXPECT_EQ(result.stopReason, StopReason::MaxEvaluations);
    EXPECT_EQ(result.evaluations, 3);
    EXPECT_THROW(Exhaustive(ExhaustiveParameters{0.5, 1}), std::invalid_argument);
    EXPECT_THROW(Exhaustive(ExhaustiveParameters{10, 0}), std::invalid_argument);
}

TEST(Greedy, ClimbsByGainPerMillisecondToTheHandOptimum) {
    // From [2,1,2] (4 ms): A→1 gains .25 for 1 ms; then C→1 .1875/1 ms; then A→0 and C→0 both
    // .0625/ms, A has the larger gain; then nothing fits: [0,1,1], the optimum here.
    HandProblem hand;
    const Result result = Greedy().run(hand.problem(), Termination::none());
    EXPECT_EQ(result.best, (Combination{0, 1, 1}));
    EXPECT_EQ(result.stopReason, StopReason::Completed);
    EXPECT_EQ(result.log.size(), 4u);  // the start and three steps
    GreedyParameters surrogate;
    surrogate.benefit = BenefitSource::Surrogate;
    Problem withTable = hand.problem();
    withTable.surrogateLoss = hand.evaluator.loss();
    const Result fromTable = Greedy(surrogate).run(withTable, Termination::none());
    EXPECT_EQ(fromTable.best, (Combination{0, 1, 1}));
    EXPECT_EQ(fromTable.evaluations, 1);
    // Without a table the surrogate is measured: 1 + 2 + 1 + 2 evaluations, the result cached.
    const Result measured = Greedy(surrogate).run(hand.problem(), Termination::none());
    EXPECT_EQ(measured.best, (Combination{0, 1, 1}));
    EXPECT_EQ(measured.evaluations, 7);
}

TEST(Greedy, ItsPathCanMissTheOptimum) {
    // Two objects; budget 10. Greedy takes B's cheap step first (gain .3 for 1 ms, against A's
    // .4 for 8 ms) and then cannot afford A: its path ends at [1, 0], fitness .6; the optimum is
    // [0, 1], fitness .7 (A alone is worth more).
    //   A: loss 0 / .4 at 9 / 1 ms;  B: loss 0 / .3 at 2 / 1 ms (base 0).
    TableEvaluator evaluator({{0.0, 0.4}, {0.0, 0.3}});
    const AdditiveCost cost(0.0, {{9.0, 1.0}, {2.0, 1.0}});
    Problem problem;
    problem.levelCounts = {2, 2};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 10.0;
    problem.surrogateLoss = evaluator.loss();
    GreedyParameters surrogate;
    surrogate.benefit = BenefitSource::Surrogate;
    EXPECT_EQ(Greedy(surrogate).run(problem, Termination::none()).best, (Combination{1, 0}));
    // With evaluator benefits greedy evaluated [0, 1] as a candidate step on the way, and every
    // algorithm returns the best combination it evaluated.
    const Result evaluated = Greedy().run(problem, Termination::none());
    EXPECT_EQ(evaluated.best, (Combination{0, 1}));
    EXPECT_EQ(evaluated.evaluations, 3);
    EXPECT_EQ(Exhaustive().run(problem, Termination::none()).best, (Combination{0, 1}));
    EXPECT_EQ(Mckp().run(problem, Termination::none()).best, (Combination{0, 1}));
}

TEST(RandomSearch, StaysFeasibleAndSpendsExactlyTheEvaluationBudget) {
    HandProblem hand;
    Termination termination = Termination::none();
    termination.maxEvaluations = 9;
    termination.maxIterations = 1000;
    const Result result = RandomSearch().run(hand.problem(), termination);
    EXPECT_LE(result.predictedMs, 8.0);
    EXPECT_EQ(result.evaluations, 9);
    EXPECT_EQ(result.stopReason, StopReason::MaxEvaluations);
    EXPECT_THROW(RandomSearch(RandomSearchParameters{0, 1}), std::invalid_argument);
}

TEST(Mckp, SolverMatchesBruteForceOnRandomAdditiveTables) {
    Random random(11);
    for (int trial = 0; trial < 200; ++trial) {
        const int variables = 1 + random.belowInt(4);
        std::vector<std::vector<double>> loss(variables);
        std::vector<std::vector<double>> cost(variables);
        std::vector<int> levels(variables);
        for (int i = 0; i < variables; ++i) {
            levels[i] = 1 + random.belowInt(4);
            for (int l = 0; l < levels[i]; ++l) {
                loss[i].push_back(random.belowInt(50) / 64.0);
                cost[i].push_back(static_cast<double>(random.belowInt(10)));  // whole ms: exact with width 1
            }
        }
        const double capacity = static_cast<double>(random.belowInt(25));
        // Brute force over the mixed-radix space.
        double bestLoss = std::numeric_limits<double>::infinity();
        Combination combination(variables, 0);
        for (bool done = false; !done;) {
            double l = 0.0;
            double c = 0.0;
            for (int i = 0; i < variables; ++i) {
                l += loss[i][combination[i]];
                c += cost[i][combination[i]];
            }
            if (c <= capacity) bestLoss = std::min(bestLoss, l);
            int i = variables - 1;
            while (i >= 0 && ++combination[i] == levels[i]) combination[i--] = 0;
            done = i < 0;
        }
        // One bucket per ms of the capacity left after each variable's cheapest level, so that
        // whole-ms costs are exact multiples of the step.
        double cheapest = 0.0;
        for (int i = 0; i < variables; ++i) cheapest += *std::min_element(cost[i].begin(), cost[i].end());
        const int buckets = std::max(1, static_cast<int>(capacity - cheapest));
        const Combination answer = solveMckp(loss, cost, capacity, buckets);
        if (bestLoss == std::numeric_limits<double>::infinity()) {
            EXPECT_TRUE(answer.empty()) << "trial " << trial;
            continue;
        }
        ASSERT_EQ(answer.size(), static_cast<std::size_t>(variables)) << "trial " << trial;
        double answerLoss = 0.0;
        double answerCost = 0.0;
        for (int i = 0; i < variables; ++i) {
            answerLoss += loss[i][answer[i]];
            answerCost += cost[i][answer[i]];
        }
        EXPECT_LE(answerCost, capacity) << "trial " << trial;
        EXPECT_DOUBLE_EQ(answerLoss, bestLoss) << "trial " << trial;
    }
}

TEST(Mckp, IsOptimalOnAnAdditiveProblemLikeExhaustive) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        SyntheticParameters parameters;
        parameters.variables = 6;
        parameters.minLevels = 2;
        parameters.maxLevels = 5;
        parameters.interactionWeight = 0.0;  // additive: the surrogate is exact
        parameters.budgetFraction = 0.1 * static_cast<double>(seed);
        parameters.seed = seed;
        SyntheticProblem synthetic(parameters);
        const Problem problem = synthetic.problem();
        const Result truth = Exhaustive().run(problem, Termination::none());
        const Result mckp = Mckp().run(problem, Termination::none());
        EXPECT_LE(mckp.predictedMs, problem.budgetMs);
        // Costs are real numbers here, so the 10000-bucket rounding may only cost a hair.
        EXPECT_NEAR(mckp.bestScore.fitness, truth.bestScore.fitness, 1e-3) << "seed " << seed;
        EXPECT_EQ(mckp.evaluations, surrogateEvaluations(problem.levelCounts) + 1);
    }
}

TEST(Mckp, EqualsExhaustiveExactlyOnAdditiveProblemsWithWholeMillisecondCosts) {
    Random random(5);
    for (int trial = 0; trial < 30; ++trial) {
        const int variables = 2 + random.belowInt(4);
        std::vector<std::vector<double>> loss(variables);
        std::vector<std::vector<double>> levelMs(variables);
        std::vector<int> levels(variables);
        for (int i = 0; i < variables; ++i) {
            levels[i] = 1 + random.belowInt(5);
            double ms = 1.0 + random.belowInt(3);
            for (int l = levels[i] - 1; l >= 0; --l) {  // finer levels cost more
                levelMs[i].insert(levelMs[i].begin(), ms);
                ms += random.belowInt(4);
            }
            for (int l = 0; l < levels[i]; ++l) loss[i].push_back(l == 0 ? 0.0 : random.belowInt(40) / 128.0);
        }
        TableEvaluator evaluator(loss);
        const AdditiveCost cost(0.0, levelMs);
        Problem problem;
        problem.levelCounts = levels;
        problem.evaluator = &evaluator;
        problem.cost = &cost;
        const double minimum = cost.predictMs(coarsestCombination(problem));
        const double maximum = cost.predictMs(finestCombination(problem));
        const int slack = random.belowInt(static_cast<int>(maximum - minimum) + 1);
        problem.budgetMs = minimum + slack;
        // One bucket per ms of slack: every cost delta is a whole number of buckets.
        const Result mckp = Mckp(MckpParameters{std::max(1, slack)}).run(problem, Termination::none());
        const Result truth = Exhaustive().run(problem, Termination::none());
        EXPECT_EQ(mckp.bestScore.fitness, truth.bestScore.fitness) << "trial " << trial;
        EXPECT_LE(mckp.predictedMs, problem.budgetMs) << "trial " << trial;
    }
}

TEST(Mckp, HandProblemWithTableNeedsOneEvaluation) {
    HandProblem hand;
    Problem problem = hand.problem();
    problem.surrogateLoss = hand.evaluator.loss();
    const Result result = Mckp().run(problem, Termination::none());
    EXPECT_EQ(result.best, (Combination{0, 1, 1}));
    EXPECT_EQ(result.evaluations, 1);
    // Unlimited budget: every variable at its least-loss level.
    EXPECT_EQ(Mckp().run(hand.problem(1e9), Termination::none()).best, (Combination{0, 0, 0}));
    Termination tooFew = Termination::none();
    tooFew.maxEvaluations = 3;
    EXPECT_THROW(Mckp().run(hand.problem(), tooFew), std::invalid_argument);
    EXPECT_THROW(Mckp(MckpParameters{0}), std::invalid_argument);
}

TEST(Mckp, NonAdditiveCostIsRepairedToTheBudget) {
    TableEvaluator evaluator({{0, 0.1, 0.3}, {0, 0.1, 0.3}, {0, 0.2, 0.3}});
    const testing::MaxCost cost(0.5, {{4, 2, 1}, {4, 2, 1}, {4, 2, 1}}, {{3, 2, 1}, {3, 2, 1}, {3, 2, 1}});
    Problem problem;
    problem.levelCounts = {3, 3, 3};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    for (double budget : {3.5, 5.0, 6.5, 8.0, 12.5}) {
        problem.budgetMs = budget;
        const Result result = Mckp().run(problem, Termination::none());
        EXPECT_LE(result.predictedMs, budget);
    }
}

TEST(Importance, ReproducesDong2015Table4) {
    const ImportanceView benchmark{15.0, 0.0, 6.0};
    auto importanceAt = [&](double d, double degrees, double s) {
        return importance(ImportanceView{d, degrees * kDegree, s}, benchmark, 0.6, 0.4);
    };
    EXPECT_DOUBLE_EQ(importanceAt(15, 0, 6), 1.0);
    EXPECT_NEAR(importanceAt(15, 30, 6), 0.75, 0.005);
    EXPECT_NEAR(importanceAt(15, 45, 9), 0.69, 0.01);
    EXPECT_NEAR(importanceAt(9, 25, 11), 1.35, 0.01);
    EXPECT_NEAR(importanceAt(9, 25, 5), 0.98, 0.01);
}

TEST(Distance, ThresholdsGivenOrDerivedThenRepaired) {
    HintProblem hints;
    DistanceParameters given;
    given.thresholds = {8.0, 16.0};
    EXPECT_EQ(distanceLevels(hints.problem(12), given), (Combination{0, 1, 2}));
    // Derived: the range [5, 20] in three bands per variable: t = 0, 0.4, 1.
    EXPECT_EQ(distanceLevels(hints.problem(12), DistanceParameters{}), (Combination{0, 1, 2}));
    const Result fits = DistanceHeuristic(given).run(hints.problem(7.0), Termination::none());
    EXPECT_EQ(fits.best, (Combination{0, 1, 2}));
    EXPECT_EQ(fits.evaluations, 1);
    const Result repaired = DistanceHeuristic(given).run(hints.problem(5.0), Termination::none());
    EXPECT_LE(repaired.predictedMs, 5.0);
    EXPECT_THROW(DistanceHeuristic(DistanceParameters{{5.0, 3.0}}), std::invalid_argument);
    HandProblem hand;  // no hints
    EXPECT_THROW(DistanceHeuristic().run(hand.problem(), Termination::none()), ProblemError);
}

TEST(Importance, RaisesMostImportantFirstAndLowersLeastImportantFirst) {
    HintProblem hints;
    ImportanceParameters parameters;
    parameters.distance.thresholds = {8.0, 16.0};
    const ImportanceHeuristic heuristic(parameters);
    const auto importances = heuristic.importances(hints.problem(12));
    EXPECT_GT(importances[0], 1.0);  // median benchmark: the middle object has I = 1
    EXPECT_DOUBLE_EQ(importances[1], 1.0);
    EXPECT_LT(importances[2], 1.0);
    // Start [0, 1, 2] = 7 ms. Budget 9: raise near (already 0), then middle to 0 (9 ms).
    EXPECT_EQ(heuristic.run(hints.problem(9.0), Termination::none()).best, (Combination{0, 0, 2}));
    // Budget 10: then far can take one step (10 ms); budget 9.5 it cannot.
    EXPECT_EQ(heuristic.run(hints.problem(10.0), Termination::none()).best, (Combination{0, 0, 1}));
    EXPECT_EQ(heuristic.run(hints.problem(9.5), Termination::none()).best, (Combination{0, 0, 2}));
    // Budget 5: lower far (already coarsest), then middle to 2 (6 ms), then near (I > 1) to 1.
    EXPECT_EQ(heuristic.run(hints.problem(5.0), Termination::none()).best, (Combination{1, 2, 2}));
    // Budget 6: the I > 1 object keeps its level.
    EXPECT_EQ(heuristic.run(hints.problem(6.0), Termination::none()).best, (Combination{0, 2, 2}));
    ImportanceParameters bad;
    bad.alpha1 = -1;
    EXPECT_THROW(ImportanceHeuristic{bad}, std::invalid_argument);
}

TEST(ScreenSize, UsesCoverageThresholdsOrPixelErrorThenLowersSmallestFirst) {
    HintProblem hints;
    Problem problem = hints.problem(12.0);
    problem.hints[0].levelScreenCoverage = {0.5, 0.2, 0.0};  // 0.6 → level 0
    problem.hints[1].levelScreenCoverage = {0.5, 0.2, 0.0};  // 0.3 → level 1
    problem.hints[2].levelPixelError = {0.0, 0.8, 3.0};      // tolerance 1 px → level 1
    EXPECT_EQ(screenSizeLevels(problem, ScreenSizeParameters{}), (Combination{0, 1, 1}));
    EXPECT_EQ(ScreenSizeHeuristic().run(problem, Termination::none()).best, (Combination{0, 1, 1}));
    problem.budgetMs = 6.0;  // 8 ms → lower the smallest (far, to 2: 7 ms), then middle (6 ms)
    EXPECT_EQ(ScreenSizeHeuristic().run(problem, Termination::none()).best, (Combination{0, 2, 2}));
    problem.hints[2].levelPixelError.clear();
    EXPECT_THROW(ScreenSizeHeuristic().run(problem, Termination::none()), ProblemError);
    EXPECT_THROW(ScreenSizeHeuristic(ScreenSizeParameters{0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::optimizer
