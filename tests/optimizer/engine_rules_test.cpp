// The engines' automatic rules (optimizer/engine_rules.hpp) on a problem worked out by hand.
#include "optimizer/engine_rules.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "fixtures.hpp"
#include "optimizer/algorithm.hpp"

namespace lodopt::optimizer {
namespace {

using testing::HintProblem;

// HintProblem's three objects (fixtures.hpp: 4 / 2 / 1 ms at levels 0 / 1 / 2, 12 ms all finest,
// 3 ms all coarsest; screen sizes 0.6, 0.3, 0.1), with
//                          near    middle   far
//   pixels per world unit  100       50      10
//   bounding radius          1        1       1
//   deviation at levels 1, 2: 0.005, 0.02 (pixelerror); 0.01, 0.04 (unreal-auto)
// pixelerror's thresholds (deviation x pixels per unit): near 0.5, 2; middle 0.25, 1; far 0.05, 0.2.
struct RuleProblem {
    HintProblem base;
    Problem problem(double budgetMs, double deviation1, double deviation2) {
        Problem p = base.problem(budgetMs);
        const double pixelsPerUnit[] = {100, 50, 10};
        for (int i = 0; i < 3; ++i) {
            p.hints[i].pixelsPerWorldUnit = pixelsPerUnit[i];
            p.hints[i].boundingRadius = 1.0;
            p.hints[i].levelDeviation = {0.0, deviation1, deviation2};
        }
        return p;
    }
};

Result runRule(EngineRule rule, const Problem& problem, EngineRuleParameters parameters = {}) {
    return EngineRuleHeuristic(rule, parameters).run(problem, Termination::none());
}

TEST(EngineRules, PixelErrorTakesTheCoarsestLevelWithinTheTolerance) {
    RuleProblem rules;
    const Problem problem = rules.problem(12.0, 0.005, 0.02);
    const auto thresholds = engineRuleThresholds(problem, EngineRule::PixelError);
    EXPECT_DOUBLE_EQ(thresholds[0][1], 0.5);
    EXPECT_DOUBLE_EQ(thresholds[1][2], 1.0);
    EXPECT_DOUBLE_EQ(thresholds[2][1], 0.05);
    // Godot's default 1 px: near 0.5 <= 1 < 2 -> 1; middle 1 <= 1 -> 2; far -> 2.
    EXPECT_EQ(engineRuleLevels(thresholds, 1.0), (Combination{1, 2, 2}));
    EXPECT_EQ(engineRuleLevels(thresholds, 0.1), (Combination{0, 0, 1}));
    EngineRuleParameters fixedBias;
    fixedBias.fitBudget = false;
    EXPECT_EQ(runRule(EngineRule::PixelError, problem, fixedBias).best, (Combination{1, 2, 2}));
}

TEST(EngineRules, TheBiasIsTheSmallestThatMeetsTheBudget) {
    RuleProblem rules;
    // Budget 12: bias 0, every object at level 0.
    EXPECT_EQ(runRule(EngineRule::PixelError, rules.problem(12.0, 0.005, 0.02)).best, (Combination{0, 0, 0}));
    // Budget 9: bias 0.05 gives {0, 0, 1} = 10 ms; 0.2 gives {0, 0, 2} = 9 ms.
    EXPECT_EQ(runRule(EngineRule::PixelError, rules.problem(9.0, 0.005, 0.02)).best, (Combination{0, 0, 2}));
    // Budget 6: bias 0.25 gives {0, 1, 2} = 7 ms; 0.5 gives {1, 1, 2} = 5 ms.
    const Result six = runRule(EngineRule::PixelError, rules.problem(6.0, 0.005, 0.02));
    EXPECT_EQ(six.best, (Combination{1, 1, 2}));
    EXPECT_DOUBLE_EQ(six.predictedMs, 5.0);
    EXPECT_EQ(six.evaluations, 1);  // a rule evaluates only its answer
    // Budget 3: only every object at its coarsest level fits (bias 2).
    EXPECT_EQ(runRule(EngineRule::PixelError, rules.problem(3.0, 0.005, 0.02)).best, (Combination{2, 2, 2}));
}

// Unreal's own steps, written out: S_k = 2 M R / (deviation_k 960 / P + R), M = 0.5 x 1920 /
// 1080, and the coarsest k >= 1 with S_k > the screen size, else 0.
int unrealLevel(double size, double radius, const std::vector<double>& deviation, double pixelError) {
    const double screenMultiple = 0.5 * 1920.0 / 1080.0;
    for (int k = int(deviation.size()) - 1; k >= 1; --k) {
        const double viewDistance = deviation[std::size_t(k)] * 960.0 / pixelError;
        const double screenSize = 2.0 * screenMultiple * radius / (viewDistance + radius);
        if (screenSize > size) return k;
    }
    return 0;
}

TEST(EngineRules, UnrealAutoFollowsTheEnginesScreenSizes) {
    RuleProblem rules;
    const Problem problem = rules.problem(12.0, 0.01, 0.04);
    const auto thresholds = engineRuleThresholds(problem, EngineRule::UnrealAuto);
    for (double pixelError : {0.3, 0.6, 1.0, 2.0, 5.0, 20.0, 100.0}) {
        const Combination levels = engineRuleLevels(thresholds, pixelError);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(levels[i], unrealLevel(problem.hints[i].screenCoverage, 1.0, {0.0, 0.01, 0.04}, pixelError))
                << "object " << i << ", pixel error " << pixelError;
        }
    }
    // At 1 px: the far object's level 1 has S_1 = 1.778 / 10.6 = 0.168 > 0.1; its level 2 0.045.
    EXPECT_EQ(engineRuleLevels(thresholds, 1.0), (Combination{0, 0, 1}));
    // A sphere larger on screen than Unreal's widest view never leaves level 0.
    Problem huge = rules.problem(12.0, 0.01, 0.04);
    huge.hints[0].screenCoverage = 2.0;
    EXPECT_EQ(engineRuleLevels(engineRuleThresholds(huge, EngineRule::UnrealAuto), 1e9)[0], 0);
    // Within a budget of 3 ms the near object cannot stay at level 0: lowered as screensize does.
    EXPECT_EQ(runRule(EngineRule::UnrealAuto, rules.problem(3.0, 0.01, 0.04)).best, (Combination{2, 2, 2}));
    // With the near object held at level 0 at every bias, 6 ms at best: it is lowered last.
    huge.budgetMs = 3.0;
    EXPECT_EQ(runRule(EngineRule::UnrealAuto, huge).best, (Combination{2, 2, 2}));
    // Budget 8: the middle object's level 1 opens at 960 x 0.01 / 4.926 = 1.95 px ({0, 1, 1}, 8 ms);
    // the far object's level 1 at 0.57 px alone is 10 ms.
    huge.budgetMs = 8.0;
    EXPECT_EQ(runRule(EngineRule::UnrealAuto, huge).best, (Combination{0, 1, 1}));
}

TEST(EngineRules, RefuseMissingHintsAndBadParameters) {
    RuleProblem rules;
    Problem problem = rules.problem(12.0, 0.005, 0.02);
    problem.hints[1].levelDeviation.clear();
    EXPECT_THROW(runRule(EngineRule::PixelError, problem), ProblemError);
    problem = rules.problem(12.0, 0.005, 0.02);
    problem.hints[2].pixelsPerWorldUnit = kUnknown;
    EXPECT_THROW(runRule(EngineRule::PixelError, problem), ProblemError);
    problem = rules.problem(12.0, 0.005, 0.02);
    problem.hints[0].boundingRadius = kUnknown;
    EXPECT_THROW(runRule(EngineRule::UnrealAuto, problem), ProblemError);
    for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
        EngineRuleParameters parameters;
        parameters.pixelError = bad;
        EXPECT_THROW(EngineRuleHeuristic(EngineRule::PixelError, parameters), std::invalid_argument);
    }
    EXPECT_EQ(makeAlgorithm("pixelerror", 1)->name(), "pixelerror");
    EXPECT_EQ(makeAlgorithm("unreal-auto", 1)->name(), "unreal-auto");
}

}  // namespace
}  // namespace lodopt::optimizer
