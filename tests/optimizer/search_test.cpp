// One search as the tool runs it (optimizer/search.hpp).
#include "optimizer/search.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "fixtures.hpp"

namespace lodopt::optimizer {
namespace {

using testing::HarborProblem;

TEST(Search, PlainAlgorithmsRunAsMakeAlgorithmRunsThem) {
    HarborProblem harbor;
    const Problem problem = harbor.problem(9.0);
    SearchOptions options;
    options.algorithm = "gapso";
    options.seed = 3;
    const Result direct = makeAlgorithm("gapso", 3)->run(problem, options.termination);
    const Result searched = runSearch(problem, options);
    EXPECT_EQ(searched.best, direct.best);
    EXPECT_EQ(searched.evaluations, direct.evaluations);
    EXPECT_TRUE(testing::sameLog(searched.log, direct.log));
}

TEST(Search, SwarmStartsFromOtherAnswersAndCountsTheirEvaluations) {
    HarborProblem harbor;
    const Problem problem = harbor.problem(9.0);
    SearchOptions options;
    options.algorithm = "gapso";
    options.startFrom = {"greedy", "mckp"};
    const Result started = runSearch(problem, options);
    const Result greedy = makeAlgorithm("greedy", 1)->run(problem, Termination{});
    // The swarm never ends below an answer it started from.
    EXPECT_GE(started.bestScore.fitness, greedy.bestScore.fitness);
    EXPECT_LE(started.predictedMs, 9.0);
    EXPECT_GT(started.evaluations, greedy.evaluations);  // the starts' evaluations count too

    options.startFrom = {"gapso"};
    EXPECT_THROW(runSearch(problem, options), std::invalid_argument);
}

TEST(Search, FillDefaultsFollowThePaperSwitch) {
    SearchOptions options;
    EXPECT_EQ(effectiveFillProbability(options), GapsoParameters{}.fillProbability);
    options.paper = true;
    EXPECT_EQ(effectiveFillProbability(options), GapsoParameters::paper().fillProbability);
    options.fillProbability = 0.4;
    EXPECT_EQ(effectiveFillProbability(options), 0.4);
    EXPECT_TRUE(isSwarmAlgorithm("pso"));
    EXPECT_FALSE(isSwarmAlgorithm("mckp"));
    EXPECT_TRUE(isStartAlgorithm("screensize"));
}

TEST(Search, AProblemWithoutVariablesEvaluatesItsOneCombination) {
    testing::TableEvaluator evaluator({});
    const AdditiveCost cost(2.0, {});
    Problem problem;
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 3.0;
    SearchOptions options;
    const Result result = runSearch(problem, options);
    EXPECT_EQ(result.evaluations, 1);
    EXPECT_EQ(result.predictedMs, 2.0);
    EXPECT_EQ(result.log.size(), 1u);
    problem.budgetMs = 1.0;
    EXPECT_THROW(runSearch(problem, options), BudgetError);
}

TEST(Search, RegisteredAlgorithmsJoinTheNamesAndRunByName) {
    // An algorithm from another library: greedy's answer under another name.
    class Renamed final : public Algorithm {
    public:
        std::string_view name() const override { return "test:greedy"; }
        Result run(const Problem& problem, const Termination& termination) const override {
            Result result = makeAlgorithm("greedy")->run(problem, termination);
            result.algorithm = "test:greedy";
            return result;
        }
    };
    const std::size_t before = algorithmNames().size();
    EXPECT_FALSE(isSeededAlgorithm("test:greedy"));
    registerAlgorithm(
        "test:greedy", [](std::uint64_t) { return std::make_unique<Renamed>(); }, false);
    ASSERT_EQ(algorithmNames().size(), before + 1);
    EXPECT_EQ(algorithmNames().back(), "test:greedy");
    EXPECT_FALSE(isSeededAlgorithm("test:greedy"));
    EXPECT_TRUE(isSeededAlgorithm("gapso"));
    EXPECT_FALSE(isSeededAlgorithm("mckp"));
    HarborProblem harbor;
    const Problem problem = harbor.problem(9.0);
    SearchOptions options;
    options.algorithm = "test:greedy";
    const Result renamed = runSearch(problem, options);
    const Result greedy = makeAlgorithm("greedy")->run(problem, Termination{});
    EXPECT_EQ(renamed.algorithm, "test:greedy");
    EXPECT_EQ(renamed.best, greedy.best);
    // A name already known, or an empty one, is refused.
    EXPECT_THROW(registerAlgorithm(
                     "test:greedy", [](std::uint64_t) { return std::make_unique<Renamed>(); }, false),
                 std::invalid_argument);
    EXPECT_THROW(registerAlgorithm(
                     "gapso", [](std::uint64_t) { return std::make_unique<Renamed>(); }, true),
                 std::invalid_argument);
    EXPECT_THROW(registerAlgorithm(
                     "", [](std::uint64_t) { return std::make_unique<Renamed>(); }, true),
                 std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::optimizer
