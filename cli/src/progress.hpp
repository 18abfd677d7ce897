// The one progress reporter of long commands: "\r<task> [k/N] 42% ETA 1m05s <label>" on a
// terminal (stderr), nothing in CI (CI set), when stderr is not a terminal, or when quiet.
// Batch jobs (sweep) ask for Lines: on a terminal the same line, otherwise (a cluster's log
// file, CI) one full line "<task> [k/N] 42% 1.3/s ETA 1m05s <label>" at most every 10 s and
// at the end; the rate is units reported per second since the reporter started (resumed units
// found finished count too, so it runs high at the start of a resumed sweep).
#pragma once

#include <chrono>
#include <string>

namespace lodopt::cli {

class Progress {
public:
    enum class Style { TerminalOnly, Lines };
    Progress(std::string task, std::size_t total, bool quiet, Style style = Style::TerminalOnly);
    // One unit of work finished; `label` says which.
    void step(const std::string& label = {});
    // `done` units are finished in all (counting other processes' and earlier runs').
    void update(std::size_t done, const std::string& label = {});
    // Clears the line.
    void finish();
    bool enabled() const { return mEnabled; }

private:
    std::string mTask;
    std::size_t mTotal;
    std::size_t mDone = 0;
    bool mEnabled;
    bool mLines = false;  // full lines: stderr is not a terminal
    double mLastLine = -1e30;
    std::chrono::steady_clock::time_point mStart;
};

// "1m05s", "12s", "2h03m".
std::string formatDuration(double seconds);

}  // namespace lodopt::cli
