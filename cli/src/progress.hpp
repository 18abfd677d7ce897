// The one progress reporter of long commands: "\r<task> [k/N] 42% ETA 1m05s <label>" on a
// terminal (stderr), nothing in CI (CI set), when stderr is not a terminal, or when quiet.
#pragma once

#include <chrono>
#include <string>

namespace lodopt::cli {

class Progress {
public:
    Progress(std::string task, std::size_t total, bool quiet);
    // One unit of work finished; `label` says which.
    void step(const std::string& label = {});
    // Clears the line.
    void finish();
    bool enabled() const { return mEnabled; }

private:
    std::string mTask;
    std::size_t mTotal;
    std::size_t mDone = 0;
    bool mEnabled;
    std::chrono::steady_clock::time_point mStart;
};

// "1m05s", "12s", "2h03m".
std::string formatDuration(double seconds);

}  // namespace lodopt::cli
