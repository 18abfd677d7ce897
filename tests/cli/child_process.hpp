// The lodopt executable as a child process, for the CLI tests that signal it mid-run
// (compare, tune, bench, schedule interrupts) or need its exit status, stdout and stderr.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>
#include "lodopt_test_paths.hpp"

namespace lodopt::cli_test {

struct Exit {
    int code = -1;    // exit status, -1 when killed by a signal
    int signal = 0;   // the signal that killed it, 0 when it exited
    std::string out;  // stdout (empty when sent to /dev/null)
    std::string err;  // stderr
};

using Environment = std::vector<std::pair<std::string, std::string>>;

inline std::string slurp(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline nlohmann::json readJson(const std::filesystem::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

inline std::vector<std::string> splitWords(const std::string& text) {
    std::istringstream stream(text);
    std::vector<std::string> words;
    for (std::string word; stream >> word;) words.push_back(word);
    return words;
}

// Runs LODOPT_EXECUTABLE with `arguments` and extra environment variables (CI=1: no progress
// line), stdout to `outFile` and stderr to `errFile`. `whileRunning(pid)` runs in the parent
// before it waits (to send signals).
inline Exit runLodoptChild(const std::vector<std::string>& arguments, const std::filesystem::path& outFile,
                           const std::filesystem::path& errFile, const Environment& environment = {},
                           const std::function<void(pid_t)>& whileRunning = {}) {
    std::vector<std::string> words = {LODOPT_EXECUTABLE};
    words.insert(words.end(), arguments.begin(), arguments.end());
    std::vector<char*> argv;
    for (std::string& word : words) argv.push_back(word.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        for (const auto& [name, value] : environment) setenv(name.c_str(), value.c_str(), 1);
        setenv("CI", "1", 1);
        const int o = open(outFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int e = open(errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(o, 1);
        dup2(e, 2);
        execv(argv[0], argv.data());
        _exit(127);
    }
    if (whileRunning) whileRunning(pid);
    int status = 0;
    waitpid(pid, &status, 0);
    Exit result;
    if (WIFEXITED(status)) result.code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
    if (outFile != "/dev/null") result.out = slurp(outFile);
    result.err = slurp(errFile);
    return result;
}

// Waits (up to 60 s) until `finished()` says the units to wait for are saved, then sends
// `signal` to `pid`; returns early when the process has ended (the caller reaps it).
inline void signalWhen(pid_t pid, const std::function<bool()>& finished, int signal) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        siginfo_t info{};
        if (waitid(P_PID, pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid) return;
        if (finished()) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    kill(pid, signal);
}

// A device profile with fixed coefficients (harbor, linear model): predictions, and so the
// searches, do not depend on this machine's speed. Harbor's overview then predicts 1.14 ms
// (coarsest) to 3.94 ms (finest) at 128x128 and 0.89 to 2.94 ms at 64x64.
inline constexpr const char* kFixedProfile =
    R"json({"format":"lodopt-device-profile","version":1,"created":"2025-01-01T00:00:00Z",)json"
    R"json("machine":{"cpu_model":"test","cores":2},)json"
    R"json("renderer":{"gl_renderer":"Mesa/X.org / llvmpipe (LLVM 15.0.6, 256 bits)",)json"
    R"json("gl_version":"4.5 (Core Profile) Mesa 22.3.6"},"render_size":{"width":128,"height":128},)json"
    R"json("scene":{"name":"harbor","seed":1},"calibration":{"seed":3,"viewpoints":8,)json"
    R"json("held_out_viewpoints":4,"fit_samples":12,"held_out_samples":12,"timing":{"predicts":"median",)json"
    R"json("frame_clock":"wall","learned_from":"median","learned_scale":1.0,"learn_request":"median",)json"
    R"json("rounds":1,"repeats_per_round":1,"warmup":1,"median_spread":0.0,"p90_spread":0.0,)json"
    R"json("seconds":0.0}},"default_model":"linear","models":[{"name":"linear","fitted":true,)json"
    R"json("coefficients":{"intercept_ms":0.5,"vertices":0.0,"triangles":2e-05,"texture_bytes":0.0,)json"
    R"json("draw_calls":0.01,"pixels":1e-05,"drawn_objects":0.0,"matrices":0.0,"bounding_boxes":0.0,)json"
    R"json("visible_triangles":4e-05,"raster_pixels":0.0,"edge_pixels":2e-05,"shaded_pixels":0.0},)json"
    R"json("fit":{"samples":0,"rms_residual_ms":0.0,"condition_number":0.0,"pairs":0,"skipped_pairs":0,)json"
    R"json("iterations":0,"notes":[],"errors":{"count":0,"mean":0.0,"median":0.0,"p90":0.0,"max":0.0}},)json"
    R"json("held_out_errors":{"count":0,"mean":0.0,"median":0.0,"p90":0.0,"max":0.0}}],)json"
    R"json("feature_names":["vertices","triangles","texture_bytes","draw_calls","pixels","drawn_objects",)json"
    R"json("matrices","bounding_boxes","visible_triangles","raster_pixels","edge_pixels","shaded_pixels"],)json"
    R"json("samples":[]})json";


// A fresh folder per test (`<tmp>/<prefix><pid>-<test name>`) holding kFixedProfile, removed
// afterwards; mProfile is the " --profile <file> " to append to a command line.
class FolderWithFixedProfile : public testing::Test {
protected:
    explicit FolderWithFixedProfile(std::string prefix) : mPrefix(std::move(prefix)) {}
    void SetUp() override {
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        mDir = std::filesystem::temp_directory_path() / (mPrefix + std::to_string(::getpid()) + "-" + info->name());
        std::filesystem::remove_all(mDir);
        std::filesystem::create_directories(mDir);
        std::ofstream(mDir / "profile.json") << kFixedProfile;
        mProfile = " --profile " + (mDir / "profile.json").string() + " ";
    }
    void TearDown() override { std::filesystem::remove_all(mDir); }
    std::string mPrefix;
    std::filesystem::path mDir;
    std::string mProfile;
};

}  // namespace lodopt::cli_test
