// Properties every algorithm must have: determinism for a seed, feasibility for any budget,
// the same answer from a parallel evaluator, and sane behaviour on degenerate problems.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fixtures.hpp"

namespace lodopt::optimizer {
namespace {

using testing::FormulaEvaluator;
using ::testing::HasSubstr;
using testing::sameLog;
using testing::ThreadPoolEvaluator;

// Small enough for exhaustive (at most 4^6 = 4096 combinations), with hints for the heuristics.
SyntheticParameters smallSynthetic(std::uint64_t seed, double budgetFraction) {
    SyntheticParameters parameters;
    parameters.variables = 6;
    parameters.minLevels = 2;
    parameters.maxLevels = 4;
    parameters.pairDensity = 0.4;
    parameters.budgetFraction = budgetFraction;
    parameters.seed = seed;
    return parameters;
}

Termination shortRun() {
    Termination termination;
    termination.maxIterations = 10;
    termination.maxEvaluations = 200;
    return termination;
}

TEST(Algorithms, FactoryKnowsEveryNameAndRefusesOthers) {
    for (const std::string& name : algorithmNames()) EXPECT_EQ(makeAlgorithm(name, 3)->name(), name);
    try {
        makeAlgorithm("annealing");
        FAIL() << "expected std::invalid_argument";
    } catch (const std::invalid_argument& error) {
        EXPECT_THAT(error.what(), HasSubstr("annealing"));
        EXPECT_THAT(error.what(), HasSubstr("gapso, pso, ga, greedy"));
    }
}

TEST(Algorithms, SameSeedGivesTheSameResultAndLog) {
    SyntheticProblem synthetic(smallSynthetic(4, 0.4));
    const Problem problem = synthetic.problem();
    for (const std::string& name : algorithmNames()) {
        const auto algorithm = makeAlgorithm(name, 5);
        const Result first = algorithm->run(problem, shortRun());
        const Result second = makeAlgorithm(name, 5)->run(problem, shortRun());
        EXPECT_EQ(first.best, second.best) << name;
        EXPECT_EQ(first.bestScore.fitness, second.bestScore.fitness) << name;
        EXPECT_EQ(first.evaluations, second.evaluations) << name;
        EXPECT_EQ(first.cacheHits, second.cacheHits) << name;
        EXPECT_EQ(first.stopReason, second.stopReason) << name;
        EXPECT_TRUE(sameLog(first.log, second.log)) << name;
        // And the same object run again.
        const Result third = algorithm->run(problem, shortRun());
        EXPECT_TRUE(sameLog(first.log, third.log)) << name;
        EXPECT_EQ(first.algorithm, name);
    }
    // Different seeds explore differently (the logs of the stochastic ones differ).
    for (const char* name : {"gapso", "pso", "ga", "random"}) {
        const Result a = makeAlgorithm(name, 1)->run(problem, shortRun());
        const Result b = makeAlgorithm(name, 2)->run(problem, shortRun());
        EXPECT_FALSE(sameLog(a.log, b.log)) << name;
    }
}

TEST(Algorithms, EveryResultIsFeasibleForManyRandomBudgets) {
    Random random(99);
    for (int trial = 0; trial < 12; ++trial) {
        const double fraction = random.uniform();
        SyntheticProblem synthetic(smallSynthetic(static_cast<std::uint64_t>(trial) + 10, fraction));
        const Problem problem = synthetic.problem();
        const Result truth = Exhaustive().run(problem, Termination::none());
        for (const std::string& name : algorithmNames()) {
            const Result result = makeAlgorithm(name, static_cast<std::uint64_t>(trial))->run(problem, shortRun());
            EXPECT_LE(result.predictedMs, problem.budgetMs) << name << " budget fraction " << fraction;
            EXPECT_DOUBLE_EQ(result.predictedMs, synthetic.cost().predictMs(result.best)) << name;
            EXPECT_DOUBLE_EQ(result.bestScore.fitness, synthetic.evaluator().fitness(result.best)) << name;
            EXPECT_LE(result.bestScore.fitness, truth.bestScore.fitness) << name;
            EXPECT_LE(result.evaluations, 200) << name;
            ASSERT_FALSE(result.log.empty()) << name;
            EXPECT_EQ(result.log.back().bestFitness, result.bestScore.fitness) << name;
        }
    }
}

TEST(Algorithms, ParallelBatchEvaluationGivesTheSameResultAsSerial) {
    SyntheticProblem synthetic(smallSynthetic(21, 0.35));
    const Problem serial = synthetic.problem();
    ThreadPoolEvaluator pool(synthetic.evaluator(), 4);
    Problem parallel = serial;
    parallel.evaluator = &pool;
    for (const std::string& name : algorithmNames()) {
        const Result a = makeAlgorithm(name, 8)->run(serial, shortRun());
        const Result b = makeAlgorithm(name, 8)->run(parallel, shortRun());
        EXPECT_EQ(a.best, b.best) << name;
        EXPECT_EQ(a.bestScore.fitness, b.bestScore.fitness) << name;
        EXPECT_TRUE(sameLog(a.log, b.log)) << name;
    }
    EXPECT_GT(pool.batches(), 0);
}

TEST(Algorithms, BudgetBelowTheMinimumIsAClearErrorForEveryAlgorithm) {
    SyntheticProblem synthetic(smallSynthetic(3, 0.0));
    Problem problem = synthetic.problem();
    problem.budgetMs = synthetic.budgetMs() * 0.5;  // budgetFraction 0: budgetMs is the minimum
    for (const std::string& name : algorithmNames()) {
        try {
            makeAlgorithm(name)->run(problem, shortRun());
            ADD_FAILURE() << name << ": expected BudgetError";
        } catch (const BudgetError& error) {
            EXPECT_DOUBLE_EQ(error.minimumMs(), synthetic.budgetMs()) << name;
            EXPECT_THAT(error.what(), HasSubstr("cheapest")) << name;
        }
    }
    EXPECT_EQ(synthetic.evaluator().componentNames().size(), 2u);
}

TEST(Algorithms, OneVariable) {
    FormulaEvaluator evaluator([](const Combination& c) { return 1.0 - 0.2 * c[0]; });
    const AdditiveCost cost(0.0, {{5, 4, 3, 2, 1}});
    Problem problem;
    problem.levelCounts = {5};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 3.5;
    problem.hints.resize(1);
    problem.hints[0].distance = 1.0;
    problem.hints[0].projectedArea = 1.0;
    problem.hints[0].screenCoverage = 0.5;
    problem.hints[0].levelPixelError = {0, 0.5, 1, 2, 4};
    problem.hints[0].levelDeviation = {0, 0.5, 1, 2, 4};
    problem.hints[0].pixelsPerWorldUnit = 1.0;
    problem.hints[0].boundingRadius = 1.0;
    for (const std::string& name : algorithmNames()) {
        const Result result = makeAlgorithm(name, 2)->run(problem, shortRun());
        EXPECT_LE(result.predictedMs, 3.5) << name;
        if (name != "distance" && name != "screensize" && name != "importance") {
            EXPECT_EQ(result.best, (Combination{2})) << name;  // the finest level that fits
        }
    }
}

TEST(Algorithms, OneLevelEverywhere) {
    FormulaEvaluator evaluator([](const Combination&) { return 0.5; });
    const AdditiveCost cost(1.0, {{2.0}, {3.0}});
    Problem problem;
    problem.levelCounts = {1, 1};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 6.0;
    problem.hints.resize(2);
    for (auto& hints : problem.hints) {
        hints.distance = 3.0;
        hints.projectedArea = 2.0;
        hints.screenCoverage = 0.2;
        hints.levelScreenCoverage = {0.0};
        hints.levelDeviation = {0.0};
        hints.pixelsPerWorldUnit = 10.0;
        hints.boundingRadius = 1.0;
    }
    for (const std::string& name : algorithmNames()) {
        const Result result = makeAlgorithm(name)->run(problem, shortRun());
        EXPECT_EQ(result.best, (Combination{0, 0})) << name;
        EXPECT_EQ(result.evaluations, 1) << name;
    }
}

TEST(Algorithms, AllEqualFitnessBreaksTiesByTimeThenOrder) {
    FormulaEvaluator constant([](const Combination&) { return 0.25; });
    const AdditiveCost cost(0.0, {{3, 2, 1}, {3, 2, 1}, {3, 2, 1}});
    Problem problem;
    problem.levelCounts = {3, 3, 3};
    problem.evaluator = &constant;
    problem.cost = &cost;
    problem.budgetMs = 7.0;
    // Exhaustive: every feasible combination ties on fitness; the cheapest is all coarsest.
    EXPECT_EQ(Exhaustive().run(problem, Termination::none()).best, (Combination{2, 2, 2}));
    for (const char* name : {"gapso", "pso", "ga", "random"}) {
        const Result a = makeAlgorithm(name, 4)->run(problem, shortRun());
        const Result b = makeAlgorithm(name, 4)->run(problem, shortRun());
        EXPECT_EQ(a.best, b.best) << name;
        EXPECT_EQ(a.bestScore.fitness, 0.25) << name;
        EXPECT_LE(a.predictedMs, 7.0) << name;
    }
    // Equal time as well: the lexicographically smallest combination wins.
    const AdditiveCost flat(0.0, {{1, 1}, {1, 1}});
    Problem flatProblem;
    flatProblem.levelCounts = {2, 2};
    flatProblem.evaluator = &constant;
    flatProblem.cost = &flat;
    EXPECT_EQ(Exhaustive().run(flatProblem, Termination::none()).best, (Combination{0, 0}));
    EXPECT_TRUE(isBetter(0.5, 2.0, {1, 1}, 0.5, 3.0, {0, 0}));
    EXPECT_TRUE(isBetter(0.5, 2.0, {0, 1}, 0.5, 2.0, {1, 0}));
    EXPECT_FALSE(isBetter(0.5, 2.0, {1, 0}, 0.5, 2.0, {1, 0}));
    EXPECT_TRUE(isBetter(0.6, 9.0, {1, 1}, 0.5, 2.0, {0, 0}));
}

TEST(Algorithms, UnlimitedBudgetLetsTheExactOnesTakeTheReference) {
    SyntheticProblem synthetic(smallSynthetic(6, 1.0));
    Problem problem = synthetic.problem();
    problem.budgetMs = std::numeric_limits<double>::infinity();
    const Combination finest = finestCombination(problem);
    EXPECT_EQ(Exhaustive().run(problem, Termination::none()).best, finest);
    EXPECT_EQ(Mckp().run(problem, Termination::none()).best, finest);
    EXPECT_EQ(Greedy().run(problem, Termination::none()).best, finest);
    for (const std::string& name : algorithmNames()) {
        const Result result = makeAlgorithm(name)->run(problem, shortRun());
        EXPECT_TRUE(std::isfinite(result.predictedMs)) << name;
    }
}

TEST(Algorithms, ANonFiniteCostPredictionIsAClearError) {
    testing::FormulaEvaluator evaluator([](const Combination&) { return 0.5; });
    class BrokenCost final : public Cost {
    public:
        double predictMs(const Combination& c) const override { return c[0] == 0 ? std::nan("") : 1.0; }
    } cost;
    Problem problem;
    problem.levelCounts = {2};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 2.0;
    Combination finest{0};
    try {
        repairToBudget(problem, finest);
        FAIL() << "expected ProblemError";
    } catch (const ProblemError& error) {
        EXPECT_THAT(error.what(), HasSubstr("[0]"));
    }
}

TEST(Termination, ValidationNamesTheFieldAndReasonsHaveNames) {
    auto messageFor = [](auto change) {
        Termination termination;
        change(termination);
        try {
            termination.validate();
        } catch (const std::invalid_argument& error) {
            return std::string(error.what());
        }
        return std::string("<no exception>");
    };
    EXPECT_THAT(messageFor([](Termination& t) { t.maxIterations = -1; }), HasSubstr("maxIterations = -1"));
    EXPECT_THAT(messageFor([](Termination& t) { t.stableIterations = -2; }), HasSubstr("stableIterations = -2"));
    EXPECT_THAT(messageFor([](Termination& t) { t.stableTolerance = std::nan(""); }), HasSubstr("stableTolerance"));
    EXPECT_THAT(messageFor([](Termination& t) { t.maxEvaluations = -5; }), HasSubstr("maxEvaluations = -5"));
    EXPECT_THAT(messageFor([](Termination& t) { t.maxSeconds = -1.0; }), HasSubstr("maxSeconds"));
    EXPECT_EQ(messageFor([](Termination&) {}), "<no exception>");
    EXPECT_FALSE(Termination::none().guaranteesStop());
    EXPECT_TRUE(Termination::paper().guaranteesStop());
    EXPECT_EQ(toString(StopReason::Completed), "completed");
    EXPECT_EQ(toString(StopReason::MaxIterations), "max-iterations");
    EXPECT_EQ(toString(StopReason::Stable), "stable");
    EXPECT_EQ(toString(StopReason::MaxEvaluations), "max-evaluations");
    EXPECT_EQ(toString(StopReason::WallTime), "wall-time");
}

TEST(Algorithms, ConstructedParametersAreValidatedForEveryAlgorithm) {
    EXPECT_THROW(DistanceHeuristic(DistanceParameters{{-1.0}}), std::invalid_argument);
    ImportanceParameters zeroAlphas;
    zeroAlphas.alpha1 = 0.0;
    zeroAlphas.alpha2 = 0.0;
    EXPECT_THROW(ImportanceHeuristic{zeroAlphas}, std::invalid_argument);
    ImportanceParameters badBenchmark;
    badBenchmark.benchmark = ImportanceView{1.0, 0.0, 0.0};
    EXPECT_THROW(ImportanceHeuristic{badBenchmark}, std::invalid_argument);
    EXPECT_THROW(SyntheticProblem(SyntheticParameters{0}), std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::optimizer
