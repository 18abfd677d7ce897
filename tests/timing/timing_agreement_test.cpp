// What a profile predicts is what `render --time` measures: a calibration's profile, asked by
// `lodopt estimate` about combinations it never timed, agrees with `lodopt render --time` on them
// within the error the calibration itself reported (docs/timemodel.md "What a profile predicts").
// Its own executable, run alone (RUN_SERIAL): another test's load would move the measured times.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "run_lodopt.hpp"

namespace {

using lodopt::cli_test::CommandResult;
using lodopt::cli_test::runLodopt;

nlohmann::json runJson(const std::string& arguments) {
    const CommandResult result = runLodopt(arguments + " --json");
    EXPECT_EQ(result.exitCode, 0) << arguments;
    return result.exitCode == 0 ? nlohmann::json::parse(result.output) : nlohmann::json();
}

// One calibration, then the frames: whether estimate and render --time agreed, with what was seen.
struct Attempt {
    bool agreed = false;
    std::string report;
};

Attempt calibrateAndCompare(const std::filesystem::path& dir, int seed) {
    Attempt attempt;
    const std::string profile = (dir / "harbor.json").string();
    const std::string size = "256x192";
    const nlohmann::json calibration =
        runJson("calibrate --scene harbor --samples 96 --jitter 1 --rounds 4 --max-rounds 4 --repeats 3 --size " +
                size + " --seed " + std::to_string(seed) + " --quiet --out " + profile);
    if (!calibration.is_object()) return attempt;
    EXPECT_EQ(calibration["predicts"], "median");
    const nlohmann::json& linear = calibration["models"][0];
    EXPECT_EQ(linear["name"], "linear");
    // The error the calibration reports for its default model, every viewpoint held out once.
    const double reportedMean = linear["rotated_held_out_errors"]["mean"].get<double>();
    const double reportedP90 = linear["rotated_held_out_errors"]["p90"].get<double>();
    EXPECT_GT(reportedP90, 0.0);

    // Combinations no calibration sample drew on purpose: fixed, spread from the finest to the
    // coarsest, on each named view (the calibration timed jittered cameras around them).
    const std::vector<std::pair<std::string, std::string>> frames = {{"0", "0,0,0"}, {"0", "2,1,3"}, {"1", "1,0,2"},
                                                                     {"1", "4,3,1"}, {"2", "0,2,0"}, {"2", "3,4,4"},
                                                                     {"3", "1,1,1"}, {"3", "5,0,2"}};
    double mean = 0.0, signedMean = 0.0;
    char line[256];
    for (const auto& [view, levels] : frames) {
        const std::string frame = "--scene harbor --view " + view + " --levels " + levels;
        const nlohmann::json estimate = runJson("estimate --profile " + profile + " " + frame);
        const nlohmann::json render = runJson("render " + frame + " --size " + size + " --time --repeats 15 --out " +
                                              (dir / "frame.png").string());
        if (!estimate.is_object() || !render.is_object()) return attempt;
        EXPECT_TRUE(estimate["warnings"].empty()) << estimate["warnings"].dump();
        EXPECT_EQ(render["timing"]["frame_clock"], "wall");
        const double predicted = estimate["predicted_ms"].get<double>();
        const double measured = render["render_ms"].get<double>();
        EXPECT_GT(measured, 0.0) << frame;
        if (!(measured > 0.0)) return attempt;
        mean += std::abs(predicted - measured) / measured / double(frames.size());
        signedMean += (predicted - measured) / measured / double(frames.size());
        std::snprintf(line, sizeof line, "  view %s levels %s: estimate %.3f ms, render --time %.3f ms\n", view.c_str(),
                      levels.c_str(), predicted, measured);
        attempt.report += line;
    }
    std::snprintf(line, sizeof line,
                  "seed %d: mean error %.1f%%, signed %.1f%%; the calibration reported mean %.1f%%, p90 %.1f%%\n", seed,
                  100.0 * mean, 100.0 * signedMean, 100.0 * reportedMean, 100.0 * reportedP90);
    attempt.report += line;
    // Within what the calibration reported: the mean error over the frames no more than its p90.
    // A context timed before it had warmed up was off by 30-45 % here (estimates at 4.5-8 ms against
    // a p90 of 17-25 %); a profile predicting another statistic than the median is off by that
    // statistic's distance on every frame.
    attempt.agreed = mean <= reportedP90;
    return attempt;
}

}  // namespace

// This machine's frame speed moves by up to half between processes minutes apart
// (docs/timemodel.md "Limits"): a disagreement must repeat in three fresh calibrations to fail.
TEST(TimingAgreement, EstimateAndRenderTimeAgreeWithinTheCalibrationsReportedError) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("lodopt-timing-agreement-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    std::string reports;
    bool agreed = false;
    for (int seed = 11; seed < 14 && !agreed; ++seed) {
        const Attempt attempt = calibrateAndCompare(dir, seed);
        reports += attempt.report;
        agreed = attempt.agreed;
    }
    std::printf("%s", reports.c_str());
    EXPECT_TRUE(agreed) << "estimate and render --time disagree beyond the calibration's reported error:\n" << reports;
    std::filesystem::remove_all(dir);
}
