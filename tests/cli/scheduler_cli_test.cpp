// lodopt tune / schedule end to end on the harbor at 128x128 with a tiny calibration (seconds):
// coefficients and both fractions reported, checkpoints and --resume, the per-frame CSV, and
// bad input mapped to exit code 2.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "scenes/builtin.hpp"
#include "scheduler/coefficients.hpp"
#include "timemodel/features.hpp"
#include "timemodel/profile.hpp"

namespace {

struct CommandResult {
    int exitCode = -1;
    std::string output;  // stdout only
};

CommandResult run(const std::string& arguments) {
    const std::string command = std::string(LODOPT_EXECUTABLE) + " " + arguments + " 2>/dev/null";
    CommandResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
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
        return "tune --scene harbor --views 4 --evals 24 --max-iterations 6 --search-evals 30 --size 128x128 --threads "
               "1 "
               "--profile " +
               sProfile + " --budget-ms " + std::to_string(sBudget) + " --out " + sCoefficients + " --quiet";
    }

    void SetUp() override {
        if (!sCalibrated) GTEST_SKIP() << "lodopt calibrate failed (no OpenGL context?)";
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
    // The file is a valid coefficients file with the report inside; one checkpoint per view.
    const lodopt::scheduler::SchedulerCoefficients c = lodopt::scheduler::loadCoefficients(sCoefficients);
    EXPECT_GT(c.importance.alpha1 + c.importance.alpha2, 0.0);
    EXPECT_TRUE(nlohmann::json::parse(readFile(sCoefficients)).contains("tuning"));
    for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(
            std::filesystem::exists(sDir / "tune" / "coeffs_views" / ("view_00" + std::to_string(k) + ".json")));
    }
}

TEST_F(SchedulerCli, ResumeSkipsFinishedViewsAndGivesTheSameAnswer) {
    ASSERT_EQ(sTune.exitCode, 0);
    const nlohmann::json first = parseOrFail(sTune);
    const std::string again = (sDir / "tune" / "again.json").string();
    // A checkpoint folder of the first run, under the second output's name.
    std::filesystem::copy(sDir / "tune" / "coeffs_views", sDir / "tune" / "again_views");
    std::string arguments = tuneArguments();
    arguments.replace(arguments.find(sCoefficients), sCoefficients.size(), again);
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
    EXPECT_GT(summary["decision_us"]["max"].get<double>(), 0.0);
    EXPECT_GT(summary["measured_ms"]["mean"].get<double>(), 0.0);
    EXPECT_GT(summary["fitness"]["mean"].get<double>(), 0.0);
    EXPECT_LE(summary["fitness"]["max"].get<double>(), 1.0);
    EXPECT_TRUE(summary.contains("measured_vs_budget"));
    EXPECT_TRUE(summary.contains("baseline_vs_budget"));
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
    EXPECT_EQ(run("tune --scene harbor --views 1 --budget-ms 5" + common).exitCode, 2);
    EXPECT_EQ(run("schedule --scene harbor --path " + sPath + " --budget-ms 5 --switch-control 1,2" + common).exitCode,
              2);
}
