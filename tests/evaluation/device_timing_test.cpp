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
    settings.learnFrom = "least";
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
    EXPECT_EQ(profile.timing.learnedFrom, "least");  // asked for, whatever auto would have chosen
    EXPECT_EQ(profile.timing.learnRequest, "least");
    EXPECT_EQ(profile.timing.predicts, "median");
    EXPECT_EQ(profile.timing.frameClock, "wall");
    // The least of a frame's draws is never above their median: the scale lifts it to the median.
    EXPECT_GE(profile.timing.learnedScale, 1.0);
    EXPECT_EQ(profile.timing.rounds, 2);
    // One factor per pass, around 1 (two passes: their medians' mean), and their spread recorded.
    ASSERT_EQ(run.passTimeFactors.size(), 2u);
    for (double factor : run.passTimeFactors) EXPECT_GT(factor, 0.0);
    EXPECT_DOUBLE_EQ(profile.timing.passDrift, timemodel::passDrift(run.passTimeFactors));
    // The speed anchor: the first view at the finest levels, timed in every pass.
    EXPECT_EQ(profile.timing.anchorView, scene.views[0].name);
    EXPECT_GT(profile.timing.anchorMs, 0.0);
    EXPECT_EQ(profile.width, 64);
    EXPECT_EQ(profile.shading, renderer::shadingName(renderer::kDefaultShading));
    EXPECT_EQ(profile.scene, scene.name);
    EXPECT_EQ(profile.seed, 5u);
    EXPECT_EQ(profile.viewpoints, int(plan.viewpoints.size()));
    EXPECT_EQ(run.otherStatistics.size(), timemodel::timingStatisticNames().size() - 1);
    for (const timemodel::ProfileSample& sample : profile.samples) {
        EXPECT_GT(sample.sample.measuredMs, 0.0);
        EXPECT_EQ(sample.sample.measuredMs, sample.medianMs);  // what every profile predicts
        EXPECT_EQ(sample.medianMs, sample.wallMedianMs);       // on the wall clock here
        EXPECT_LE(sample.leastMs, sample.leastMedianMs);
        EXPECT_LE(sample.leastMedianMs, sample.medianMs);
        EXPECT_GT(sample.gpuMedianMs, 0.0);  // Mesa's timer, recorded beside the wall clock
    }
    // The models predict the median: the linear model's coefficients are the least's times the scale.
    const timemodel::ModelResult* linear = nullptr;
    for (const timemodel::ModelResult& m : profile.models) linear = m.name == "linear" ? &m : linear;
    ASSERT_NE(linear, nullptr);
    ASSERT_TRUE(linear->fitted);
    std::vector<timemodel::Sample> leastSamples;
    for (const timemodel::ProfileSample& s : profile.samples) {
        if (s.heldOut) continue;
        leastSamples.push_back(s.sample);
        leastSamples.back().measuredMs = s.leastMs;
    }
    const std::unique_ptr<timemodel::TimeModel> unscaled = timemodel::makeTimeModel("linear");
    unscaled->fit(leastSamples);
    ASSERT_EQ(unscaled->coefficients().size(), linear->coefficients.size());
    for (std::size_t c = 0; c < linear->coefficients.size(); ++c) {
        EXPECT_NEAR(linear->coefficients[c], profile.timing.learnedScale * unscaled->coefficients()[c],
                    1e-6 * (1e-9 + std::abs(linear->coefficients[c])))
            << linear->coefficientNames[c];
    }
    EXPECT_TRUE(std::any_of(profile.models.begin(), profile.models.end(),
                            [](const timemodel::ModelResult& m) { return m.fitted; }));
    // The profile reads back and yields a model.
    const timemodel::DeviceProfile read = timemodel::profileFromJson(timemodel::profileToJson(profile), "test");
    EXPECT_NE(timemodel::modelFromProfile(read), nullptr);
}

TEST(DeviceTiming, SpeedProbeTimesTheAnchorAgainAndRefusesWhatItCannotCompare) {
    const scenes::Scene scene = scenes::makeHarborScene();
    timemodel::DeviceProfile profile;
    profile.scene = scene.name;
    profile.width = profile.height = 64;
    profile.shading = renderer::shadingName(renderer::kDefaultShading);
    profile.timing.anchorView = scene.views[0].name;
    profile.timing.anchorMs = 1000.0;  // a machine far slower than any this runs on
    const evaluation::SpeedProbe probe = evaluation::probeSpeed(scene, profile, smallSettings(), 3, 1);
    EXPECT_EQ(probe.view, scene.views[0].name);
    EXPECT_EQ(probe.anchorMs, 1000.0);
    EXPECT_GT(probe.probeMs, 0.0);
    EXPECT_LT(probe.probeMs, 1000.0);  // a 64x64 harbor frame
    EXPECT_DOUBLE_EQ(probe.ratio, probe.probeMs / 1000.0);

    const auto refused = [&](timemodel::DeviceProfile changed, const std::string& expected) {
        try {
            evaluation::probeSpeed(scene, changed, smallSettings(), 1, 0);
            ADD_FAILURE() << "probed: " << expected;
        } catch (const std::invalid_argument& error) {
            EXPECT_NE(std::string(error.what()).find(expected), std::string::npos) << error.what();
        }
    };
    timemodel::DeviceProfile older = profile;
    older.timing.anchorMs = 0.0;
    refused(older, "no speed anchor");
    timemodel::DeviceProfile otherScene = profile;
    otherScene.scene = "forest";
    refused(otherScene, "scene 'forest'");
    timemodel::DeviceProfile otherSize = profile;
    otherSize.width = 512;
    refused(otherSize, "512x64");
    timemodel::DeviceProfile otherView = profile;
    otherView.timing.anchorView = "nowhere";
    refused(otherView, "view 'nowhere'");
}
