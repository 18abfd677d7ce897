// lodopt tune / schedule end to end on the harbor at 128x128 with a tiny calibration (seconds):
// coefficients and both fractions reported, checkpoints and --resume (tune's views; schedule's
// frame batches, interrupted by SIGINT/SIGTERM), the per-frame CSV, and bad input mapped to
// exit code 2.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "child_process.hpp"
#include "cli_common.hpp"
#include "interrupt.hpp"
#include "run_lodopt.hpp"
#include "scenes/builtin.hpp"
#include "scheduler/coefficients.hpp"
#include "scheduler/tuning.hpp"
#include "timemodel/features.hpp"
#include "timemodel/profile.hpp"

namespace {

using lodopt::cli_test::CommandResult;

CommandResult run(const std::string& arguments) {
    return lodopt::cli_test::runLodopt(arguments);
}

nlohmann::json parseOrFail(const CommandResult& result) {
    const nlohmann::json json = nlohmann::json::parse(result.output, nullptr, false);
    EXPECT_FALSE(json.is_discarded()) << result.output;
    return json;
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream file(path);
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

using lodopt::cli_test::Exit;

// The lodopt executable as a child process (stdout to /dev/null, stderr kept).
Exit runChild(const std::string& arguments, const std::filesystem::path& errFile,
              const lodopt::cli_test::Environment& environment = {},
              const std::function<void(pid_t)>& whileRunning = {}) {
    return lodopt::cli_test::runLodoptChild(lodopt::cli_test::splitWords(arguments), "/dev/null", errFile, environment,
                                            whileRunning);
}

// Frames saved in a schedule checkpoint (0 while it is missing or being replaced).
std::size_t savedFrames(const std::filesystem::path& checkpoint) {
    if (!std::filesystem::exists(checkpoint)) return 0;
    const nlohmann::json saved = nlohmann::json::parse(readFile(checkpoint), nullptr, false);
    return saved.is_discarded() ? 0 : saved["frames"].size();
}

// Sends `signal` to `pid` once `checkpoint` holds `frames` frames (or the process has ended).
void killAfterFrames(pid_t pid, const std::filesystem::path& checkpoint, std::size_t frames, int signal) {
    lodopt::cli_test::signalWhen(pid, [&] { return savedFrames(checkpoint) >= frames; }, signal);
}

// frames.csv as rows of cells, without the named columns (wall times).
std::vector<std::vector<std::string>> csvWithout(const std::string& csv, const std::vector<std::string>& dropped) {
    std::vector<std::vector<std::string>> rows;
    std::vector<bool> keep;
    std::istringstream lines(csv);
    for (std::string line; std::getline(lines, line);) {
        std::vector<std::string> cells;
        std::stringstream cellStream(line);
        for (std::string cell; std::getline(cellStream, cell, ',');) cells.push_back(cell);
        if (!line.empty() && line.back() == ',') cells.push_back("");
        if (keep.empty()) {
            for (const std::string& cell : cells)
                keep.push_back(std::find(dropped.begin(), dropped.end(), cell) == dropped.end());
        }
        std::vector<std::string> kept;
        for (std::size_t c = 0; c < cells.size() && c < keep.size(); ++c) {
            if (keep[c]) kept.push_back(cells[c]);
        }
        rows.push_back(kept);
    }
    return rows;
}

// One column of frames.csv as numbers (NaN for empty cells).
std::vector<double> csvColumn(const std::string& csv, const std::string& name) {
    const std::vector<std::vector<std::string>> rows = csvWithout(csv, {});
    std::vector<double> values;
    if (rows.empty()) return values;
    const auto at = std::find(rows[0].begin(), rows[0].end(), name);
    if (at == rows[0].end()) return values;
    const std::size_t c = std::size_t(at - rows[0].begin());
    for (std::size_t r = 1; r < rows.size(); ++r)
        values.push_back(c < rows[r].size() && !rows[r][c].empty() ? std::stod(rows[r][c]) : NAN);
    return values;
}

nlohmann::json summaryWithoutWallTimes(const std::filesystem::path& dir) {
    nlohmann::json summary = nlohmann::json::parse(readFile(dir / "summary.json"));
    EXPECT_TRUE(summary.contains("setup_seconds") && summary.contains("decision_us"));
    summary.erase("setup_seconds");
    summary.erase("decision_us");
    return summary;
}

class SchedulerCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sDir = std::filesystem::temp_directory_path() / ("lodopt-cli-scheduler-" + std::to_string(::getpid()));
        std::filesystem::remove_all(sDir);
        std::filesystem::create_directories(sDir);
        sProfile = (sDir / "device.json").string();
        sCalibrated = run("calibrate --scene harbor --samples 24 --jitter 1 --rounds 1 --repeats 1 --warmup 1 "
                          "--size 128x128 --seed 3 --out " +
                          sProfile + " --quiet")
                          .exitCode == 0;
        if (!sCalibrated) return;
        // A budget between the cheapest and the dearest frame of the harbor's views, so that
        // it binds on every view and never rules one out.
        const lodopt::scenes::Scene scene = lodopt::scenes::loadScene("harbor");
        const auto model = lodopt::timemodel::modelFromProfile(lodopt::timemodel::loadProfile(sProfile));
        double highestCoarsest = 0.0, lowestFinest = 1e30;
        for (const lodopt::scenes::Camera& camera : scene.views) {
            const lodopt::timemodel::FeatureTable table(scene, camera, 128, 128);
            highestCoarsest = std::max(highestCoarsest,
                                       model->estimateMs(table.features(lodopt::scenes::coarsestCombination(scene))));
            lowestFinest =
                std::min(lowestFinest, model->estimateMs(table.features(lodopt::scenes::referenceCombination(scene))));
        }
        sBudget = std::max(1.3 * highestCoarsest, 0.5 * (highestCoarsest + lowestFinest));
        // A camera path file: eight frames circling the ship.
        nlohmann::json frames = nlohmann::json::array();
        for (int f = 0; f < 8; ++f) {
            const double angle = 0.4 * f;
            frames.push_back({{"position", {60.0 * std::cos(angle), 18.0, 60.0 * std::sin(angle)}},
                              {"target", {0.0, 2.0, 0.0}},
                              {"far", 2000.0}});
        }
        sPath = (sDir / "orbit.json").string();
        std::ofstream(sPath) << nlohmann::json{{"name", "orbit"}, {"frames_per_second", 10}, {"frames", frames}}.dump();
        sCoefficients = (sDir / "tune" / "coeffs.json").string();
        sTune = run(tuneArguments() + " --json");
    }
    static void TearDownTestSuite() { std::filesystem::remove_all(sDir); }

    static std::string tuneArguments() {
        return "tune --scene harbor --view-count 4 --evals 24 --max-iterations 6 --search-evals 30 --size 128x128 --threads "
               "1 "
               "--profile " +
               sProfile + " --budget-ms " + std::to_string(sBudget) + " --out " + sCoefficients + " --quiet";
    }

    // tuneArguments() writing tune/<name>.json, beside a copy of the first run's view
    // checkpoints under that name, so that --resume reuses them.
    static std::string resumingArguments(const std::string& name) {
        std::filesystem::copy(sDir / "tune" / "coeffs_views", sDir / "tune" / (name + "_views"));
        std::string arguments = tuneArguments();
        const std::string out = (sDir / "tune" / (name + ".json")).string();
        return arguments.replace(arguments.find(sCoefficients), sCoefficients.size(), out);
    }

    void SetUp() override {
        // The suite's own set-up: its failure is every test's failure, never a skip.
        ASSERT_TRUE(sCalibrated) << "lodopt calibrate, the set-up of these tests, failed";
    }

    static std::filesystem::path sDir;
    static std::string sProfile, sPath, sCoefficients;
    static double sBudget;
    static bool sCalibrated;
    static CommandResult sTune;
};

std::filesystem::path SchedulerCli::sDir;
std::string SchedulerCli::sProfile, SchedulerCli::sPath, SchedulerCli::sCoefficients;
double SchedulerCli::sBudget = 0.0;
bool SchedulerCli::sCalibrated = false;
CommandResult SchedulerCli::sTune;

}  // namespace

TEST_F(SchedulerCli, TuneReportsTunedAndPublishedFractions) {
    ASSERT_EQ(sTune.exitCode, 0) << sTune.output;
    const nlohmann::json report = parseOrFail(sTune);
    EXPECT_EQ(report["views"], 4);
    EXPECT_EQ(report["held_out_views"], 1);
    ASSERT_EQ(report["per_view"].size(), 4u);
    int heldOut = 0;
    for (const nlohmann::json& view : report["per_view"]) {
        heldOut += view["held_out"].get<bool>() ? 1 : 0;
        EXPECT_GT(view["optimizer_fitness"].get<double>(), 0.0);
        EXPECT_GT(view["tuned_fraction"].get<double>(), 0.0);
        EXPECT_LE(view["optimizer_predicted_ms"].get<double>(), sBudget + 1e-9);  // the optimizer's answer fits
    }
    EXPECT_EQ(heldOut, 1);
    for (const char* which : {"defaults", "tuned"}) {
        for (const char* part : {"tuning_fraction", "held_out_fraction"}) {
            const double fraction = report[which][part].get<double>();
            EXPECT_GT(fraction, 0.0) << which << " " << part;
            EXPECT_LT(fraction, 1.5) << which << " " << part;
        }
    }
    // The search starts at the defaults and only accepts improvements.
    EXPECT_GE(report["tuned"]["tuning_fraction"].get<double>(), report["defaults"]["tuning_fraction"].get<double>());
    EXPECT_TRUE(report["forms"].contains("published"));
    EXPECT_TRUE(report["forms"].contains("extended"));
    // The default choice: the form with the better tuning score; "tuned" reports that set.
    EXPECT_EQ(report["selection"]["rule"], "tuning");
    EXPECT_FALSE(report["selection"].contains("folds"));
    EXPECT_FALSE(report["forms"]["published"].contains("cross_validated_fraction"));
    const int best = lodopt::scheduler::firstBestAbove(-INFINITY, {report["forms"]["published"]["tuning_fraction"].get<double>(),
                                                              report["forms"]["extended"]["tuning_fraction"].get<double>()});
    const std::string writtenForm = best == 1 ? "extended" : "published";
    EXPECT_EQ(report["selection"]["written"], writtenForm);
    EXPECT_EQ(report["coefficients"], report["forms"][writtenForm]["coefficients"]);
    // The file is a valid coefficients file with the report inside; one checkpoint per view.
    const lodopt::scheduler::SchedulerCoefficients c = lodopt::scheduler::loadCoefficients(sCoefficients);
    EXPECT_GT(c.importance.alpha1 + c.importance.alpha2, 0.0);
    EXPECT_TRUE(nlohmann::json::parse(readFile(sCoefficients)).contains("tuning"));
    for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(
            std::filesystem::exists(sDir / "tune" / "coeffs_views" / ("view_00" + std::to_string(k) + ".json")));
    }
}

TEST_F(SchedulerCli, SelectCvWritesTheDefaultsOrTheBestFormOutOfFold) {
    ASSERT_EQ(sTune.exitCode, 0);
    const std::string out = (sDir / "tune" / "bycv.json").string();
    const CommandResult result = run(resumingArguments("bycv") + " --resume --select cv --json");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const nlohmann::json report = parseOrFail(result);
    // 3 tuning views, 3 folds (the default); the written set is the defaults or the form whose
    // out-of-fold score beats them, and "tuned" reports that set.
    EXPECT_EQ(report["selection"]["rule"], "cv");
    EXPECT_EQ(report["selection"]["folds"], 3);
    const std::string writtenSet = report["selection"]["written"].get<std::string>();
    const double defaultsScore = report["selection"]["defaults_cross_validated_fraction"].get<double>();
    EXPECT_EQ(defaultsScore, report["defaults"]["tuning_fraction"].get<double>());  // nothing fitted
    std::vector<double> scores;
    for (const char* form : {"published", "extended"}) {
        scores.push_back(report["forms"][form]["cross_validated_fraction"].get<double>());
        EXPECT_GT(scores.back(), 0.0) << form;
    }
    const int best = lodopt::scheduler::firstBestAbove(defaultsScore, scores);
    EXPECT_EQ(writtenSet, best < 0 ? "defaults" : best == 0 ? "published" : "extended");
    if (writtenSet == "defaults") {
        EXPECT_EQ(report["tuned"], report["defaults"]);
        EXPECT_EQ(lodopt::scheduler::loadCoefficients(out).importance.alpha1, 0.6);
    } else {
        EXPECT_EQ(report["coefficients"], report["forms"][writtenSet]["coefficients"]);
        EXPECT_EQ(report["tuned"]["held_out_fraction"], report["forms"][writtenSet]["held_out_fraction"]);
    }
    // The searches on all tuning views do not depend on the rule.
    const nlohmann::json first = parseOrFail(sTune);
    EXPECT_EQ(report["forms"]["published"]["coefficients"], first["forms"]["published"]["coefficients"]);
    EXPECT_EQ(report["forms"]["extended"]["coefficients"], first["forms"]["extended"]["coefficients"]);
}

TEST_F(SchedulerCli, SelectCvWithOneTuningViewFallsBackToTheTuningScore) {
    // 2 views, 1 held out: one tuning view cannot be split into folds.
    const std::string out = (sDir / "tune_two" / "coeffs.json").string();
    const CommandResult result =
        run("tune --scene harbor --view-count 2 --evals 8 --max-iterations 2 --search-evals 8 --size 96x96 --threads 1 "
            "--profile " + sProfile + " --budget-ms " + std::to_string(sBudget) + " --out " + out +
            " --select cv --quiet --json");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const nlohmann::json report = parseOrFail(result);
    EXPECT_EQ(report["selection"]["rule"], "tuning");
    EXPECT_NE(report["selection"]["written"], "defaults");
    EXPECT_FALSE(report["forms"]["published"].contains("cross_validated_fraction"));
}

TEST_F(SchedulerCli, ResumeSkipsFinishedViewsAndGivesTheSameAnswer) {
    ASSERT_EQ(sTune.exitCode, 0);
    const nlohmann::json first = parseOrFail(sTune);
    const std::string arguments = resumingArguments("again");
    const CommandResult resumed = run(arguments + " --resume --json");
    ASSERT_EQ(resumed.exitCode, 0) << resumed.output;
    const nlohmann::json second = parseOrFail(resumed);
    for (const nlohmann::json& view : second["per_view"]) EXPECT_TRUE(view["resumed"].get<bool>());
    EXPECT_EQ(second["tuned"], first["tuned"]);
    EXPECT_EQ(second["defaults"], first["defaults"]);
    EXPECT_EQ(second["coefficients"], first["coefficients"]);
    // Other settings do not resume from those checkpoints.
    const CommandResult mismatch = run(arguments + " --resume --seed 9");
    EXPECT_EQ(mismatch.exitCode, 2);
}

TEST_F(SchedulerCli, ScheduleWritesFramesAndSummary) {
    ASSERT_EQ(sTune.exitCode, 0);
    const std::string out = (sDir / "schedule").string();
    const CommandResult result =
        run("schedule --scene harbor --path " + sPath + " --budget-ms " + std::to_string(sBudget) + " --coeffs " +
            sCoefficients + " --size 128x128 --profile " + sProfile + " --render --repeats 1 --out " + out +
            " --json --quiet");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const nlohmann::json summary = parseOrFail(result);
    EXPECT_EQ(summary["frames"], 8);
    EXPECT_EQ(summary["path"], "orbit");
    EXPECT_EQ(summary["switch_rule"], "hysteresis");  // the default (docs/scheduler.md, Goal 4)
    EXPECT_EQ(summary["shading"], "pbr");              // renderer::kDefaultShading
    EXPECT_EQ(summary["switch_margin"].get<double>(), 0.05);
    EXPECT_EQ(summary["switch_refill"].get<double>(), 0.05);  // docs/scheduler.md "Why r = 0.05"
    EXPECT_EQ(summary["feedback_beta"].get<double>(), 0.7);  // docs/scheduler.md "Feedback"
    EXPECT_GT(summary["decision_us"]["max"].get<double>(), 0.0);
    EXPECT_GT(summary["measured_ms"]["mean"].get<double>(), 0.0);
    EXPECT_GT(summary["fitness"]["mean"].get<double>(), 0.0);
    EXPECT_LE(summary["fitness"]["max"].get<double>(), 1.0);
    EXPECT_TRUE(summary.contains("measured_vs_budget"));
    EXPECT_TRUE(summary.contains("baseline_vs_budget"));
    EXPECT_EQ(summary["frame_time"]["statistic"], "median");  // what every profile predicts
    EXPECT_EQ(summary["frame_time"]["draws"], 1);
    // The measurement ceiling: the first, middle and last frames timed 20 times each (default).
    const nlohmann::json& ceiling = summary["measurement_ceiling"];
    ASSERT_EQ(ceiling["probes"].size(), 3u);
    EXPECT_EQ(ceiling["probes"][0]["frame"], 0);
    EXPECT_EQ(ceiling["probes"][1]["frame"], 4);
    EXPECT_EQ(ceiling["probes"][2]["frame"], 7);
    double sum = 0.0;
    for (const nlohmann::json& probe : ceiling["probes"]) {
        EXPECT_EQ(probe["measurements"], 20);
        EXPECT_GT(probe["median_ms"].get<double>(), 0.0);
        EXPECT_LE(probe["p10_ratio"].get<double>(), 1.0);
        EXPECT_GE(probe["p90_ratio"].get<double>(), 1.0);
        // A share of the 20 measurements: k / 20 with 1 <= k <= 20.
        const double twentieths = probe["ceiling"].get<double>() * 20.0;
        EXPECT_NEAR(twentieths, std::round(twentieths), 1e-9);
        EXPECT_GE(std::round(twentieths), 1.0);
        EXPECT_LE(std::round(twentieths), 20.0);
        sum += probe["ceiling"].get<double>();
    }
    EXPECT_DOUBLE_EQ(ceiling["ceiling"].get<double>(), sum / 3.0);
    // Goal 1 over the binding frames, as a share of that ceiling.
    const nlohmann::json& goal = summary["goal_1"];
    EXPECT_EQ(goal["binding_frames"], summary["measured_vs_budget"]["binding"]["frames"]);
    EXPECT_DOUBLE_EQ(goal["ceiling"].get<double>(), ceiling["ceiling"].get<double>());
    if (goal["binding_frames"].get<int>() > 0) {
        EXPECT_DOUBLE_EQ(goal["of_ceiling"].get<double>(),
                         goal["within_10_percent"].get<double>() / ceiling["ceiling"].get<double>());
    } else {
        EXPECT_TRUE(goal["of_ceiling"].is_null());
    }
    const std::string csv = readFile(std::filesystem::path(out) / "frames.csv");
    std::istringstream lines(csv);
    std::string header;
    std::getline(lines, header);
    for (const char* column :
         {"frame", "decision_us", "predicted_ms", "measured_ms", "fitness", "switches", "level_0", "level_5"}) {
        EXPECT_NE(header.find(column), std::string::npos) << column;
    }
    int rows = 0;
    for (std::string line; std::getline(lines, line);) ++rows;
    EXPECT_EQ(rows, 8);
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "summary.json"));
    // The paper's rule stays selectable.
    const CommandResult vmi20 =
        run("schedule --scene harbor --path " + sPath + " --budget-ms " + std::to_string(sBudget) +
            " --size 128x128 --profile " + sProfile + " --switch-rule vmi20 --out " + out + "_vmi20 --json --quiet");
    ASSERT_EQ(vmi20.exitCode, 0) << vmi20.output;
    EXPECT_EQ(parseOrFail(vmi20)["switch_rule"], "vmi20");
}

TEST_F(SchedulerCli, BadInputExitsWithTwo) {
    const std::string common = " --size 128x128 --profile " + sProfile + " --out " + (sDir / "bad").string();
    // The harbor has no camera path of its own.
    EXPECT_EQ(run("schedule --scene harbor --budget-ms 5" + common).exitCode, 2);
    EXPECT_EQ(run("schedule --scene harbor --path nowhere.json --budget-ms 5" + common).exitCode, 2);
    const std::string badPath = (sDir / "bad_path.json").string();
    std::ofstream(badPath) << R"({"frames": [{"position": [0, 1, 2]}]})";
    EXPECT_EQ(run("schedule --scene harbor --path " + badPath + " --budget-ms 5" + common).exitCode, 2);
    const std::string badCoefficients = (sDir / "bad_coeffs.json").string();
    std::ofstream(badCoefficients) << R"({"format": "lodopt-scheduler-coefficients", "version": 1})";
    EXPECT_EQ(
        run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --coeffs " + badCoefficients + common).exitCode,
        2);
    EXPECT_EQ(run("tune --scene harbor --view-count 1 --budget-ms 5" + common).exitCode, 2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --switch-control 1,2" + common).exitCode,
              2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --render --frame-time mean" + common)
                  .exitCode,
              2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --switch-rule dwell" + common).exitCode,
              2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --render --noise-probe -1" + common).exitCode,
              2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --switch-margin 1" + common).exitCode, 2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --switch-refill 1" + common).exitCode, 2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --switch-refill -0.1" + common).exitCode,
              2);
}

TEST_F(SchedulerCli, AFramesTimeIsTheMedianOfItsDrawsAsTheProfilePredicts) {
    const std::string out = (sDir / "schedule_median").string();
    const CommandResult result =
        run("schedule --scene harbor --path " + sPath + " --budget-ms " + std::to_string(sBudget) +
            " --size 128x128 --profile " + sProfile +
            " --render --no-fitness --repeats 3 --frames 3 --noise-probe 0 --out " + out + " --json --quiet");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const nlohmann::json summary = parseOrFail(result);
    EXPECT_EQ(summary["frame_time"]["statistic"], "median");
    EXPECT_EQ(summary["frame_time"]["clock"], "wall");  // llvmpipe
    EXPECT_EQ(summary["frame_time"]["draws"], 3);
    EXPECT_EQ(summary["frames"], 3);
    EXPECT_GT(summary["measured_ms"]["median"].get<double>(), 0.0);
    EXPECT_FALSE(summary.contains("measurement_ceiling"));  // --noise-probe 0
    EXPECT_TRUE(summary["goal_1"]["of_ceiling"].is_null());  // nothing to divide by
    // The least of the draws is no longer a choice: one statistic, the profile's.
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 3 --render --frame-time min --out " + out)
                  .exitCode,
              2);
}

// ---- schedule: interrupts and --resume ----------------------------------------------------

// 8 frames in batches of 2 = 4 checkpoints. Without --render every column but the decision's
// wall time is deterministic, so a resumed run must equal an uninterrupted one.
std::string scheduleArguments(const std::string& path, const std::string& profile, double budget,
                              const std::string& out) {
    return "schedule --scene harbor --path " + path + " --budget-ms " + std::to_string(budget) +
           " --size 128x128 --batch 2 --profile " + profile + " --out " + out + " --quiet";
}

TEST_F(SchedulerCli, ScheduleInterruptedBySignalsResumesToTheSameOutputs) {
    const std::filesystem::path whole = sDir / "schedule_whole";
    const Exit full = runChild(scheduleArguments(sPath, sProfile, sBudget, whole.string()), sDir / "err.txt");
    ASSERT_EQ(full.code, 0) << full.err;
    EXPECT_FALSE(std::filesystem::exists(whole / "schedule.checkpoint.json")) << "removed at the end";
    const std::string expectedCsv = readFile(whole / "frames.csv");
    const nlohmann::json expectedSummary = summaryWithoutWallTimes(whole);

    for (const auto& [signal, after] : {std::pair{SIGINT, 4}, std::pair{SIGTERM, 2}}) {
        SCOPED_TRACE(strsignal(signal));
        const std::filesystem::path out = sDir / ("schedule_cut" + std::to_string(signal));
        const std::filesystem::path checkpoint = out / "schedule.checkpoint.json";
        const std::string arguments = scheduleArguments(sPath, sProfile, sBudget, out.string());
        const Exit cut =
            runChild(arguments, sDir / "err.txt", {{"LODOPT_TEST_WAIT_AFTER_UNITS", std::to_string(after)}},
                     [&](pid_t pid) { killAfterFrames(pid, checkpoint, std::size_t(after), signal); });
        EXPECT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
        const std::string what = std::string("schedule: interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") +
                                 " after " + std::to_string(after) + " of 8 frames";
        EXPECT_NE(cut.err.find(what), std::string::npos) << cut.err;
        EXPECT_NE(cut.err.find("resume with: "), std::string::npos) << cut.err;
        EXPECT_NE(cut.err.find(" --resume"), std::string::npos) << cut.err;
        // Only complete files: the checkpoint with exactly the finished frames, no outputs yet.
        EXPECT_EQ(savedFrames(checkpoint), std::size_t(after));
        EXPECT_FALSE(std::filesystem::exists(out / "frames.csv"));
        for (const auto& entry : std::filesystem::directory_iterator(out)) {
            EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
        }
        const Exit refused = runChild(arguments, sDir / "err.txt");
        EXPECT_EQ(refused.code, 2);
        EXPECT_NE(refused.err.find("--resume"), std::string::npos) << refused.err;

        const Exit resumed = runChild(arguments + " --resume", sDir / "err.txt");
        ASSERT_EQ(resumed.code, 0) << resumed.err;
        EXPECT_FALSE(std::filesystem::exists(checkpoint));
        EXPECT_EQ(csvWithout(readFile(out / "frames.csv"), {"decision_us"}), csvWithout(expectedCsv, {"decision_us"}));
        EXPECT_EQ(summaryWithoutWallTimes(out), expectedSummary);
    }
}

// With --render the measured times cannot repeat; the resumed run takes the saved frames'
// measurements from the checkpoint and replays their feedback. Without feedback every other
// column equals an uninterrupted run's; with it, the saved frames and the model's feedback
// scale after them are restored exactly.
TEST_F(SchedulerCli, ScheduleResumeWithRenderRestoresMeasuredFramesAndFeedback) {
    const std::vector<std::string> measuredColumns = {"decision_us", "measured_ms", "baseline_measured_ms"};
    const std::string render = " --render --repeats 1";
    const std::filesystem::path whole = sDir / "render_whole";
    const Exit full = runChild(scheduleArguments(sPath, sProfile, sBudget, whole.string()) + render + " --no-feedback",
                               sDir / "err.txt");
    ASSERT_EQ(full.code, 0) << full.err;

    for (const bool feedback : {false, true}) {
        SCOPED_TRACE(feedback ? "feedback" : "no feedback");
        const std::filesystem::path out = sDir / (feedback ? "render_feedback" : "render_plain");
        const std::filesystem::path checkpoint = out / "schedule.checkpoint.json";
        const std::string arguments =
            scheduleArguments(sPath, sProfile, sBudget, out.string()) + render + (feedback ? "" : " --no-feedback");
        const Exit cut = runChild(arguments, sDir / "err.txt", {{"LODOPT_TEST_WAIT_AFTER_UNITS", "4"}},
                                  [&](pid_t pid) { killAfterFrames(pid, checkpoint, 4, SIGINT); });
        ASSERT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
        const nlohmann::json saved = nlohmann::json::parse(readFile(checkpoint));
        ASSERT_EQ(saved["frames"].size(), 4u);

        const Exit resumed = runChild(arguments + " --resume", sDir / "err.txt");
        ASSERT_EQ(resumed.code, 0) << resumed.err;
        const std::string csv = readFile(out / "frames.csv");
        const std::vector<double> measured = csvColumn(csv, "measured_ms");
        const std::vector<double> scale = csvColumn(csv, "feedback_scale");
        ASSERT_EQ(measured.size(), 8u);
        for (std::size_t f = 0; f < 4; ++f) {
            const double savedMs = saved["frames"][f]["measured_ms"].get<double>();
            const double savedScale = saved["frames"][f]["feedback_scale"].get<double>();
            EXPECT_NEAR(measured[f], savedMs, 1e-7 * savedMs) << "frame " << f;
            EXPECT_NEAR(scale[f], savedScale, 1e-7 * savedScale) << "frame " << f;
        }
        if (feedback) {
            EXPECT_NE(saved["frames"][3]["feedback_scale"].get<double>(), 1.0) << "the feedback did act";
        } else {
            EXPECT_EQ(csvWithout(csv, measuredColumns), csvWithout(readFile(whole / "frames.csv"), measuredColumns));
        }
    }
}

TEST_F(SchedulerCli, ScheduleResumeRefusesOtherOptionsOrABrokenCheckpoint) {
    const std::filesystem::path out = sDir / "schedule_refuse";
    const std::filesystem::path checkpoint = out / "schedule.checkpoint.json";
    const std::string arguments = scheduleArguments(sPath, sProfile, sBudget, out.string());
    const Exit cut = runChild(arguments, sDir / "err.txt", {{"LODOPT_TEST_WAIT_AFTER_UNITS", "2"}},
                              [&](pid_t pid) { killAfterFrames(pid, checkpoint, 2, SIGINT); });
    ASSERT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
    const std::string saved = readFile(checkpoint);

    const Exit otherBudget =
        runChild(scheduleArguments(sPath, sProfile, 1.5 * sBudget, out.string()) + " --resume", sDir / "err.txt");
    EXPECT_EQ(otherBudget.code, 2);
    EXPECT_NE(otherBudget.err.find("--budget-ms"), std::string::npos) << otherBudget.err;
    const Exit otherControl = runChild(arguments + " --no-switch-control --resume", sDir / "err.txt");
    EXPECT_EQ(otherControl.code, 2);
    EXPECT_NE(otherControl.err.find("--no-switch-control"), std::string::npos) << otherControl.err;

    std::ofstream(checkpoint) << saved.substr(0, saved.size() / 2);
    const Exit broken = runChild(arguments + " --resume", sDir / "err.txt");
    EXPECT_EQ(broken.code, 2);
    EXPECT_NE(broken.err.find("not a readable schedule checkpoint"), std::string::npos) << broken.err;

    // The batch size changes no result: resuming with another one is accepted.
    std::ofstream(checkpoint) << saved;
    std::string otherBatchArguments = arguments;
    otherBatchArguments.replace(otherBatchArguments.find("--batch 2"), 9, "--batch 3");
    const Exit otherBatch = runChild(otherBatchArguments + " --resume", sDir / "err.txt");
    EXPECT_EQ(otherBatch.code, 0) << otherBatch.err;
    EXPECT_FALSE(std::filesystem::exists(checkpoint));
}
