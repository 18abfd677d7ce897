#include "interrupt.hpp"

#include <cassert>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <thread>
#include <vector>

#include <signal.h>

namespace lodopt::cli {
namespace {

volatile std::sig_atomic_t gSignal = 0;
bool gInstalled = false;
struct sigaction gPreviousInt {};
struct sigaction gPreviousTerm {};

// Only async-signal-safe calls here: a flag, and on the second signal signal() + raise().
extern "C" void onInterruptSignal(int signal) {
    if (gSignal != 0) {
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return;
    }
    gSignal = signal;
}

const char* signalName(int signal) {
    switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "a signal";
    }
}

// LODOPT_TEST_WAIT_AFTER_UNITS (see the header): -1 when unset or not a number.
long testWaitUnit() {
    const char* text = std::getenv("LODOPT_TEST_WAIT_AFTER_UNITS");
    if (!text || !*text) return -1;
    char* end = nullptr;
    const long value = std::strtol(text, &end, 10);
    return (*end == '\0' && value >= 0) ? value : -1;
}

}  // namespace

InterruptGuard::InterruptGuard() {
    assert(!gInstalled && "InterruptGuards do not nest");
    gSignal = 0;
    struct sigaction action {};
    action.sa_handler = &onInterruptSignal;
    sigemptyset(&action.sa_mask);
    // SA_RESTART: a signal must not turn a write in progress into an I/O error.
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, &gPreviousInt);
    sigaction(SIGTERM, &action, &gPreviousTerm);
    gInstalled = true;
}

InterruptGuard::~InterruptGuard() {
    sigaction(SIGINT, &gPreviousInt, nullptr);
    sigaction(SIGTERM, &gPreviousTerm, nullptr);
    gInstalled = false;
}

int interruptSignal() {
    return static_cast<int>(gSignal);
}

bool interruptRequested() {
    return gSignal != 0;
}

void pollInterrupt(const std::string& command, std::size_t unitsDone, std::size_t unitsTotal,
                   const std::string& unitName, const std::string& savedPath) {
    if (gSignal == 0 && testWaitUnit() == static_cast<long>(unitsDone)) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
        while (gSignal == 0 && std::chrono::steady_clock::now() < deadline) {
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
    }
    if (gSignal == 0) return;
    std::string message = command + ": interrupted by " + signalName(gSignal) + " after " + std::to_string(unitsDone) +
                          " of " + std::to_string(unitsTotal) + " " + unitName + "s";
    message += unitsDone > 0 ? "; the finished ones are saved in " + savedPath : "; nothing to save yet";
    message += "\nresume with: " + resumeCommandLine();
    throw Interrupted(message);
}

std::string shellQuote(const std::string& word) {
    if (word.empty()) return "''";
    bool plain = true;
    for (char c : word) {
        const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                        std::string("_./=:,+@%-").find(c) != std::string::npos;
        plain = plain && ok;
    }
    if (plain) return word;
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

std::string resumeCommandLine() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    const std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> words;
    std::string word;
    for (char c : raw) {
        if (c == '\0') {
            words.push_back(word);
            word.clear();
        } else {
            word += c;
        }
    }
    if (!word.empty()) words.push_back(word);
    if (words.empty()) words.push_back("lodopt");
    bool hasResume = false;
    std::string line;
    for (const std::string& w : words) {
        hasResume = hasResume || w == "--resume";
        if (!line.empty()) line += ' ';
        line += shellQuote(w);
    }
    if (!hasResume) line += " --resume";
    return line;
}

}  // namespace lodopt::cli
