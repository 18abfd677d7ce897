// Robustness of the lodopt command (issue #9): determinism across runs and thread counts,
// interrupts (SIGINT, SIGTERM, SIGKILL) in the middle of `compare` and `--resume`, hostile
// scenes and images at the command line, and the metrics fuzz corpus replayed in-process.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <thread>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "../fuzz/fuzz_metrics_input.hpp"
#include "child_process.hpp"
#include "interrupt.hpp"
#include "scenes/gltf_io.hpp"
#include "scenes/mesh_builder.hpp"
#include "lodopt_test_paths.hpp"

namespace fs = std::filesystem;

namespace {

using lodopt::cli_test::Exit;
using lodopt::cli_test::readJson;
using lodopt::cli_test::slurp;

// The lodopt executable as a child process; stdout and stderr go to files in `dir`.
Exit runLodopt(const std::vector<std::string>& arguments, const fs::path& dir,
               const lodopt::cli_test::Environment& environment = {},
               const std::function<void(pid_t)>& whileRunning = {}) {
    return lodopt::cli_test::runLodoptChild(arguments, dir / "stdout.txt", dir / "stderr.txt", environment,
                                            whileRunning);
}

std::vector<std::string> split(const std::string& text) { return lodopt::cli_test::splitWords(text); }

// Drops the named CSV columns (by header) from every row.
std::string withoutColumns(const std::string& csv, const std::vector<std::string>& names) {
    std::istringstream lines(csv);
    std::string line, result;
    std::vector<bool> keep;
    while (std::getline(lines, line)) {
        std::vector<std::string> cells;
        std::stringstream cellStream(line);
        for (std::string cell; std::getline(cellStream, cell, ',');) cells.push_back(cell);
        if (!line.empty() && line.back() == ',') cells.push_back("");
        if (keep.empty()) {
            for (const std::string& cell : cells) keep.push_back(std::find(names.begin(), names.end(), cell) == names.end());
        }
        for (std::size_t c = 0; c < cells.size(); ++c) {
            if (c >= keep.size() || keep[c]) result += cells[c] + ",";
        }
        result += "\n";
    }
    return result;
}


class Robustness : public lodopt::cli_test::FolderWithFixedProfile {
protected:
    Robustness() : FolderWithFixedProfile("lodopt-robust-") {}
};

// ---- Determinism ------------------------------------------------------------------------

// The same optimize with the same seed: identical result.json (timing fields aside),
// curve.csv (elapsed column aside) and images, with 1 or 2 threads and when repeated.
TEST_F(Robustness, OptimizeIsIdenticalAcrossThreadCountsAndRuns) {
    struct Output {
        nlohmann::json result;
        std::string curve, optimized, reference;
    };
    auto run = [&](const std::string& name, int threads) {
        const fs::path out = mDir / name;
        const Exit exit = runLodopt(split("optimize --scene harbor --size 128x128 --seed 3 --budget-ms 2.5 --quiet "
                                          "--max-iterations 12 --threads " +
                                          std::to_string(threads) + mProfile + " --out " + out.string()),
                                    mDir);
        EXPECT_EQ(exit.code, 0) << exit.err;
        Output output;
        output.result = readJson(out / "result.json");
        for (const char* timing : {"setup_seconds", "evals_per_second", "search_seconds", "wall_seconds"}) {
            EXPECT_TRUE(output.result.contains(timing)) << timing;
            output.result.erase(timing);
        }
        output.curve = withoutColumns(slurp(out / "curve.csv"), {"elapsed_seconds"});
        output.optimized = slurp(out / "optimized.png");
        output.reference = slurp(out / "reference.png");
        return output;
    };
    const Output one = run("t1", 1), two = run("t2", 2), again = run("t1again", 1);
    EXPECT_GT(one.result["evaluations"].get<int>(), 1);
    EXPECT_EQ(one.result, two.result);
    EXPECT_EQ(one.result, again.result);
    EXPECT_EQ(one.curve, two.curve);
    EXPECT_EQ(one.curve, again.curve);
    EXPECT_GT(std::count(one.curve.begin(), one.curve.end(), '\n'), 2);
    EXPECT_TRUE(one.optimized == two.optimized && one.optimized == again.optimized) << "optimized.png differs";
    EXPECT_TRUE(one.reference == two.reference) << "reference.png differs";
}

// ---- Interrupts and --resume -------------------------------------------------------------

const char* kCompare =
    "compare --scene harbor --view overview --size 64x64 --budget-ms 2 --algos random,greedy,gapso --seeds 3 "
    "--evals 20 --quiet --out ";
constexpr int kCompareRuns = 9;

struct CompareOutput {
    nlohmann::json summary;
    std::string table, curves;
};

CompareOutput compareOutput(const fs::path& out) {
    CompareOutput output;
    output.summary = readJson(out / "compare.json");
    for (nlohmann::json& row : output.summary["algorithms"]) {
        EXPECT_TRUE(row.contains("median_wall_seconds"));
        row.erase("median_wall_seconds");
    }
    output.table = withoutColumns(slurp(out / "compare.csv"), {"median_wall_seconds"});
    output.curves = slurp(out / "curves.csv");
    return output;
}

void expectSameCompare(const CompareOutput& a, const CompareOutput& b) {
    EXPECT_EQ(a.summary, b.summary);
    EXPECT_EQ(a.table, b.table);
    EXPECT_EQ(a.curves, b.curves);
}

// Sends `signal` to `pid` once `checkpoint` lists `runs` runs (or the process has ended).
void killAfterRuns(pid_t pid, const fs::path& checkpoint, std::size_t runs, int signal) {
    lodopt::cli_test::signalWhen(
        pid,
        [&] {
            if (!fs::exists(checkpoint)) return false;
            const nlohmann::json saved = nlohmann::json::parse(slurp(checkpoint), nullptr, false);
            return !saved.is_discarded() && saved["runs"].size() >= runs;
        },
        signal);
}

// A compare interrupted after unit k by each signal, then resumed (with another thread count):
// the outputs equal an uninterrupted run's, wall times aside.
TEST_F(Robustness, CompareInterruptedBySignalsResumesToTheSameResult) {
    const fs::path whole = mDir / "whole";
    const Exit full = runLodopt(split(kCompare + whole.string() + mProfile + " --threads 2"), mDir);
    ASSERT_EQ(full.code, 0) << full.err;
    EXPECT_FALSE(fs::exists(whole / "compare.checkpoint.json")) << "removed once the outputs are written";
    const CompareOutput expected = compareOutput(whole);

    struct Case {
        int signal;
        std::size_t after;
    };
    for (const Case& c : {Case{SIGINT, 2}, Case{SIGTERM, 5}, Case{SIGKILL, 1}}) {
        SCOPED_TRACE(strsignal(c.signal));
        const fs::path out = mDir / ("cut" + std::to_string(c.signal));
        const fs::path checkpoint = out / "compare.checkpoint.json";
        const Exit cut = runLodopt(split(kCompare + out.string() + mProfile + " --threads 2"), mDir,
                                   {{"LODOPT_TEST_WAIT_AFTER_UNITS", std::to_string(c.after)}},
                                   [&](pid_t pid) { killAfterRuns(pid, checkpoint, c.after, c.signal); });
        if (c.signal == SIGKILL) {
            EXPECT_EQ(cut.signal, SIGKILL);
        } else {
            EXPECT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
            const std::string what = std::string("interrupted by ") + (c.signal == SIGINT ? "SIGINT" : "SIGTERM") +
                                     " after " + std::to_string(c.after) + " of " + std::to_string(kCompareRuns) + " runs";
            EXPECT_NE(cut.err.find(what), std::string::npos) << cut.err;
            EXPECT_NE(cut.err.find("resume with: "), std::string::npos) << cut.err;
            EXPECT_NE(cut.err.find(" --resume"), std::string::npos) << cut.err;
        }
        // Every file left behind is complete: the checkpoint parses and holds exactly the
        // finished runs; no summary yet; no temporary file.
        const nlohmann::json saved = readJson(checkpoint);
        EXPECT_EQ(saved["runs"].size(), c.after);
        EXPECT_FALSE(fs::exists(out / "compare.json"));
        for (const auto& entry : fs::directory_iterator(out)) {
            EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
        }
        // Without --resume the saved runs are not silently thrown away.
        const Exit refused = runLodopt(split(kCompare + out.string() + mProfile), mDir);
        EXPECT_EQ(refused.code, 2);
        EXPECT_NE(refused.err.find("--resume"), std::string::npos) << refused.err;

        const Exit resumed = runLodopt(split(kCompare + out.string() + mProfile + " --threads 1 --resume"), mDir);
        ASSERT_EQ(resumed.code, 0) << resumed.err;
        EXPECT_FALSE(fs::exists(checkpoint));
        expectSameCompare(expected, compareOutput(out));
    }
}

TEST_F(Robustness, CompareResumeRefusesADifferentRunOrABrokenCheckpoint) {
    const fs::path out = mDir / "out";
    const fs::path checkpoint = out / "compare.checkpoint.json";
    const Exit cut = runLodopt(split(kCompare + out.string() + mProfile), mDir, {{"LODOPT_TEST_WAIT_AFTER_UNITS", "1"}},
                               [&](pid_t pid) { killAfterRuns(pid, checkpoint, 1, SIGINT); });
    ASSERT_EQ(cut.code, lodopt::cli::kExitInterrupted) << cut.err;
    const std::string saved = slurp(checkpoint);

    std::string other = kCompare;
    other.replace(other.find("--budget-ms 2"), 13, "--budget-ms 3");
    const Exit changed = runLodopt(split(other + out.string() + mProfile + " --resume"), mDir);
    EXPECT_EQ(changed.code, 2);
    EXPECT_NE(changed.err.find("--budget-ms"), std::string::npos) << changed.err;
    // The fill probability changes GA-PSO's runs, so it is part of the identity too.
    const Exit filled = runLodopt(split(kCompare + out.string() + mProfile + " --fill 0.5 --resume"), mDir);
    EXPECT_EQ(filled.code, 2);
    EXPECT_NE(filled.err.find("--fill"), std::string::npos) << filled.err;

    std::ofstream(checkpoint) << saved.substr(0, saved.size() / 2);
    const Exit broken = runLodopt(split(kCompare + out.string() + mProfile + " --resume"), mDir);
    EXPECT_EQ(broken.code, 2);
    EXPECT_NE(broken.err.find("not a readable compare checkpoint"), std::string::npos) << broken.err;

    // More seeds than before: the saved run is reused, the rest is computed.
    std::ofstream(checkpoint) << saved;
    std::string more = kCompare;
    more.replace(more.find("--seeds 3"), 9, "--seeds 4");
    const Exit extended = runLodopt(split(more + out.string() + mProfile + " --resume"), mDir);
    EXPECT_EQ(extended.code, 0) << extended.err;
    EXPECT_EQ(readJson(out / "compare.json")["seeds"], 4);
}

// The interrupt API in-process: the flag, the message, the resume line, and that a second
// signal stops the process at once (checked in a forked child).
TEST(Interrupt, FlagMessageResumeLineAndSecondSignal) {
    using namespace lodopt::cli;
    {
        InterruptGuard guard;
        EXPECT_FALSE(interruptRequested());
        EXPECT_NO_THROW(pollInterrupt("tune", 0, 4, "configuration", "x.json"));
        raise(SIGTERM);
        EXPECT_EQ(interruptSignal(), SIGTERM);
        try {
            pollInterrupt("tune", 3, 8, "configuration", "out/tune/checkpoint.json");
            ADD_FAILURE() << "no Interrupted";
        } catch (const Interrupted& interrupted) {
            const std::string message = interrupted.what();
            EXPECT_NE(message.find("tune: interrupted by SIGTERM after 3 of 8 configurations; the finished ones are "
                                   "saved in out/tune/checkpoint.json"),
                      std::string::npos)
                << message;
            EXPECT_NE(message.find("\nresume with: "), std::string::npos);
            EXPECT_EQ(message.substr(message.size() - 9), " --resume");
        }
    }
    EXPECT_EQ(shellQuote("plain/path-1.glb"), "plain/path-1.glb");
    EXPECT_EQ(shellQuote("it's here"), "'it'\\''s here'");
    EXPECT_EQ(shellQuote(""), "''");

    const pid_t child = fork();
    if (child == 0) {
        InterruptGuard guard;
        raise(SIGINT);
        if (!interruptRequested()) _exit(3);
        raise(SIGINT);  // the second one takes the default action
        _exit(4);
    }
    int status = 0;
    waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << "status " << status;
}

// ---- Hostile scenes and images at the command line -----------------------------------------

lodopt::scenes::Mesh boxMesh(float half, int material) {
    lodopt::scenes::MeshBuilder builder(material);
    builder.addBox(glm::vec3(0.0f), glm::vec3(half));
    return builder.finish();
}

// One box object with `levels` levels (halving in size), at `position`, and a camera at z = 10
// looking at the origin.
lodopt::scenes::Scene boxScene(glm::vec3 position, int levels) {
    lodopt::scenes::Scene scene;
    scene.name = "edge";
    scene.materials.push_back(lodopt::scenes::diffuseMaterial("red", {0.8f, 0.2f, 0.2f}));
    lodopt::scenes::Object object;
    object.name = "box";
    object.transform = glm::translate(glm::mat4(1.0f), position);
    for (int l = 0; l < levels; ++l) {
        lodopt::scenes::Level level;
        level.meshes.push_back(boxMesh(1.0f / float(1 << l), 0));
        object.levels.push_back(level);
    }
    scene.objects.push_back(object);
    lodopt::scenes::Camera camera;
    camera.name = "front";
    camera.position = {0, 0, 10};
    camera.target = {0, 0, 0};
    scene.views.push_back(camera);
    lodopt::scenes::updateStatistics(scene);
    return scene;
}

TEST_F(Robustness, OptimizeOnEdgeScenesBehavesAsDocumented) {
    const std::string common = " --view 0 --size 48x48 --quiet --max-iterations 5" + mProfile + "--out ";
    // Off screen: nothing to search, the fixed combination, fitness 1.
    const fs::path away = mDir / "away.glb";
    lodopt::scenes::exportGltf(boxScene({0, 0, 40}, 2), away.string());
    const Exit offScreen = runLodopt(split("optimize --scene " + away.string() + " --budget-ms 100" + common +
                                           (mDir / "o1").string()),
                                     mDir);
    ASSERT_EQ(offScreen.code, 0) << offScreen.err;
    nlohmann::json result = readJson(mDir / "o1" / "result.json");
    EXPECT_EQ(result["skipped_objects"]["searched_objects"], 0);
    EXPECT_EQ(result["skipped_objects"]["outside_frustum"], 1);
    EXPECT_EQ(result["fitness"], 1.0);

    // Budget far above the finest combination: every object at level 0, fitness 1.
    const fs::path visible = mDir / "visible.glb";
    lodopt::scenes::exportGltf(boxScene({0, 0, 0}, 3), visible.string());
    for (const std::string algorithm : {"gapso", "greedy", "mckp", "exhaustive"}) {
        const Exit rich = runLodopt(split("optimize --scene " + visible.string() + " --budget-ms 1e6 --algo " +
                                          algorithm + common + (mDir / algorithm).string()),
                                    mDir);
        ASSERT_EQ(rich.code, 0) << rich.err;
        result = readJson(mDir / algorithm / "result.json");
        EXPECT_EQ(result["combination"], nlohmann::json::array({0})) << algorithm;
        EXPECT_EQ(result["fitness"], 1.0) << algorithm;
    }

    // Budget below the cheapest combination: exit 2 and the minimum stated.
    const Exit poor = runLodopt(split("optimize --scene " + visible.string() + " --budget-ms 0.0001" + common +
                                      (mDir / "poor").string()),
                                mDir);
    EXPECT_EQ(poor.code, 2);
    EXPECT_NE(poor.err.find("below the cheapest combination"), std::string::npos) << poor.err;
    EXPECT_NE(poor.err.find("predicted at"), std::string::npos) << poor.err;
}

TEST_F(Robustness, ScenesWithoutObjectsAndHostileFilesAreBadInput) {
    // A glTF with no node, and one whose only object has no triangle (left out with a warning).
    const fs::path empty = mDir / "empty.gltf";
    std::ofstream(empty) << R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0})";
    lodopt::scenes::Scene degenerate = boxScene({0, 0, 0}, 1);
    degenerate.objects[0].levels[0].meshes[0].indices.clear();
    const fs::path noTriangles = mDir / "no_triangles.glb";
    lodopt::scenes::exportGltf(degenerate, noTriangles.string());
    for (const fs::path& scene : {empty, noTriangles}) {
        const Exit exit = runLodopt(split("optimize --budget-ms 5 --view 0 --size 32x32 --quiet --scene " +
                                          scene.string() + mProfile + " --out " + (mDir / "x").string()),
                                    mDir);
        EXPECT_EQ(exit.code, 2) << scene;
        EXPECT_NE(exit.err.find("has no objects"), std::string::npos) << exit.err;
    }
    // Hostile files: an error naming the file, exit 2, never a crash.
    const fs::path nested = mDir / "nested.gltf";
    std::ofstream(nested) << R"({"asset": {"version": "2.0"}, "extras": )" << std::string(100000, '[')
                          << std::string(100000, ']') << "}";
    const fs::path truncated = mDir / "truncated.glb";
    std::ofstream(truncated, std::ios::binary) << std::string("glTF\x02\0\0\0\xff\xff\0\0", 12);
    for (const fs::path& scene : {nested, truncated}) {
        const Exit exit = runLodopt(split("scene info " + scene.string()), mDir);
        EXPECT_EQ(exit.code, 2) << scene;
        EXPECT_NE(exit.err.find(scene.filename().string()), std::string::npos) << exit.err;
    }
    // Images: not an image, a PNG header (valid CRC) promising 60000 x 60000 pixels.
    const fs::path text = mDir / "text.png";
    std::ofstream(text) << "not an image";
    const fs::path header = mDir / "header.png";
    const unsigned char png[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                 0, 0, 0xEA, 0x60, 0, 0, 0xEA, 0x60, 8, 6, 0, 0, 0, 0x80, 0xD2, 0x75, 0x42};
    std::ofstream(header, std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
    for (const fs::path& image : {text, header}) {
        const Exit exit = runLodopt({"metrics", image.string(), image.string()}, mDir);
        EXPECT_EQ(exit.code, 2) << image << exit.err;
        EXPECT_NE(exit.err.find(image.filename().string()), std::string::npos) << exit.err;
    }
}

// "Nothing lost": every file lodopt writes goes through scenes::writeFileAtomically (a temporary
// name, then rename). A stream or image writer opened anywhere else in the modules' sources
// would bypass it; inside the helpers they write the path named `temporary`.
TEST(AtomicOutput, EveryWriterInTheSourcesWritesATemporaryFile) {
    const fs::path root = fs::path(LODOPT_SOURCE_DIR);
    int writers = 0;
    for (const char* module : {"cli", "scenes", "renderer", "metrics", "timemodel", "optimizer", "evaluation",
                               "scheduler"}) {
        if (!fs::exists(root / module / "src")) continue;
        for (const auto& entry : fs::recursive_directory_iterator(root / module / "src")) {
            if (entry.path().extension() != ".cpp" && entry.path().extension() != ".hpp") continue;
            std::ifstream in(entry.path());
            int number = 0;
            for (std::string line; std::getline(in, line);) {
                ++number;
                const bool opens = line.find("std::ofstream") != std::string::npos ||
                                   line.find("\"wb\"") != std::string::npos ||
                                   line.find("OutputFile ") != std::string::npos ||
                                   line.find("imwrite(") != std::string::npos;
                const std::size_t first = line.find_first_not_of(' ');
                if (!opens || line.compare(first, 2, "//") == 0) continue;
                ++writers;
                EXPECT_NE(line.find("temporary"), std::string::npos)
                    << entry.path().string() << ":" << number << " writes a file without writeFileAtomically: " << line;
            }
        }
    }
    EXPECT_GE(writers, 2) << "atomic_file.cpp and image_io.cpp write through their temporary path";
}

// Every seed and crash regression of the fuzz_metrics_input target, in-process, in every build.
TEST(MetricsFuzzCorpus, ReplaysWithoutCrashing) {
    const fs::path root = fs::path(LODOPT_SOURCE_DIR) / "tests" / "fuzz";
    int inputs = 0;
    for (const char* folder : {"corpus/metrics_input", "regressions/metrics_input"}) {
        if (!fs::exists(root / folder)) continue;
        for (const auto& entry : fs::directory_iterator(root / folder)) {
            const std::string bytes = slurp(entry.path());
            SCOPED_TRACE(entry.path().string());
            EXPECT_NO_THROW(lodopt::fuzz::runMetricsInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
            ++inputs;
        }
    }
    EXPECT_GE(inputs, 10);
}

}  // namespace
