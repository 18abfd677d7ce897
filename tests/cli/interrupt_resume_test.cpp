// Interrupts and --resume of `lodopt tune` and `lodopt bench` (docs/robustness.md): each is
// stopped by a signal after a known unit (LODOPT_TEST_WAIT_AFTER_UNITS), leaves exactly the
// finished units in its checkpoint, refuses to start over it without --resume, and resumes
// (with another thread count) to the outputs of an uninterrupted run, timings aside. The
// bench checkpoint's JSON round trip is checked in-process.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "bench_checkpoint.hpp"
#include "checkpoint.hpp"
#include "child_process.hpp"
#include "cli_common.hpp"
#include "interrupt.hpp"
#include "report_data.hpp"

namespace fs = std::filesystem;

namespace {

using lodopt::cli_test::Exit;
using lodopt::cli_test::readJson;
using lodopt::cli_test::signalWhen;
using lodopt::cli_test::slurp;

// The lodopt executable as a child process; stdout and stderr go to files in `dir`.
Exit runLodopt(const std::string& arguments, const fs::path& dir, const lodopt::cli_test::Environment& environment = {},
               const std::function<void(pid_t)>& whileRunning = {}) {
    return lodopt::cli_test::runLodoptChild(lodopt::cli_test::splitWords(arguments), dir / "stdout.txt",
                                            dir / "stderr.txt", environment, whileRunning);
}

void expectNoTemporaryFile(const fs::path& dir) {
    for (const auto& entry : fs::directory_iterator(dir)) {
        EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }
}

void expectInterruptMessage(const Exit& cut, int signal, const std::string& what) {
    EXPECT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
    const std::string expected = std::string("interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") + what;
    EXPECT_NE(cut.err.find(expected), std::string::npos) << cut.err;
    EXPECT_NE(cut.err.find("resume with: "), std::string::npos) << cut.err;
    EXPECT_NE(cut.err.find(" --resume"), std::string::npos) << cut.err;
}

class InterruptResume : public lodopt::cli_test::FolderWithFixedProfile {
protected:
    InterruptResume() : FolderWithFixedProfile("lodopt-resume-") {}
};

// ---- tune: one unit per view ---------------------------------------------------------------

const char* kTune =
    "tune --scene harbor --view-count 4 --evals 12 --max-iterations 4 --search-evals 10 --size 64x64 --budget-ms 2 "
    "--quiet --out ";

std::size_t viewFiles(const fs::path& dir) {
    std::size_t count = 0;
    if (!fs::is_directory(dir)) return 0;
    for (const auto& entry : fs::directory_iterator(dir)) count += entry.path().extension() == ".json" ? 1 : 0;
    return count;
}

// coeffs.json without what may differ between an uninterrupted and a resumed run: timings,
// the checkpoint folder's name and whether a view was resumed.
nlohmann::json tuneResult(const fs::path& file) {
    nlohmann::json document = readJson(file);
    nlohmann::json& tuning = document["tuning"];
    for (const char* key : {"seconds", "checkpoints"}) {
        EXPECT_TRUE(tuning.contains(key)) << key;
        tuning.erase(key);
    }
    for (nlohmann::json& view : tuning["per_view"]) {
        view.erase("optimizer_seconds");
        view.erase("resumed");
    }
    return document;
}

TEST_F(InterruptResume, TuneStopsAfterAViewAndResumesToTheSameCoefficients) {
    const fs::path whole = mDir / "whole" / "coeffs.json";
    const Exit full = runLodopt(kTune + whole.string() + mProfile + " --threads 2", mDir);
    ASSERT_EQ(full.code, 0) << full.err;
    const nlohmann::json expected = tuneResult(whole);
    ASSERT_EQ(expected["tuning"]["per_view"].size(), 4u);

    const fs::path out = mDir / "cut" / "coeffs.json";
    const fs::path views = mDir / "cut" / "coeffs_views";
    const Exit cut = runLodopt(kTune + out.string() + mProfile + " --threads 2", mDir,
                               {{"LODOPT_TEST_WAIT_AFTER_UNITS", "2"}}, [&](pid_t pid) {
                                   signalWhen(
                                       pid, [&] { return viewFiles(views) >= 2; }, SIGINT);
                               });
    expectInterruptMessage(cut, SIGINT, " after 2 of 4 views; the finished ones are saved in " + views.string());
    // Exactly the finished views, each complete; no coefficients file yet; no temporary file.
    EXPECT_EQ(viewFiles(views), 2u);
    for (const char* name : {"view_000.json", "view_001.json"}) {
        EXPECT_EQ(readJson(views / name)["format"], "lodopt-tune-view") << name;
    }
    EXPECT_FALSE(fs::exists(out));
    expectNoTemporaryFile(views);

    // Without --resume the saved views are not silently overwritten.
    const Exit refused = runLodopt(kTune + out.string() + mProfile, mDir);
    EXPECT_EQ(refused.code, 2);
    EXPECT_NE(refused.err.find("add --resume"), std::string::npos) << refused.err;
    // Another result-changing option is refused by name.
    const Exit changed = runLodopt(kTune + out.string() + mProfile + " --seed 9 --resume", mDir);
    EXPECT_EQ(changed.code, 2);
    EXPECT_NE(changed.err.find("--seed"), std::string::npos) << changed.err;
    EXPECT_EQ(viewFiles(views), 2u);

    const Exit resumed = runLodopt(kTune + out.string() + mProfile + " --threads 1 --resume", mDir);
    ASSERT_EQ(resumed.code, 0) << resumed.err;
    const nlohmann::json perView = readJson(out)["tuning"]["per_view"];
    ASSERT_EQ(perView.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(perView[k]["resumed"].get<bool>(), k < 2) << "view " << k;
    EXPECT_EQ(tuneResult(out), expected);
    EXPECT_EQ(viewFiles(views), 4u);  // tune keeps its checkpoints for later runs

    // The tune finished (coeffs.json is newer than its views): the same command again, without
    // --resume, starts over instead of refusing, and gives the same coefficients.
    const Exit again = runLodopt(kTune + out.string() + mProfile + " --threads 2", mDir);
    ASSERT_EQ(again.code, 0) << again.err;
    const nlohmann::json rerun = readJson(out);
    for (const nlohmann::json& view : rerun["tuning"]["per_view"]) EXPECT_FALSE(view["resumed"].get<bool>());
    EXPECT_EQ(tuneResult(out), expected);
    EXPECT_EQ(viewFiles(views), 4u);

    // A broken checkpoint is bad input, not a crash.
    const std::string saved = slurp(views / "view_000.json");
    std::ofstream(views / "view_000.json") << saved.substr(0, saved.size() / 2);
    const Exit broken = runLodopt(kTune + out.string() + mProfile + " --resume", mDir);
    EXPECT_EQ(broken.code, 2);
    EXPECT_NE(broken.err.find("not a tune checkpoint"), std::string::npos) << broken.err;
}

// ---- bench: one unit per grid run, then best known, paths, metrics, time models -------------

// random (2 seeds) and greedy (1) at one budget: 3 runs + 4 sections = 7 units.
const char* kBench =
    "bench --scene harbor --size 64x64 --quick --algos random,greedy --evals 20 --candidates 4 --timing-frames 2 "
    "--quiet --out ";
constexpr std::size_t kBenchUnits = 7;

std::size_t savedUnits(const nlohmann::json& checkpoint) {
    std::size_t units = checkpoint["runs"].size();
    for (const char* section : {"best_known", "eval_paths", "metrics", "time_models"}) {
        units += checkpoint.contains(section) ? 1 : 0;
    }
    return units;
}

// The columns of a CSV that do not depend on timing, as JSON rows.
nlohmann::json csvColumns(const fs::path& file, const std::vector<std::string>& columns) {
    const lodopt::cli::CsvTable table = lodopt::cli::readCsv(file.string());
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        nlohmann::json row;
        for (const std::string& column : columns) {
            EXPECT_TRUE(table.has(column)) << file << ": " << column;
            if (table.has(column)) row[column] = table.text(r, column);
        }
        rows.push_back(row);
    }
    return rows;
}

// Everything deterministic a bench writes: fitness, gaps, evaluation counts, fast-vs-full
// differences, metric deviations, the calibration rows and sample counts of the time models.
nlohmann::json benchResult(const fs::path& dir) {
    nlohmann::json document = readJson(dir / "bench.json");
    for (const char* key : {"seconds", "eval_paths", "metrics", "time_model_errors", "out"}) document.erase(key);
    document["best_known"].erase("exhaustive_seconds");
    document["surrogate_table"].erase("seconds");
    for (nlohmann::json& row : document["algorithm_budget"]) row.erase("median_wall_seconds");
    for (nlohmann::json& run : document["runs"]) run.erase("wall_seconds");
    document["runs_csv"] =
        csvColumns(dir / "bench_runs.csv", {"algorithm", "evaluation_budget", "seed", "fitness", "gap", "evaluations",
                                            "predicted_ms", "evaluations_to_near_best"});
    document["algorithms_csv"] =
        csvColumns(dir / "bench_algorithms.csv",
                   {"algorithm", "evaluation_budget", "runs", "median_gap", "min_gap", "max_gap", "median_fitness",
                    "median_evaluations", "reached_near_best", "median_evaluations_to_near_best"});
    // A restored section keeps the thread count it was measured with: not compared.
    document["paths_csv"] = csvColumns(dir / "bench_eval_paths.csv", {"path", "workload", "mode", "candidates",
                                                                      "mean_abs_fitness_diff", "max_abs_fitness_diff"});
    document["metrics_csv"] =
        csvColumns(dir / "bench_metrics.csv", {"function", "width", "height", "reference", "abs_deviation"});
    document["time_csv"] = csvColumns(dir / "bench_timemodel.csv", {"model", "source", "samples"});
    return document;
}

std::string csvNumber(double value) {
    std::ostringstream out;
    out << std::setprecision(std::numeric_limits<double>::max_digits10) << value;  // as bench writes its CSVs
    return out.str();
}

TEST_F(InterruptResume, BenchStopsAfterAUnitAndResumesToTheSameTables) {
    const fs::path whole = mDir / "whole";
    const Exit full = runLodopt(kBench + whole.string() + mProfile + " --threads 1", mDir);
    ASSERT_EQ(full.code, 0) << full.err;
    EXPECT_FALSE(fs::exists(whole / "bench.checkpoint.json")) << "removed once the outputs are written";
    const nlohmann::json expected = benchResult(whole);
    ASSERT_EQ(expected["runs_csv"].size(), 3u);

    struct Case {
        int signal;
        std::size_t after;
    };
    // In the grid, after the best-known search and the evaluation paths, after the metrics.
    for (const Case& c : {Case{SIGTERM, 2}, Case{SIGINT, 5}, Case{SIGKILL, 6}}) {
        SCOPED_TRACE(strsignal(c.signal));
        const fs::path out = mDir / ("cut" + std::to_string(c.signal));
        const fs::path checkpoint = out / "bench.checkpoint.json";
        auto saved = [&] {
            if (!fs::exists(checkpoint)) return false;
            const nlohmann::json json = nlohmann::json::parse(slurp(checkpoint), nullptr, false);
            return !json.is_discarded() && savedUnits(json) >= c.after;
        };
        const Exit cut = runLodopt(kBench + out.string() + mProfile + " --threads 2", mDir,
                                   {{"LODOPT_TEST_WAIT_AFTER_UNITS", std::to_string(c.after)}},
                                   [&](pid_t pid) { signalWhen(pid, saved, c.signal); });
        if (c.signal == SIGKILL) {
            EXPECT_EQ(cut.signal, SIGKILL);
        } else {
            expectInterruptMessage(cut, c.signal,
                                   " after " + std::to_string(c.after) + " of " + std::to_string(kBenchUnits) +
                                       " units; the finished ones are saved in " + checkpoint.string());
        }
        const nlohmann::json units = readJson(checkpoint);
        EXPECT_EQ(savedUnits(units), c.after);
        EXPECT_EQ(units["runs"].size(), std::min<std::size_t>(c.after, 3));
        EXPECT_FALSE(fs::exists(out / "bench.json"));
        EXPECT_FALSE(fs::exists(out / "bench_runs.csv"));
        expectNoTemporaryFile(out);

        const Exit refused = runLodopt(kBench + out.string() + mProfile, mDir);
        EXPECT_EQ(refused.code, 2);
        EXPECT_NE(refused.err.find("add --resume"), std::string::npos) << refused.err;

        const Exit resumed = runLodopt(kBench + out.string() + mProfile + " --threads 1 --resume", mDir);
        ASSERT_EQ(resumed.code, 0) << resumed.err;
        EXPECT_FALSE(fs::exists(checkpoint));
        EXPECT_EQ(benchResult(out), expected);
        // The saved runs were taken from the checkpoint, not run again: their wall times are
        // the interrupted process's.
        const lodopt::cli::CsvTable runs = lodopt::cli::readCsv((out / "bench_runs.csv").string());
        for (std::size_t r = 0; r < units["runs"].size(); ++r) {
            EXPECT_EQ(runs.text(r, "wall_seconds"), csvNumber(units["runs"][r]["wall_seconds"].get<double>())) << r;
        }
    }
}

TEST_F(InterruptResume, BenchResumeRefusesOtherOptionsAndABrokenCheckpoint) {
    const fs::path out = mDir / "out";
    const fs::path checkpoint = out / "bench.checkpoint.json";
    const Exit cut =
        runLodopt(kBench + out.string() + mProfile, mDir, {{"LODOPT_TEST_WAIT_AFTER_UNITS", "1"}}, [&](pid_t pid) {
            signalWhen(
                pid, [&] { return fs::exists(checkpoint); }, SIGINT);
        });
    ASSERT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
    const std::string saved = slurp(checkpoint);

    std::string other = kBench;
    other.replace(other.find("--candidates 4"), 14, "--candidates 5");
    const Exit changed = runLodopt(other + out.string() + mProfile + " --resume", mDir);
    EXPECT_EQ(changed.code, 2);
    EXPECT_NE(changed.err.find("--candidates"), std::string::npos) << changed.err;
    EXPECT_EQ(slurp(checkpoint), saved) << "a refused resume leaves the checkpoint alone";

    std::ofstream(checkpoint) << saved.substr(0, saved.size() / 2);
    const Exit broken = runLodopt(kBench + out.string() + mProfile + " --resume", mDir);
    EXPECT_EQ(broken.code, 2);
    EXPECT_NE(broken.err.find("not a readable bench checkpoint"), std::string::npos) << broken.err;
}

// In-process: every double of every unit comes back bit for bit, NaN included.
TEST(BenchCheckpoint, DoublesRoundTripExactly) {
    using namespace lodopt::cli;
    const double awkward[] = {0.1 + 0.2, 1.0 / 3.0, 5e-324, 1.7976931348623157e308, -0.0, 0.9820709083698521};
    BenchCheckpoint written;
    for (std::size_t i = 0; i < std::size(awkward); ++i) {
        written.runs.push_back({"gapso",
                                30,
                                i + 1,
                                awkward[i],
                                awkward[(i + 1) % 6],
                                awkward[(i + 2) % 6],
                                std::int64_t(i) * 7,
                                {{1, awkward[(i + 3) % 6]}, {std::int64_t(i) * 5 + 2, awkward[(i + 4) % 6]}}});
    }
    written.bestKnown = lodopt::evaluation::BestKnown{awkward[0], "exhaustive", 150.0, 103, awkward[1]};
    written.evalPaths = std::vector<lodopt::evaluation::EvalPathRow>{
        {"full", "random", "single", 1, 4, awkward[2], awkward[3], NAN, NAN},
        {"fast", "walk", "batch", 2, 4, awkward[4], awkward[5], 1e-17, 0.0}};
    lodopt::evaluation::MetricsRow ssim{"ssim", 64, 64, 12, awkward[1], "OpenCV", awkward[0], 1.67e-14};
    lodopt::evaluation::MetricsRow recall{"precision_recall", 64, 64, 9, awkward[3], "", NAN, NAN};
    written.metrics = std::vector<lodopt::evaluation::MetricsRow>{ssim, recall};
    written.timeModels = TimeModelSection{{{"linear", "this view, timed now", 2, awkward[0], awkward[1], NAN, 0.5}},
                                          {"the profile was measured at 128x128"}};
    const fs::path file =
        fs::temp_directory_path() / ("lodopt-bench-checkpoint-" + std::to_string(::getpid()) + ".json");
    const nlohmann::json identity = {{"scene", "harbor"}, {"candidates", 4}};
    const CheckpointFile checkpoint(file.string(), "bench", "units");
    checkpoint.save(identity, benchToCheckpoint(written));
    BenchCheckpoint read;
    EXPECT_TRUE(checkpoint.restore(true, true, identity,
                                   [&](const nlohmann::json& saved) { read = benchFromCheckpoint(saved); }));

    auto same = [](double a, double b) {
        return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
    };
    ASSERT_EQ(read.runs.size(), written.runs.size());
    for (std::size_t i = 0; i < read.runs.size(); ++i) {
        EXPECT_EQ(read.runs[i].seed, written.runs[i].seed);
        EXPECT_EQ(read.runs[i].evaluations, written.runs[i].evaluations);
        EXPECT_TRUE(same(read.runs[i].wallSeconds, written.runs[i].wallSeconds)) << i;
        EXPECT_TRUE(same(read.runs[i].fitness, written.runs[i].fitness)) << i;
        EXPECT_TRUE(same(read.runs[i].predictedMs, written.runs[i].predictedMs)) << i;
        ASSERT_EQ(read.runs[i].improvements.size(), 2u);
        for (std::size_t k = 0; k < 2; ++k) {
            EXPECT_EQ(read.runs[i].improvements[k].first, written.runs[i].improvements[k].first);
            EXPECT_TRUE(same(read.runs[i].improvements[k].second, written.runs[i].improvements[k].second)) << i;
        }
    }
    ASSERT_TRUE(read.bestKnown && read.evalPaths && read.metrics && read.timeModels);
    EXPECT_TRUE(same(read.bestKnown->fitness, awkward[0]));
    EXPECT_EQ(read.bestKnown->evaluations, 103);
    ASSERT_EQ(read.evalPaths->size(), 2u);
    EXPECT_TRUE(std::isnan((*read.evalPaths)[0].maxAbsFitnessDiff));
    EXPECT_TRUE(same((*read.evalPaths)[1].evaluationsPerSecond, awkward[5]));
    EXPECT_TRUE(same((*read.evalPaths)[1].meanAbsFitnessDiff, 1e-17));
    EXPECT_EQ((*read.evalPaths)[1].threads, 2);
    ASSERT_EQ(read.metrics->size(), 2u);
    EXPECT_TRUE(same((*read.metrics)[0].absDeviation, 1.67e-14));
    EXPECT_TRUE(std::isnan((*read.metrics)[1].referenceMicrosecondsPerCall));
    ASSERT_EQ(read.timeModels->rows.size(), 1u);
    EXPECT_TRUE(same(read.timeModels->rows[0].median, awkward[1]));
    EXPECT_TRUE(std::isnan(read.timeModels->rows[0].p90));
    EXPECT_EQ(read.timeModels->warnings, written.timeModels->warnings);

    // Written with other options: refused, naming the option.
    try {
        checkpoint.restore(true, true, {{"scene", "harbor"}, {"candidates", 5}}, [](const nlohmann::json&) {});
        ADD_FAILURE() << "no UsageError";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("--candidates 4, this run has 5"), std::string::npos) << error.what();
    }
    // Without --resume an existing checkpoint is refused rather than overwritten.
    try {
        checkpoint.restore(false, true, identity, [](const nlohmann::json&) {});
        ADD_FAILURE() << "no UsageError";
    } catch (const UsageError& error) {
        EXPECT_NE(std::string(error.what()).find("add --resume"), std::string::npos) << error.what();
    }
    checkpoint.remove();
    EXPECT_FALSE(fs::exists(file));
    EXPECT_FALSE(checkpoint.restore(true, true, identity, [](const nlohmann::json&) {}));
}

}  // namespace
