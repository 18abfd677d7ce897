// lodopt calibrate / estimate: a tiny real calibration (seconds), predictions from its
// profile and from the shipped one, and bad input mapped to exit code 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "run_lodopt.hpp"
#include "timemodel/profile.hpp"
#include "timemodel/timing.hpp"

namespace {

using lodopt::cli_test::CommandResult;

CommandResult run(const std::string& arguments) {
    return lodopt::cli_test::runLodopt(arguments);
}

// One tiny calibration shared by the tests of this file (timing it once keeps the suite fast).
class TimeModelCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sDir = std::filesystem::temp_directory_path() / ("lodopt-cli-timemodel-" + std::to_string(::getpid()));
        std::filesystem::remove_all(sDir);
        std::filesystem::create_directories(sDir);
        sProfile = (sDir / "device.json").string();
        sCalibration =
            run("calibrate --scene harbor --samples 24 --jitter 1 --rounds 2 --max-rounds 2 --repeats 1 "
                "--warmup 1 --size 96x72 --seed 3 --out " +
                sProfile + " --json");
    }
    static void TearDownTestSuite() { std::filesystem::remove_all(sDir); }

    static nlohmann::json estimate(const std::string& arguments, int expectedExit = 0) {
        CommandResult result = run("estimate " + arguments + " --json");
        EXPECT_EQ(result.exitCode, expectedExit) << arguments;
        if (result.exitCode != 0) return {};
        return nlohmann::json::parse(result.output);
    }

    static std::filesystem::path sDir;
    static std::string sProfile;
    static CommandResult sCalibration;
};

std::filesystem::path TimeModelCli::sDir;
std::string TimeModelCli::sProfile;
CommandResult TimeModelCli::sCalibration;

}  // namespace

TEST_F(TimeModelCli, CalibrateFitsEveryModelAndWritesAProfile) {
    ASSERT_EQ(sCalibration.exitCode, 0) << sCalibration.output;
    const nlohmann::json report = nlohmann::json::parse(sCalibration.output);
    EXPECT_EQ(report["samples"], 24);
    EXPECT_GT(report["held_out_samples"].get<int>(), 0);
    EXPECT_EQ(report["fit_samples"].get<int>() + report["held_out_samples"].get<int>(), 24);
    EXPECT_EQ(report["held_out_viewpoints"], 4);  // one of each named view's two viewpoints
    ASSERT_EQ(report["models"].size(), 3u);
    EXPECT_EQ(report["models"][0]["name"], "linear");
    EXPECT_TRUE(report["models"][0]["fitted"].get<bool>());
    EXPECT_GT(report["models"][0]["held_out_errors"]["count"].get<int>(), 0);
    // Every viewpoint held out once over the folds: every sample measured by a model that did
    // not see its viewpoint.
    EXPECT_EQ(report["models"][0]["rotated_held_out_errors"]["count"], 24);
    ASSERT_TRUE(std::filesystem::exists(sProfile));
    const lodopt::timemodel::DeviceProfile profile = lodopt::timemodel::loadProfile(sProfile);
    EXPECT_EQ(profile.scene, "harbor");
    EXPECT_EQ(profile.width, 96);
    EXPECT_EQ(profile.height, 72);
    EXPECT_EQ(profile.samples.size(), 24u);
    EXPECT_NE(profile.glRenderer.find("llvmpipe"), std::string::npos) << profile.glRenderer;
    EXPECT_FALSE(profile.machine.cpuModel.empty());
    // Every profile predicts the median of a frame's draws; by default (--learn-from auto) the
    // models learn from the statistic that predicted it best on the fitting viewpoints.
    EXPECT_EQ(report["predicts"], "median");
    EXPECT_EQ(report["frame_clock"], "wall");  // llvmpipe: its timer misses the rasterization
    EXPECT_EQ(report["learn_request"], "auto");
    EXPECT_EQ(profile.timing.learnRequest, "auto");
    const std::string learned = report["learned_from"];
    EXPECT_EQ(profile.timing.learnedFrom, learned);
    EXPECT_DOUBLE_EQ(profile.timing.learnedScale, report["learned_scale"].get<double>());
    const nlohmann::json& judged = report["learn_choice"]["candidates"];
    ASSERT_EQ(judged.size(), 3u) << report["learn_choice"];
    ASSERT_TRUE(judged.contains(learned)) << learned;
    EXPECT_TRUE(report["learn_choice"]["measured"].get<bool>());
    for (const auto& [other, candidate] : judged.items()) {
        EXPECT_GT(candidate["errors"]["count"].get<int>(), 0) << other;
        EXPECT_LE(judged[learned]["errors"]["mean"].get<double>(), candidate["errors"]["mean"].get<double>()) << other;
    }
    for (const auto& s : profile.samples) {
        EXPECT_GT(s.sample.measuredMs, 0.0);
        EXPECT_EQ(s.sample.measuredMs, s.medianMs);
        // The median of the passes' least times lies between their least and their greatest.
        EXPECT_GE(s.leastMedianMs, s.leastMs);
        EXPECT_GT(s.wallMedianMs, 0.0);
        EXPECT_GT(s.gpuMedianMs, 0.0);  // Mesa's timer, recorded beside the wall clock
    }
    // The same draws refitted learning from every other statistic.
    for (const std::string& other : lodopt::timemodel::timingStatisticNames()) {
        if (other == learned) {
            EXPECT_FALSE(report["other_statistics"].contains(other));
            continue;
        }
        ASSERT_TRUE(report["other_statistics"].contains(other)) << other;
        EXPECT_EQ(report["other_statistics"][other]["models"].size(), 3u) << other;
        EXPECT_GT(report["other_statistics"][other]["scale"].get<double>(), 0.0) << other;
        EXPECT_GE(report["other_statistics"][other]["split_half_p90"].get<double>(),
                  report["other_statistics"][other]["split_half_median"].get<double>())
            << other;
    }
    // Two passes: each held-out sample timed twice, the two compared (repeatability).
    EXPECT_EQ(profile.timing.rounds, 2);
    const double halfMedian = report["split_half_median"].get<double>();
    EXPECT_GT(halfMedian, 0.0);  // two draws on a nanosecond clock are never equal
    EXPECT_GE(report["split_half_p90"].get<double>(), halfMedian);
    EXPECT_DOUBLE_EQ(profile.timing.splitHalfMedian, halfMedian);
    EXPECT_DOUBLE_EQ(profile.timing.splitHalfP90, report["split_half_p90"].get<double>());
    // Each pass's speed against the run's, their drift recorded in the profile, and a warning
    // exactly when the drift passes the threshold.
    ASSERT_EQ(report["pass_time_factors"].size(), 2u) << report["pass_time_factors"];
    const double drift = report["pass_drift"].get<double>();
    EXPECT_GE(drift, 0.0);
    EXPECT_DOUBLE_EQ(profile.timing.passDrift, drift);
    const bool warned = report["warnings"].size() == 1 &&
                        report["warnings"][0].get<std::string>().find("between the calibration's passes") !=
                            std::string::npos;
    EXPECT_EQ(warned, drift > lodopt::timemodel::kPassDriftWarning) << report["warnings"];
    // The speed anchor: view 0 at the finest levels, recorded for `estimate --speed-probe`.
    EXPECT_EQ(report["anchor_view"], "overview");
    EXPECT_GT(report["anchor_ms"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(profile.timing.anchorMs, report["anchor_ms"].get<double>());
}

TEST_F(TimeModelCli, CalibrateLearnsFromTheStatisticItIsGivenAndStillPredictsTheMedian) {
    const std::string out = (sDir / "learned_from_least.json").string();
    const CommandResult result =
        run("calibrate --scene harbor --samples 16 --jitter 1 --rounds 3 --max-rounds 3 --repeats 2 --warmup 0 "
            "--size 64x48 --seed 5 --learn-from least --out " +
            out + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const nlohmann::json report = nlohmann::json::parse(result.output);
    EXPECT_EQ(report["learned_from"], "least");
    EXPECT_EQ(report["learn_request"], "least");
    EXPECT_EQ(report["predicts"], "median");
    EXPECT_GE(report["learned_scale"].get<double>(), 1.0);  // a least is never above its median
    EXPECT_TRUE(report["other_statistics"].contains("least-median"));
    EXPECT_TRUE(report["other_statistics"].contains("median"));
    const lodopt::timemodel::DeviceProfile profile = lodopt::timemodel::loadProfile(out);
    EXPECT_EQ(profile.timing.learnedFrom, "least");
    EXPECT_EQ(profile.timing.rounds, 3);
    for (const auto& s : profile.samples) {
        EXPECT_EQ(s.sample.measuredMs, s.medianMs);
        EXPECT_GE(s.leastMedianMs, s.leastMs);
    }
    // An older name of a statistic is not an option any more.
    EXPECT_EQ(run("calibrate --scene harbor --samples 16 --learn-from wall-min --out " + out).exitCode, 2);
}

TEST_F(TimeModelCli, CalibrateMakesAtLeastRoundsPassesAndMoreWithinTheBudget) {
    // The pass rule the defaults rest on (--rounds 6 --max-rounds 25 --time-budget 110): at least
    // --rounds passes whatever the budget, more up to --max-rounds while the budget allows.
    const auto passes = [](const std::string& options, const std::string& name) {
        const std::string out = (sDir / name).string();
        const CommandResult result =
            run("calibrate --scene harbor --samples 8 --jitter 1 --repeats 1 --warmup 0 "
                "--size 32x24 --seed 7 --quiet " +
                options + " --out " + out);
        EXPECT_EQ(result.exitCode, 0) << options;
        return result.exitCode == 0 ? lodopt::timemodel::loadProfile(out).timing.rounds : -1;
    };
    EXPECT_EQ(passes("--rounds 3 --max-rounds 9 --time-budget 0", "no_budget.json"), 3);
    EXPECT_EQ(passes("--rounds 2 --max-rounds 5 --time-budget 600", "budget.json"), 5);
    EXPECT_EQ(passes("--rounds 4 --max-rounds 2 --time-budget 600", "rounds_over_max.json"), 4);
}

TEST_F(TimeModelCli, EstimateFromTheProfilePredictsEveryModel) {
    ASSERT_EQ(sCalibration.exitCode, 0);
    const nlohmann::json fine = estimate("--profile " + sProfile + " --scene harbor --view 1 --levels 0,0,0");
    const nlohmann::json coarse = estimate("--profile " + sProfile + " --scene harbor --view 1 --levels 5,4,4");
    ASSERT_FALSE(fine.is_null());
    ASSERT_FALSE(coarse.is_null());
    EXPECT_EQ(fine["model"], "linear");
    EXPECT_EQ(fine["width"], 96);  // the profile's size by default
    EXPECT_TRUE(fine["warnings"].empty()) << fine["warnings"].dump();
    EXPECT_GT(fine["predicted_ms"].get<double>(), 0.0);
    EXPECT_GE(fine["predicted_ms"].get<double>(), coarse["predicted_ms"].get<double>());
    EXPECT_GT(fine["features"]["triangles"].get<double>(), coarse["features"]["triangles"].get<double>());
    for (const char* model : {"dong", "wimmer"}) {
        const nlohmann::json other =
            estimate("--profile " + sProfile + " --scene harbor --view 1 --levels 0,2,1 --model " + model);
        ASSERT_FALSE(other.is_null()) << model;
        EXPECT_EQ(other["model"], model);
        EXPECT_TRUE(std::isfinite(other["predicted_ms"].get<double>()));
    }
}

TEST_F(TimeModelCli, EstimateSpeedProbeScalesThePredictionByTheAnchorsTimeNow) {
    ASSERT_EQ(sCalibration.exitCode, 0);
    const std::string asked = "--profile " + sProfile + " --scene harbor --view 1 --levels 0,2,1";
    const nlohmann::json plain = estimate(asked);
    const nlohmann::json probed = estimate(asked + " --speed-probe");
    ASSERT_FALSE(plain.is_null());
    ASSERT_FALSE(probed.is_null());
    EXPECT_TRUE(plain["speed_probe"].is_null());
    EXPECT_DOUBLE_EQ(plain["predicted_ms"].get<double>(), plain["model_ms"].get<double>());
    EXPECT_DOUBLE_EQ(probed["model_ms"].get<double>(), plain["model_ms"].get<double>());
    const nlohmann::json& probe = probed["speed_probe"];
    const double ratio = probe["ratio"].get<double>();
    EXPECT_GT(probe["probe_ms"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(probe["anchor_ms"].get<double>(), lodopt::timemodel::loadProfile(sProfile).timing.anchorMs);
    EXPECT_DOUBLE_EQ(ratio, probe["probe_ms"].get<double>() / probe["anchor_ms"].get<double>());
    EXPECT_DOUBLE_EQ(probed["predicted_ms"].get<double>(), plain["model_ms"].get<double>() * ratio);
    // The anchor is the profile's frame: not another size, not another scene.
    estimate("--profile " + sProfile + " --size 128x96 --speed-probe", 2);
    estimate("--profile " + sProfile + " --scene forest --speed-probe", 2);
}

TEST_F(TimeModelCli, EstimateWarnsWhenFramesWouldBeTimedOnAnotherClock) {
    ASSERT_EQ(sCalibration.exitCode, 0);
    // The profile timed llvmpipe's frames on the wall clock; asked about the GPU timer's frames.
    const nlohmann::json result = estimate("--profile " + sProfile + " --frame-clock gpu --levels 0,2,1");
    ASSERT_FALSE(result.is_null());
    ASSERT_EQ(result["warnings"].size(), 1u);
    EXPECT_NE(result["warnings"][0].get<std::string>().find("wall clock, this renderer on the gpu clock"),
              std::string::npos)
        << result["warnings"];
    EXPECT_TRUE(estimate("--profile " + sProfile + " --frame-clock wall --levels 0,2,1")["warnings"].empty());
    estimate("--profile " + sProfile + " --frame-clock cpu", 2);  // not a frame clock
}

TEST_F(TimeModelCli, RefitLearnsFromTheRecordedSamplesWithoutTimingAnything) {
    ASSERT_EQ(sCalibration.exitCode, 0);
    const std::string out = (sDir / "refitted.json").string();
    const CommandResult result =
        run("calibrate --refit " + sProfile + " --learn-from least --out " + out + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const nlohmann::json report = nlohmann::json::parse(result.output);
    EXPECT_EQ(report["refit"], sProfile);
    EXPECT_EQ(report["learned_from"], "least");
    EXPECT_EQ(report["predicts"], "median");
    const lodopt::timemodel::DeviceProfile original = lodopt::timemodel::loadProfile(sProfile);
    const lodopt::timemodel::DeviceProfile refitted = lodopt::timemodel::loadProfile(out);
    ASSERT_EQ(refitted.samples.size(), original.samples.size());
    EXPECT_EQ(refitted.timing.rounds, original.timing.rounds);  // the same draws, none added
    for (std::size_t i = 0; i < original.samples.size(); ++i) {
        EXPECT_EQ(refitted.samples[i].leastMs, original.samples[i].leastMs);
        EXPECT_EQ(refitted.samples[i].sample.measuredMs, original.samples[i].medianMs);
    }
    EXPECT_EQ(run("calibrate --refit " + (sDir / "missing.json").string() + " --out " + out).exitCode, 2);
}

TEST_F(TimeModelCli, EstimateWarnsForAnotherRenderSize) {
    ASSERT_EQ(sCalibration.exitCode, 0);
    const nlohmann::json result = estimate("--profile " + sProfile + " --size 512x512 --levels 0,2,1");
    ASSERT_FALSE(result.is_null());
    ASSERT_EQ(result["warnings"].size(), 1u);
    EXPECT_NE(result["warnings"][0].get<std::string>().find("96x72"), std::string::npos);
}

TEST_F(TimeModelCli, BadInputExitsWithTwo) {
    const std::string out = (sDir / "never.json").string();
    EXPECT_EQ(run("calibrate --samples 1 --out " + out).exitCode, 2);
    EXPECT_EQ(run("calibrate --views nowhere --samples 8 --out " + out).exitCode, 2);
    EXPECT_EQ(run("calibrate --rounds 0 --out " + out).exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(out));
    estimate("--profile " + (sDir / "missing.json").string(), 2);
    const std::string corrupt = (sDir / "corrupt.json").string();
    std::ofstream(corrupt) << "{\"format\": \"lodopt-device-profile\", \"version\": 1}";
    estimate("--profile " + corrupt, 2);
    if (sCalibration.exitCode == 0) {
        estimate("--profile " + sProfile + " --model funkhouser", 2);
        estimate("--profile " + sProfile + " --levels 0,9,0", 2);
        estimate("--profile " + sProfile + " --view nowhere", 2);
    }
}

TEST_F(TimeModelCli, EstimateWithoutAProfileUsesTheShippedOne) {
    if (lodopt::timemodel::shippedProfileScenes().empty()) {
        EXPECT_EQ(run("estimate --scene harbor").exitCode, 2);
        GTEST_SKIP() << "this build ships no profile";
    }
    const nlohmann::json result = estimate("--scene harbor --view 0 --levels 0,2,1 --no-renderer-check");
    ASSERT_FALSE(result.is_null());
    EXPECT_EQ(result["profile"], "shipped:harbor");
    EXPECT_GT(result["predicted_ms"].get<double>(), 0.0);
    // The frame is drawn as the profile was measured unless --shading says otherwise, which warns.
    EXPECT_EQ(result["shading"], lodopt::timemodel::shippedProfile("harbor").shading);
    const std::string other = result["shading"] == "pbr" ? "lambert" : "pbr";
    const nlohmann::json otherShading =
        estimate("--scene harbor --view 0 --levels 0,2,1 --no-renderer-check --shading " + other);
    ASSERT_FALSE(otherShading.is_null());
    EXPECT_EQ(otherShading["shading"], other);
    EXPECT_EQ(otherShading["predicted_ms"], result["predicted_ms"]);
    bool warned = false;
    for (const auto& warning : otherShading["warnings"]) {
        warned |= warning.get<std::string>().find("measured with --shading") != std::string::npos;
    }
    EXPECT_TRUE(warned) << otherShading.dump();
    estimate("--scene harbor --shading phong", 2);
}
