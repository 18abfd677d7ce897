// Timing frames and calibrating a device profile (evaluation/device_timing.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "evaluation/device_timing.hpp"
#include "scenes/builtin.hpp"

using namespace lodopt;

namespace {

renderer::RenderSettings smallSettings() {
    renderer::RenderSettings settings;
    settings.width = settings.height = 64;
    return settings;
}

}  // namespace

TEST(DeviceTiming, DrawTimesArePositiveAndOrdered) {
    const scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    const evaluation::DrawTimes times =
        evaluation::timeDraws(renderer, scenes::referenceCombination(scene), scene.views[0], 5, 1);
    EXPECT_GT(times.wallMin, 0.0);
    EXPECT_LE(times.wallMin, times.wallMedian);
    EXPECT_GT(times.cpuMedian, 0.0);
    EXPECT_EQ(evaluation::batchTime(times, "wall-min"), times.wallMin);
    EXPECT_EQ(evaluation::batchTime(times, "wall-min-median"), times.wallMin);
    EXPECT_EQ(evaluation::batchTime(times, "wall-median"), times.wallMedian);
    EXPECT_EQ(evaluation::batchTime(times, "cpu"), times.cpuMedian);
}

TEST(DeviceTiming, CalibrationTimesEverySampleInEveryPassAndFitsTheProfile) {
    const scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    timemodel::CalibrationOptions planOptions;
    planOptions.samples = 24;
    planOptions.seed = 5;
    const timemodel::CalibrationPlan plan = timemodel::planCalibration(scene, planOptions);
    evaluation::CalibrationSettings settings;
    settings.rounds = 2;
    settings.maxRounds = 2;
    settings.repeats = 1;
    settings.clock = "wall-median";
    int calls = 0;
    int lastPass = -1;
    const evaluation::CalibrationResult run = evaluation::calibrateDevice(
        scene, renderer, plan, planOptions.seed, settings, [&](int pass, std::size_t done, std::size_t total) {
            ++calls;
            EXPECT_EQ(total, plan.samples.size());
            EXPECT_GE(done, 1u);
            EXPECT_LE(done, total);
            lastPass = pass;
        });
    EXPECT_EQ(calls, 2 * int(plan.samples.size()));
    EXPECT_EQ(lastPass, 1);

    const timemodel::DeviceProfile& profile = run.profile;
    EXPECT_EQ(profile.samples.size(), plan.samples.size());
    EXPECT_EQ(run.fitSamples + run.heldOutSamples, plan.samples.size());
    EXPECT_GT(run.heldOutSamples, 0u);
    EXPECT_EQ(profile.timing.clock, "wall-median");  // asked for, whatever auto would have chosen
    EXPECT_EQ(profile.timing.clockRequest, "wall-median");
    EXPECT_EQ(profile.timing.rounds, 2);
    EXPECT_EQ(profile.width, 64);
    EXPECT_EQ(profile.shading, renderer::shadingName(renderer::kDefaultShading));
    EXPECT_EQ(profile.scene, scene.name);
    EXPECT_EQ(profile.seed, 5u);
    EXPECT_EQ(profile.viewpoints, int(plan.viewpoints.size()));
    EXPECT_EQ(run.otherClocks.size(), timemodel::timingClockNames().size() - 1);
    for (const timemodel::ProfileSample& sample : profile.samples) {
        EXPECT_GT(sample.sample.measuredMs, 0.0);
        EXPECT_EQ(sample.sample.measuredMs, sample.wallMedianMs);
        EXPECT_LE(sample.wallMinMs, sample.wallMedianMs);
    }
    EXPECT_TRUE(std::any_of(profile.models.begin(), profile.models.end(),
                            [](const timemodel::ModelResult& m) { return m.fitted; }));
    // The profile reads back and yields a model.
    const timemodel::DeviceProfile read = timemodel::profileFromJson(timemodel::profileToJson(profile), "test");
    EXPECT_NE(timemodel::modelFromProfile(read), nullptr);
}
