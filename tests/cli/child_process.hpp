// The lodopt executable as a child process, for the CLI tests that signal it mid-run
// (compare, tune, bench, schedule interrupts) or need its exit status, stdout and stderr.
#pragma once

#include <fcntl.h>
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

}  // namespace lodopt::cli_test
