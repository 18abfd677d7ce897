// Switch control (VMI20 §7): the allowed range of levels, and that it stops an object that
// oscillates across a distance threshold from switching every frame.
#include "scheduler/switch_control.hpp"

#include <gtest/gtest.h>

#include "fixtures.hpp"
#include "scheduler/scheduler.hpp"

namespace lodopt::scheduler {
namespace {

const std::vector<double> kRates = {0.0, 0.3, 0.6, 0.9, 0.95};  // five levels

TEST(SwitchControl, RatesFromTriangles) {
    const std::vector<double> rates = simplificationRates({1000, 500, 100, 0});
    ASSERT_EQ(rates.size(), 4u);
    EXPECT_DOUBLE_EQ(rates[0], 0.0);
    EXPECT_DOUBLE_EQ(rates[1], 0.5);
    EXPECT_DOUBLE_EQ(rates[2], 0.9);
    EXPECT_DOUBLE_EQ(rates[3], 1.0);
    EXPECT_DOUBLE_EQ(simplificationRates({0, 0})[1], 0.0);
}

TEST(SwitchControl, DisabledAllowsEveryLevel) {
    SwitchControlParameters p;
    p.enabled = false;
    const LevelRange r = allowedLevels(2, 0.0, 100.0, kRates, p);
    EXPECT_EQ(r.finest, 0);
    EXPECT_EQ(r.coarsest, 4);
}

TEST(SwitchControl, HoldsUntilTheDwellTimeHasPassed) {
    SwitchControlParameters p;
    p.delta2 = 0.1;
    p.k2 = 1.0;
    p.nearDistance = 2.0;
    // dist − near = 10 → dwell 1 s.
    LevelRange r = allowedLevels(2, 0.9, 12.0, kRates, p);
    EXPECT_EQ(r.finest, 2);
    EXPECT_EQ(r.coarsest, 2);
    r = allowedLevels(2, 1.1, 12.0, kRates, p);
    EXPECT_LT(r.finest, 2);
    EXPECT_GT(r.coarsest, 2);
    // Nearer objects may switch sooner: dist − near = 1 → 0.1 s.
    r = allowedLevels(2, 0.2, 3.0, kRates, p);
    EXPECT_LT(r.finest, 2);
}

TEST(SwitchControl, StepSizeGrowsWithDistance) {
    SwitchControlParameters p;
    p.delta1 = 0.1;
    p.k1 = 1.0;
    p.delta2 = 0.0;
    p.nearDistance = 0.0;
    // Near (bound 0.1): one step each way only, whatever the rates.
    LevelRange r = allowedLevels(2, 1.0, 1.0, kRates, p);
    EXPECT_EQ(r.finest, 1);
    EXPECT_EQ(r.coarsest, 3);
    // Far (bound 0.65): up to |Δrate| < 0.65: level 0 (0.6 away) and level 4 (0.35 away).
    r = allowedLevels(2, 1.0, 6.5, kRates, p);
    EXPECT_EQ(r.finest, 0);
    EXPECT_EQ(r.coarsest, 4);
    // Bound 0.4: level 0 is 0.6 away, so one step finer only.
    r = allowedLevels(2, 1.0, 4.0, kRates, p);
    EXPECT_EQ(r.finest, 1);
    EXPECT_EQ(r.coarsest, 4);
}

TEST(SwitchControl, RejectsBadParameters) {
    SwitchControlParameters p;
    p.delta1 = 0.0;
    EXPECT_THROW(validateSwitchControl(p), std::invalid_argument);
    p = {};
    p.k2 = -1.0;
    EXPECT_THROW(validateSwitchControl(p), std::invalid_argument);
    EXPECT_NO_THROW(validateSwitchControl(SwitchControlParameters{}));
}

// One blob; the eye swings back and forth across the distance threshold (20 radii) every
// frame, and the budget is exactly the cost of the threshold's level, so without control the
// level flips every frame. With it (dwell 0.1 s · (20 − 2)^0.5 ≈ 0.42 s ≈ 13 frames) a raise
// waits for the dwell time; lowering for the budget is forced when it must be.
int flickerSwitches(bool control) {
    const scenes::Scene scene = testing::makeGridScene(1, 1, 1.0f);
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.coefficients.thresholds.values = {20.0, 1000.0};
    p.switchControl = {control, 0.15, 0.5, 0.1, 0.5, 2.0};
    const double msPerTriangle = 1e-3;
    FrameScheduler scheduler(index, testing::triangleModel(0.0, msPerTriangle), p);
    const glm::vec3 center = index.shape(0).center;
    const double radius = index.shape(0).radius;
    int switches = 0;
    for (int frame = 0; frame < 60; ++frame) {
        const double relative = frame % 2 == 0 ? 19.9 : 20.1;
        const scenes::Camera camera = testing::lookAt(center + glm::vec3(0, 0, float(relative * radius)), center);
        const int level = relative < 20.0 ? 0 : 1;
        scheduler.setBudgetMs(double(scene.objects[0].levels[level].stats.triangles) * msPerTriangle + 1e-9);
        const FrameDecision& decision = scheduler.decide(camera, frame / 30.0);
        EXPECT_TRUE(decision.budgetMet) << "frame " << frame;
        switches += decision.switches;
    }
    return switches;
}

TEST(SwitchControl, PreventsFlickerAcrossAThreshold) {
    const int without = flickerSwitches(false);
    const int with = flickerSwitches(true);
    EXPECT_GE(without, 55);  // every frame but the first
    EXPECT_LE(with, without / 4);
}

}  // namespace
}  // namespace lodopt::scheduler
