// lodopt bench --quick on a tiny harbor: its CSVs, bench.json and Pareto plot; the best known
// fitness is the exhaustive optimum (harbor has 150 combinations); the fast path agrees with
// the full path; progress goes to the terminal and never into --json stdout.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "report_data.hpp"
#include "run_lodopt.hpp"
#include "lodopt_test_paths.hpp"

namespace {

namespace fs = std::filesystem;

using lodopt::cli_test::CommandResult;
using lodopt::cli_test::runLodopt;
using lodopt::cli_test::runShell;

std::string readText(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
}

class BenchCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        sDir = fs::temp_directory_path() / ("lodopt-cli-bench-" + std::to_string(::getpid()));
        fs::remove_all(sDir);
        fs::create_directories(sDir);
        sProfile = (sDir / "device.json").string();
        const bool calibrated = runLodopt(
                                    "calibrate --scene harbor --samples 16 --jitter 1 --rounds 1 --repeats 1 "
                                    "--warmup 1 --size 96x96 --seed 3 --quiet --out " +
                                    sProfile)
                                    .exitCode == 0;
        if (!calibrated) return;
        sBench = runLodopt("bench --scene harbor --size 96x96 --profile " + sProfile +
                           " --quick --algos gapso,greedy --threads 2 --out " + (sDir / "bench").string() + " --json");
    }
    static void TearDownTestSuite() { fs::remove_all(sDir); }

    void SetUp() override { ASSERT_EQ(sBench.exitCode, 0) << "bench failed in " << sDir; }

    static fs::path sDir;
    static std::string sProfile;
    static CommandResult sBench;
};

fs::path BenchCli::sDir;
std::string BenchCli::sProfile;
CommandResult BenchCli::sBench;

}  // namespace

TEST_F(BenchCli, QuickRunWritesEveryTable) {
    const nlohmann::json document = nlohmann::json::parse(sBench.output);  // stdout is one JSON document
    EXPECT_EQ(document["scene"], "harbor");
    EXPECT_EQ(document["best_known"]["source"], "exhaustive");
    EXPECT_EQ(document["best_known"]["combinations"].get<double>(), 150.0);
    const fs::path dir = sDir / "bench";
    EXPECT_EQ(nlohmann::json::parse(readText(dir / "bench.json"))["algorithm_budget"], document["algorithm_budget"]);

    using lodopt::cli::readCsv;
    const lodopt::cli::CsvTable algorithms = readCsv((dir / "bench_algorithms.csv").string());
    ASSERT_EQ(algorithms.rows.size(), 4u);  // {gapso, greedy} x {30, 100}
    EXPECT_EQ(algorithms.text(0, "algorithm"), "gapso");
    EXPECT_EQ(algorithms.text(1, "evaluation_budget"), "100");
    EXPECT_EQ(algorithms.text(0, "runs"), "2");  // --quick: two seeds
    EXPECT_EQ(algorithms.text(2, "runs"), "1");  // greedy is deterministic
    const double best = document["best_known"]["fitness"].get<double>();
    const lodopt::cli::CsvTable runs = readCsv((dir / "bench_runs.csv").string());
    ASSERT_EQ(runs.rows.size(), 6u);
    for (std::size_t r = 0; r < runs.rows.size(); ++r) {
        EXPECT_LE(runs.number(r, "fitness"), best + 1e-12);
        EXPECT_NEAR(runs.number(r, "gap"), best - runs.number(r, "fitness"), 1e-6);
        EXPECT_LE(runs.number(r, "evaluations"), runs.number(r, "evaluation_budget"));
        EXPECT_GT(runs.number(r, "wall_seconds"), 0.0);
    }

    const lodopt::cli::CsvTable paths = readCsv((dir / "bench_eval_paths.csv").string());
    ASSERT_EQ(paths.rows.size(), 6u);  // {random, walk} x {full, fast batch, fast single}
    for (std::size_t r = 0; r < paths.rows.size(); ++r) {
        EXPECT_GT(paths.number(r, "evals_per_second"), 0.0);
        if (paths.text(r, "path") == "fast") {
            // Layers composite to the full render except at exactly equal depths (none here).
            EXPECT_LT(paths.number(r, "max_abs_fitness_diff"), 1e-9) << paths.text(r, "workload");
        }
    }
    const lodopt::cli::CsvTable metrics = readCsv((dir / "bench_metrics.csv").string());
    ASSERT_GE(metrics.rows.size(), 5u);
    EXPECT_EQ(metrics.text(0, "function"), "ssim");
    EXPECT_LT(metrics.number(0, "abs_deviation"), 1e-9);  // float64 vs float64, same definition
    EXPECT_GT(metrics.number(0, "microseconds_per_call"), 0.0);
    const lodopt::cli::CsvTable models = readCsv((dir / "bench_timemodel.csv").string());
    ASSERT_FALSE(models.rows.empty());
    bool timedNow = false;
    for (std::size_t r = 0; r < models.rows.size(); ++r) {
        if (models.text(r, "source") != "this view, timed now") continue;
        timedNow = true;
        EXPECT_EQ(models.text(r, "samples"), "8");  // --quick: 8 frames
        EXPECT_GE(models.number(r, "mean_error"), 0.0);
    }
    EXPECT_TRUE(timedNow);

    const std::string pareto = readText(dir / "bench_pareto.gp");
    EXPECT_NE(pareto.find("set logscale xy"), std::string::npos);
    EXPECT_NE(readText(dir / "bench_pareto.dat").find("# greedy"), std::string::npos);
    const char* configured = std::getenv("LODOPT_GNUPLOT");
    if (configured && (std::string(configured) == "none" || ::access(configured, X_OK) != 0)) {
        EXPECT_TRUE(document["pareto_plot"].is_null());
        GTEST_SKIP() << "LODOPT_GNUPLOT=" << configured << " turns the plot off: the plot itself is not checked";
    }
    ASSERT_EQ(std::system("command -v gnuplot >/dev/null 2>&1"), 0) << "gnuplot (gnuplot-nox: the quick start installs it)";
    EXPECT_EQ(document["pareto_plot"], "bench_pareto.png");
    EXPECT_EQ(readText(dir / "bench_pareto.png").compare(0, 4, "\x89PNG"), 0);
}

TEST_F(BenchCli, ReportShowsTheBench) {
    const CommandResult result = runLodopt("report " + (sDir / "bench").string() + " --json");
    ASSERT_EQ(result.exitCode, 0);
    const std::string html = readText(sDir / "bench" / "report.html");
    EXPECT_NE(html.find("bench: harbor / overview"), std::string::npos);
    EXPECT_NE(html.find("Fast vs full evaluation path"), std::string::npos);
    EXPECT_NE(html.find("deviation from float64 references"), std::string::npos);
    EXPECT_NE(html.find("Time models"), std::string::npos);
    EXPECT_TRUE(fs::exists(sDir / "bench" / "report_files" / "bench_pareto.gp"));
}

TEST_F(BenchCli, ProgressGoesToTheTerminalAndJsonStdoutStaysClean) {
    ASSERT_EQ(std::system("command -v script >/dev/null 2>&1"), 0) << "no 'script' (bsdutils) to provide a terminal";
    // `script` gives the command a pseudo-terminal for stderr; stdout goes to a file.
    const fs::path out = sDir / "terminal.json";
    const std::string inner = "env -u CI " + std::string(LODOPT_EXECUTABLE) +
                              " bench --scene harbor --size 64x64 --profile " + sProfile +
                              " --quick --algos random --evals 20 --candidates 4 --timing-frames 2 --out " +
                              (sDir / "terminal").string() + " --json > " + out.string();
    const CommandResult terminal = runShell("script -qec '" + inner + "' /dev/null");
    ASSERT_EQ(terminal.exitCode, 0) << terminal.output;
    EXPECT_NE(terminal.output.find("bench ["), std::string::npos) << terminal.output;
    EXPECT_NE(terminal.output.find("ETA"), std::string::npos);
    const nlohmann::json document = nlohmann::json::parse(readText(out));  // throws if polluted
    EXPECT_EQ(document["algorithms"], nlohmann::json::array({"random"}));
    // --quiet: no progress line even on a terminal.
    const CommandResult quiet = runShell("script -qec '" + inner + " --quiet' /dev/null");
    ASSERT_EQ(quiet.exitCode, 0);
    EXPECT_EQ(quiet.output.find("bench ["), std::string::npos) << quiet.output;
}

TEST_F(BenchCli, BadOptionsExitWithTwo) {
    const std::string base =
        "bench --scene harbor --size 64x64 --profile " + sProfile + " --out " + (sDir / "bad").string();
    EXPECT_EQ(runLodopt(base + " --evals 0").exitCode, 2);
    EXPECT_EQ(runLodopt(base + " --evals 30,x").exitCode, 2);
    EXPECT_EQ(runLodopt(base + " --algos exhaustive").exitCode, 2);
    EXPECT_EQ(runLodopt(base + " --algos nosuch").exitCode, 2);
    EXPECT_EQ(runLodopt(base + " --view all").exitCode, 2);
    EXPECT_EQ(runLodopt(base + " --budget-ms 0.000001").exitCode, 2);  // below the all-coarsest prediction
    EXPECT_FALSE(fs::exists(sDir / "bad" / "bench.json"));
}
