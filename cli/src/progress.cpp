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

Progress::Progress(std::string task, std::size_t total, bool quiet, Style style)
    : mTask(std::move(task)), mTotal(total), mStart(std::chrono::steady_clock::now()) {
    const bool terminal = ::isatty(STDERR_FILENO);
    mEnabled = !quiet && (style == Style::Lines || (std::getenv("CI") == nullptr && terminal));
    mLines = !terminal;
}

void Progress::step(const std::string& label) { update(mDone + 1, label); }

void Progress::update(std::size_t done, const std::string& label) {
    mDone = done;
    if (!mEnabled) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - mStart).count();
    const bool last = mDone >= mTotal;
    if (mLines && !last && elapsed - mLastLine < 10.0) return;
    mLastLine = elapsed;
    const double rate = elapsed > 0.0 ? double(mDone) / elapsed : 0.0;
    const double remaining = rate > 0.0 ? double(mTotal - std::min(mDone, mTotal)) / rate : -1.0;
    const double percent = mTotal ? 100.0 * double(mDone) / double(mTotal) : 100.0;
    if (mLines) {
        std::fprintf(stderr, "%s [%zu/%zu] %3.0f%% %.2g/s ETA %s %s\n", mTask.c_str(), mDone, mTotal, percent, rate,
                     formatDuration(remaining).c_str(), label.c_str());
    } else {
        std::fprintf(stderr, "\r\033[K%s [%zu/%zu] %3.0f%% ETA %s %s", mTask.c_str(), mDone, mTotal, percent,
                     formatDuration(remaining).c_str(), label.c_str());
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (mEnabled && !mLines) std::fprintf(stderr, "\r\033[K");
}

}  // namespace lodopt::cli
