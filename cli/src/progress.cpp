#include "progress.hpp"

#include <cstdio>
#include <cstdlib>

#include <unistd.h>

namespace lodopt::cli {

std::string formatDuration(double seconds) {
    if (!(seconds >= 0.0)) return "?";
    long total = long(seconds + 0.5);
    char text[32];
    if (total >= 3600) std::snprintf(text, sizeof(text), "%ldh%02ldm", total / 3600, (total / 60) % 60);
    else if (total >= 60) std::snprintf(text, sizeof(text), "%ldm%02lds", total / 60, total % 60);
    else std::snprintf(text, sizeof(text), "%lds", total);
    return text;
}

Progress::Progress(std::string task, std::size_t total, bool quiet)
    : mTask(std::move(task)),
      mTotal(total),
      mEnabled(!quiet && std::getenv("CI") == nullptr && ::isatty(STDERR_FILENO)),
      mStart(std::chrono::steady_clock::now()) {}

void Progress::step(const std::string& label) {
    ++mDone;
    if (!mEnabled) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
    const double remaining = mDone > 0 ? elapsed / double(mDone) * double(mTotal - std::min(mDone, mTotal)) : 0.0;
    std::fprintf(stderr, "\r\033[K%s [%zu/%zu] %3.0f%% ETA %s %s", mTask.c_str(), mDone, mTotal,
                 mTotal ? 100.0 * double(mDone) / double(mTotal) : 100.0, formatDuration(remaining).c_str(),
                 label.c_str());
    std::fflush(stderr);
}

void Progress::finish() {
    if (mEnabled) std::fprintf(stderr, "\r\033[K");
}

}  // namespace lodopt::cli
