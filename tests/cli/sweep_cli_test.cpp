// lodopt sweep: one process, shards and merge, mpirun ranks, resume after a killed rank; the
// merged table is the same bytes in every case.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "child_process.hpp"
#include "run_lodopt.hpp"
#include "lodopt_test_paths.hpp"

namespace lodopt::cli_test {
namespace {

namespace fs = std::filesystem;

// Eight views of the harbor at 64x64 under a budget some grid views cannot meet (recorded as
// infeasible), with a short search: a few seconds in all.
const std::string kSweep =
    "sweep --scene harbor --grid 2x2x2@5 --size 64x64 --budget-ms 0.5515 --max-evals 60 --threads 1 --quiet";

struct SweepFolders {
    fs::path root;
    SweepFolders() {
        root = fs::temp_directory_path() /
               ("lodopt_sweep_" + std::to_string(::getpid()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(root);
        fs::create_directories(root);
    }
    ~SweepFolders() { fs::remove_all(root); }
    std::string operator/(const std::string& name) const { return (root / name).string(); }
};

// The one-process sweep every other way of running is compared with.
std::string referenceSweep(const SweepFolders& folders) {
    const CommandResult run = runLodopt(kSweep + " --out " + (folders / "one"));
    EXPECT_EQ(run.exitCode, 0);
    return slurp(folders / "one/sweep.json");
}

TEST(SweepCli, OneProcessWritesEveryViewAndTheMergedTable) {
    SweepFolders folders;
    const CommandResult run = runLodopt(kSweep + " --out " + (folders / "one") + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json summary = nlohmann::json::parse(run.output);
    EXPECT_EQ(summary["views"], 8);
    EXPECT_EQ(summary["ranks"], 1);
    const nlohmann::json sweep = readJson(folders / "one/sweep.json");
    ASSERT_EQ(sweep["views"].size(), 8u);
    const std::size_t objects = sweep["objects"].size();
    int infeasible = 0;
    for (const nlohmann::json& view : sweep["views"]) {
        EXPECT_EQ(view["levels"].size(), objects);
        EXPECT_EQ(view["screen_sizes"].size(), objects);
        // The searched objects, ascending and in range, as many as searched_objects says.
        const std::vector<int> searched = view["searched"].get<std::vector<int>>();
        EXPECT_EQ(searched.size(), view["searched_objects"].get<std::size_t>());
        EXPECT_TRUE(std::is_sorted(searched.begin(), searched.end()));
        for (int object : searched) EXPECT_LT(std::size_t(object), objects);
        EXPECT_GT(view["fitness"].get<double>(), 0.0);
        EXPECT_LE(view["fitness"].get<double>(), 1.0);
        if (view["feasible"].get<bool>()) {
            EXPECT_LE(view["predicted_ms"].get<double>(), 0.5515 + 1e-12);
        } else {
            ++infeasible;
            EXPECT_GT(view["predicted_ms"].get<double>(), 0.5515);
        }
    }
    EXPECT_EQ(summary["infeasible_views"], infeasible);
    // The budget sits among the views' cheapest predictions (shipped harbor profile at 64x64):
    // both kinds of view are exercised.
    EXPECT_GT(infeasible, 0);
    EXPECT_LT(infeasible, 8);
    // One header and one line per view; the timing table names the rank.
    std::ifstream csv(folders / "one/sweep.csv");
    int lines = 0;
    for (std::string line; std::getline(csv, line);) ++lines;
    EXPECT_EQ(lines, 9);
    EXPECT_NE(slurp(folders / "one/sweep_timing.csv").find("view,rank,setup_seconds"), std::string::npos);
    // Running it again over a finished sweep starts afresh and gives the same table.
    const std::string first = slurp(folders / "one/sweep.json");
    ASSERT_EQ(runLodopt(kSweep + " --out " + (folders / "one")).exitCode, 0);
    EXPECT_EQ(slurp(folders / "one/sweep.json"), first);
}

TEST(SweepCli, ResumeRunsOnlyTheMissingViews) {
    SweepFolders folders;
    const std::string reference = referenceSweep(folders);
    // An interrupted sweep: two views and the merged table missing.
    fs::remove(folders / "one/views/view_000002.json");
    fs::remove(folders / "one/views/view_000005.json");
    fs::remove(folders / "one/sweep.json");
    EXPECT_EQ(runLodopt(kSweep + " --out " + (folders / "one")).exitCode, 2);  // refused without --resume
    const CommandResult resumed = runLodopt(kSweep + " --out " + (folders / "one") + " --resume --json");
    ASSERT_EQ(resumed.exitCode, 0);
    EXPECT_EQ(nlohmann::json::parse(resumed.output)["computed_by_rank0"], 2);
    EXPECT_EQ(slurp(folders / "one/sweep.json"), reference);
    // Another budget over the same folder is another sweep: refused, naming the option.
    const Exit other = runLodoptChild(splitWords("sweep --scene harbor --grid 2x2x2@5 --size 64x64 --budget-ms 0.552 "
                                                 "--max-evals 60 --resume --out " + (folders / "one")),
                                      "/dev/null", folders / "err.txt");
    EXPECT_EQ(other.code, 2);
    EXPECT_NE(other.err.find("--budget-ms"), std::string::npos) << other.err;
}

TEST(SweepCli, ShardsMergeIntoTheSameTable) {
    SweepFolders folders;
    const std::string reference = referenceSweep(folders);
    std::string merge = "sweep --merge";
    for (int shard = 0; shard < 3; ++shard) {
        const std::string out = folders / ("shard" + std::to_string(shard));
        ASSERT_EQ(runLodopt(kSweep + " --shard " + std::to_string(shard) + "/3 --out " + out).exitCode, 0);
        EXPECT_FALSE(fs::exists(out + "/sweep.json"));  // shards do not merge
        merge += " " + out;
    }
    ASSERT_EQ(runLodopt(merge + " --out " + (folders / "merged")).exitCode, 0);
    EXPECT_EQ(slurp(folders / "merged/sweep.json"), reference);
    EXPECT_EQ(slurp(folders / "merged/sweep.csv"), slurp(folders / "one/sweep.csv"));
    // A missing shard: the merge names the missing views and writes nothing.
    const Exit partial = runLodoptChild(splitWords("sweep --merge " + (folders / "shard0") + " " +
                                                   (folders / "shard1") + " --out " + (folders / "partial")),
                                        "/dev/null", folders / "err.txt");
    EXPECT_EQ(partial.code, 2);
    EXPECT_NE(partial.err.find("views have no file (2, 5)"), std::string::npos) << partial.err;
    EXPECT_FALSE(fs::exists(folders / "partial/sweep.json"));
}

TEST(SweepCli, BadInputIsRefusedWithExitCode2) {
    SweepFolders folders;
    const std::string base = "sweep --scene harbor --budget-ms 3.4 --out " + (folders / "bad") + " ";
    EXPECT_EQ(runLodopt(base + "--grid 2x2x2@5 --view-count 3").exitCode, 2);  // two camera sources
    EXPECT_EQ(runLodopt(base).exitCode, 2);                                     // none
    EXPECT_EQ(runLodopt(base + "--grid 2x2@5").exitCode, 2);
    EXPECT_EQ(runLodopt(base + "--grid 2x2x2@5 --shard 3/2").exitCode, 2);
    EXPECT_EQ(runLodopt(base + "--grid 2x2x2@5 --grid-box 1,2,0,3").exitCode, 2);
    std::ofstream(folders / "cameras.json") << R"([{"position": [0, 1, 2]}])";
    const Exit cameras = runLodoptChild(splitWords(base + "--cameras " + (folders / "cameras.json")), "/dev/null",
                                        folders / "err.txt");
    EXPECT_EQ(cameras.code, 2);
    EXPECT_NE(cameras.err.find("cameras[0]"), std::string::npos) << cameras.err;
    EXPECT_FALSE(fs::exists(folders / "bad/sweep.json"));
}

TEST(SweepCli, CamerasFromAFileAndSampledViews) {
    SweepFolders folders;
    std::ofstream(folders / "cameras.json")
        << R"({"cameras": [{"name": "a, quoted", "position": [0, 3, 30], "target": [0, 0, 0]},)"
        << R"( {"position": [20, 5, 20], "target": [0, 0, 0], "fov_y_degrees": 60}]})";
    ASSERT_EQ(runLodopt("sweep --scene harbor --cameras " + (folders / "cameras.json") +
                        " --size 64x64 --budget-ms 3.4 --max-evals 30 --out " + (folders / "file"))
                  .exitCode,
              0);
    const nlohmann::json sweep = readJson(folders / "file/sweep.json");
    ASSERT_EQ(sweep["views"].size(), 2u);
    EXPECT_EQ(sweep["views"][1]["camera"]["fov_y_degrees"], 60.0);
    EXPECT_NE(slurp(folders / "file/sweep.csv").find("\"a, quoted\""), std::string::npos);
    ASSERT_EQ(runLodopt("sweep --scene harbor --view-count 3 --size 64x64 --budget-ms 3.4 --max-evals 30 --out " +
                        (folders / "sampled"))
                  .exitCode,
              0);
    EXPECT_EQ(readJson(folders / "sampled/sweep.json")["views"].size(), 3u);
}

#if defined(LODOPT_MPIRUN)
// mpirun as the quick start installs it; as root Open MPI wants two variables, and more ranks
// than cores need --oversubscribe. Under the sanitizers the ranks run without LeakSanitizer:
// Open MPI unloads the components it dlopened at MPI_Finalize, so their allocations reach LSan
// from "<unknown module>", which no suppression can name. The same sweep code runs
// leak-checked without mpirun (SweepCli.*); ASan's other checks stay on in the ranks.
std::string mpirun(int ranks) {
    std::string prefix = "ASAN_OPTIONS=\"${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0\" ";
    if (::geteuid() == 0) prefix += "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ";
    return prefix + LODOPT_MPIRUN + std::string(" --oversubscribe -np ") + std::to_string(ranks) + " " +
           LODOPT_EXECUTABLE + " ";
}

TEST(SweepMpi, OneTwoAndFourRanksWriteTheSameBytes) {
    SweepFolders folders;
    const std::string reference = referenceSweep(folders);
    for (int ranks : {1, 2, 4}) {
        const std::string out = folders / ("ranks" + std::to_string(ranks));
        const CommandResult run = runShell(mpirun(ranks) + kSweep + " --json --out " + out + " 2>/dev/null");
        ASSERT_EQ(run.exitCode, 0) << ranks << " ranks";
        EXPECT_EQ(nlohmann::json::parse(run.output)["ranks"], ranks);
        EXPECT_EQ(slurp(out + "/sweep.json"), reference) << ranks << " ranks";
        EXPECT_EQ(slurp(out + "/sweep.csv"), slurp(folders / "one/sweep.csv")) << ranks << " ranks";
    }
    // --shard under mpirun is refused by every rank.
    EXPECT_EQ(runShell(mpirun(2) + kSweep + " --shard 0/2 --out " + (folders / "x") + " >/dev/null 2>&1").exitCode, 2);
}

TEST(SweepMpi, AKilledRankLosesOnlyItsViewAndResumeFinishes) {
    SweepFolders folders;
    const std::string reference = referenceSweep(folders);
    const std::string out = folders / "killed";
    // Rank 1 stops after searching its first view, before writing it, and is killed there.
    std::thread killer([&] {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
        const fs::path marker = fs::path(out) / "held_rank_1";
        while (!fs::exists(marker) && std::chrono::steady_clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        // Let rank 0 finish every other view first, so exactly one is lost.
        while (std::chrono::steady_clock::now() < deadline) {
            int files = 0;
            if (fs::is_directory(fs::path(out) / "views")) {
                for (const auto& entry : fs::directory_iterator(fs::path(out) / "views")) files += int(entry.is_regular_file());
            }
            if (files >= 7) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        if (fs::exists(marker)) ::kill(std::stoi(slurp(marker)), SIGKILL);
    });
    const CommandResult killed =
        runShell("LODOPT_TEST_SWEEP_HOLD_RANK=1 " + mpirun(2) + kSweep + " --out " + out + " >/dev/null 2>&1");
    killer.join();
    EXPECT_NE(killed.exitCode, 0);
    EXPECT_FALSE(fs::exists(out + "/sweep.json"));
    int files = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(out) / "views")) files += int(entry.is_regular_file());
    EXPECT_EQ(files, 7);
    fs::remove(fs::path(out) / "held_rank_1");
    // Finished with another number of ranks.
    const CommandResult resumed = runShell(mpirun(4) + kSweep + " --resume --out " + out + " >/dev/null 2>&1");
    ASSERT_EQ(resumed.exitCode, 0);
    EXPECT_EQ(slurp(out + "/sweep.json"), reference);
}
#else
TEST(SweepMpi, BuiltWithMpiInCi) {
    // The quick start builds with LODOPT_MPI=ON; a CI build without MPI lost the MPI tests.
    if (std::getenv("CI") != nullptr) FAIL() << "lodopt was built without MPI (libopenmpi-dev) in CI";
    GTEST_SKIP() << "built without MPI: the mpirun tests need libopenmpi-dev and openmpi-bin";
}
#endif

}  // namespace
}  // namespace lodopt::cli_test

namespace lodopt::cli_test {
namespace {

TEST(SweepCli, TuneAndReportTakeAFinishedSweep) {
    SweepFolders folders;
    referenceSweep(folders);
    const nlohmann::json sweep = readJson(folders / "one/sweep.json");
    int feasible = 0;
    for (const nlohmann::json& view : sweep["views"]) feasible += view["feasible"].get<bool>() ? 1 : 0;
    const CommandResult tune = runLodopt("tune --scene harbor --budget-ms 0.5515 --size 64x64 --search-evals 10 --from " +
                                         (folders / "one") + " --out " + (folders / "coeffs.json") + " --json --quiet");
    ASSERT_EQ(tune.exitCode, 0) << tune.output;
    const nlohmann::json report = nlohmann::json::parse(tune.output);
    EXPECT_EQ(report["from"], folders / "one");
    EXPECT_EQ(report["per_view"].size(), std::size_t(feasible));  // infeasible views left out
    // The optimizer's answers are the sweep's: tune scores the first feasible view's levels with
    // its fast evaluator, the sweep scored them with a full render, at the same size and weights.
    double sweepFitness = -1.0;
    for (const nlohmann::json& view : sweep["views"]) {
        if (view["feasible"].get<bool>()) {
            sweepFitness = view["fitness"].get<double>();
            break;
        }
    }
    EXPECT_NEAR(report["per_view"][0]["optimizer_fitness"].get<double>(), sweepFitness, 1e-6);
    // A sweep made under another budget is refused, naming the option.
    const Exit other = runLodoptChild(splitWords("tune --scene harbor --budget-ms 0.6 --size 64x64 --from " +
                                                 (folders / "one") + " --out " + (folders / "c2.json")),
                                      "/dev/null", folders / "err.txt");
    EXPECT_EQ(other.code, 2);
    EXPECT_NE(other.err.find("--budget-ms"), std::string::npos) << other.err;

    const CommandResult page = runLodopt("report " + (folders / "one") + " --out " + (folders / "page.html"),
                                         "LODOPT_GNUPLOT=none");
    ASSERT_EQ(page.exitCode, 0);
    const std::string html = slurp(folders / "page.html");
    EXPECT_NE(html.find("sweep: harbor"), std::string::npos);
    EXPECT_NE(html.find("min screen size"), std::string::npos);  // the table beside the level plot
    EXPECT_EQ(html.find("view_000000.json"), std::string::npos);  // view files are not listed as inputs
}

}  // namespace
}  // namespace lodopt::cli_test
