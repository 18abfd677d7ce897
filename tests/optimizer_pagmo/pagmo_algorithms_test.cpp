// pagmo2's optimizers on lodopt's problem (optimizer/pagmo_algorithms.hpp): they reach the
// optimum where it is known, count evaluations as lodopt's searches do, stay within the budget
// and repeat exactly for a seed.
#include "optimizer/pagmo_algorithms.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <stdexcept>

#include "../optimizer/fixtures.hpp"
#include "evaluation/search_view.hpp"
#include "optimizer/search.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::optimizer {
namespace {

using testing::HarborProblem;

// Remembers every combination it is asked to score, to check what the search counted.
class RecordingEvaluator final : public Evaluator {
public:
    explicit RecordingEvaluator(Evaluator& inner) : mInner(inner) {}
    Score evaluate(const Combination& combination) override {
        ++calls;
        seen.insert(combination);
        return mInner.evaluate(combination);
    }
    int calls = 0;
    std::set<Combination> seen;

private:
    Evaluator& mInner;
};

Result runPagmo(const std::string& name, const Problem& problem, std::uint64_t seed, Termination termination) {
    PagmoParameters parameters;
    parameters.algorithm = name;
    parameters.seed = seed;
    return PagmoAlgorithm(parameters).run(problem, termination);
}

TEST(PagmoAlgorithms, EveryAlgorithmReachesTheExhaustiveOptimumOfASmallProblem) {
    HarborProblem harbor;
    const Problem problem = harbor.problem(9.0);
    const Result optimum = makeAlgorithm("exhaustive")->run(problem, Termination::none());
    Termination termination;
    termination.maxIterations = 200;
    termination.stableIterations = 0;
    for (const std::string& name : pagmoAlgorithmNames()) {
        const Result result = runPagmo(name, problem, 1, termination);
        EXPECT_EQ(result.algorithm, name);
        EXPECT_LE(result.predictedMs, 9.0) << name;
        EXPECT_EQ(result.bestScore.fitness, optimum.bestScore.fitness) << name;
        // 125 combinations: no algorithm can pay for more.
        EXPECT_LE(result.evaluations, 125) << name;
    }
}

TEST(PagmoAlgorithms, CountEachNewCombinationOnceAndStopAtTheEvaluationBudget) {
    SyntheticParameters parameters;  // 30 variables, 4-6 levels
    SyntheticProblem synthetic(parameters);
    Problem problem = synthetic.problem();
    RecordingEvaluator recording(*problem.evaluator);
    problem.evaluator = &recording;
    Termination termination;
    termination.maxIterations = 1000;
    termination.stableIterations = 0;
    termination.maxEvaluations = 150;
    for (const std::string& name : pagmoAlgorithmNames()) {
        recording.calls = 0;
        recording.seen.clear();
        const Result result = runPagmo(name, problem, 2, termination);
        // Every evaluation is a new combination; the budget is met exactly (the space is huge).
        EXPECT_EQ(result.evaluations, 150) << name;
        EXPECT_EQ(recording.calls, 150) << name;
        EXPECT_EQ(recording.seen.size(), 150u) << name;
        EXPECT_EQ(result.stopReason, StopReason::MaxEvaluations) << name;
        EXPECT_LE(result.predictedMs, problem.budgetMs) << name;
        EXPECT_TRUE(recording.seen.count(result.best)) << name;
        // The log's last row counts what the result counts.
        ASSERT_FALSE(result.log.empty());
        EXPECT_EQ(result.log.back().evaluations, 150) << name;
        EXPECT_EQ(result.log.back().bestFitness, result.bestScore.fitness) << name;
    }
}

TEST(PagmoAlgorithms, ASeedRepeatsTheRunAndAnotherSeedChangesIt) {
    SyntheticProblem synthetic(SyntheticParameters{});
    const Problem problem = synthetic.problem();
    Termination termination;
    termination.maxIterations = 15;
    int differing = 0;
    for (const std::string& name : pagmoAlgorithmNames()) {
        const Result a = runPagmo(name, problem, 7, termination);
        const Result b = runPagmo(name, problem, 7, termination);
        EXPECT_EQ(a.best, b.best) << name;
        EXPECT_TRUE(testing::sameLog(a.log, b.log)) << name;
        const Result c = runPagmo(name, problem, 8, termination);
        differing += testing::sameLog(a.log, c.log) ? 0 : 1;
    }
    EXPECT_EQ(differing, int(pagmoAlgorithmNames().size()));
}

TEST(PagmoAlgorithms, RegisteredNamesRunThroughTheToolsSearch) {
    registerPagmoAlgorithms();
    registerPagmoAlgorithms();  // a second call does nothing
    const std::vector<std::string>& names = algorithmNames();
    for (const std::string& name : pagmoAlgorithmNames()) {
        EXPECT_EQ(std::count(names.begin(), names.end(), name), 1) << name;
        EXPECT_TRUE(isSeededAlgorithm(name)) << name;
    }
    HarborProblem harbor;
    const Problem problem = harbor.problem(9.0);
    SearchOptions options;
    options.algorithm = "pagmo:sade";
    options.seed = 3;
    const Result searched = runSearch(problem, options);
    const Result direct = runPagmo("pagmo:sade", problem, 3, options.termination);
    EXPECT_EQ(searched.best, direct.best);
    EXPECT_TRUE(testing::sameLog(searched.log, direct.log));
    EXPECT_THROW(registerAlgorithm(
                     "pagmo:sade", [](std::uint64_t) { return makeAlgorithm("gapso"); }, true),
                 std::invalid_argument);
}

TEST(PagmoAlgorithms, AVariableWithOneLevelStaysAtIt) {
    // Variable 1 has a single level: its bounds are [0, 0] (integer) or [0, 1] (continuous).
    testing::FormulaEvaluator evaluator([](const Combination& c) { return 1.0 - 0.1 * c[0] - 0.04 * c[2]; });
    AdditiveCost cost{0.0, {{4.0, 2.0, 1.0}, {1.0}, {3.0, 2.0, 1.0}}};
    Problem problem;
    problem.levelCounts = {3, 1, 3};
    problem.evaluator = &evaluator;
    problem.cost = &cost;
    problem.budgetMs = 6.0;
    Termination termination;
    termination.maxIterations = 30;
    for (const std::string& name : pagmoAlgorithmNames()) {
        const Result result = runPagmo(name, problem, 1, termination);
        EXPECT_EQ(result.best[1], 0) << name;
        EXPECT_LE(result.predictedMs, 6.0) << name;
        // The optimum: 4 + 1 + 1 = 6 ms, fitness 0.92 (the next best, {1, 0, 0}, 0.90).
        EXPECT_EQ(result.best, (Combination{0, 0, 2})) << name;
    }
}

TEST(PagmoAlgorithms, RefusesAnUnknownNameAndATooSmallPopulation) {
    PagmoParameters parameters;
    parameters.algorithm = "pagmo:nope";
    EXPECT_THROW(PagmoAlgorithm{parameters}, std::invalid_argument);
    parameters.algorithm = "pagmo:sade";
    parameters.population = 6;
    EXPECT_THROW(PagmoAlgorithm{parameters}, std::invalid_argument);
    parameters.population = 7;
    EXPECT_NO_THROW(PagmoAlgorithm{parameters});
}

// The real harbor (rendered, scored by the fast path, timed by the shipped profile): pagmo's
// SADE finds the exhaustive optimum.
TEST(PagmoAlgorithms, SadeFindsTheExhaustiveOptimumOfTheRenderedHarbor) {
    const scenes::Scene scene = scenes::makeHarborScene();
    renderer::RenderSettings settings;
    settings.width = settings.height = 96;
    renderer::Renderer renderer(scene, settings);
    const auto model = timemodel::modelFromProfile(timemodel::shippedProfile("harbor"));
    const evaluation::FrameTimeEstimator estimate = [&](const timemodel::FrameFeatures& f) {
        return model->estimateMs(f);
    };
    evaluation::SearchViewSettings viewSettings;
    viewSettings.budgetMs = 8.0;
    const evaluation::SearchView view = evaluation::prepareSearchView(scene, scene.views[0], renderer, {}, estimate,
                                                                      model->readFeatures(), viewSettings);
    const Result optimum = makeAlgorithm("exhaustive")->run(view.problem, Termination::none());
    Termination termination;
    termination.maxIterations = 100;
    const Result sade = runPagmo("pagmo:sade", view.problem, 1, termination);
    EXPECT_EQ(sade.bestScore.fitness, optimum.bestScore.fitness);
    EXPECT_EQ(sade.best, optimum.best);
    EXPECT_LE(sade.evaluations, optimum.evaluations);
}

}  // namespace
}  // namespace lodopt::optimizer
