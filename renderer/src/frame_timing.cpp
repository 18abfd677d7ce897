// Timing frames: naming the clocks, summarizing a batch (renderer.hpp FrameClock, FrameTimes) and
// the per-context timer (frame_timer.hpp).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <ctime>

#include "frame_timer.hpp"
#include "renderer/renderer.hpp"

namespace lodopt::renderer {

const char* frameClockName(FrameClock clock) {
    switch (clock) {
        case FrameClock::Wall:
            return "wall";
        case FrameClock::GpuTimer:
            return "gpu";
        case FrameClock::Auto:
            break;
    }
    return "auto";
}

FrameClock parseFrameClock(const std::string& name) {
    if (name == "auto") return FrameClock::Auto;
    if (name == "wall") return FrameClock::Wall;
    if (name == "gpu") return FrameClock::GpuTimer;
    throw RenderError("unknown frame clock '" + name + "' (auto, wall or gpu)");
}

bool isSoftwareRasterizer(const std::string& glRenderer) {
    std::string lower = glRenderer;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const char* name : {"llvmpipe", "softpipe", "swiftshader", "software rasterizer"}) {
        if (lower.find(name) != std::string::npos) return true;
    }
    return false;
}

double FrameTimes::median() const {
    std::vector<double> sorted = frameMs();
    if (sorted.empty()) return 0.0;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

double FrameTimes::least() const {
    const std::vector<double>& times = frameMs();
    return times.empty() ? 0.0 : *std::min_element(times.begin(), times.end());
}

namespace {

double processCpuMs() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

}  // namespace

FrameTimer::FrameTimer(FrameClock requested, const std::string& glRenderer) {
    GLint bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &bits);
    if (glGetError() != GL_NO_ERROR) bits = 0;
    if (bits > 0) glGenQueries(1, &mQuery);
    switch (requested) {
        case FrameClock::Wall:
            mClock = FrameClock::Wall;
            break;
        case FrameClock::GpuTimer:
            if (!mQuery) {
                throw RenderError("frame clock gpu: " + glRenderer +
                                  " has no GL_TIME_ELAPSED timer (0 counter bits); use --frame-clock wall");
            }
            mClock = FrameClock::GpuTimer;
            break;
        case FrameClock::Auto:
            mClock = mQuery && !isSoftwareRasterizer(glRenderer) ? FrameClock::GpuTimer : FrameClock::Wall;
            break;
    }
}

void FrameTimer::release() {
    if (mQuery) glDeleteQueries(1, &mQuery);
    mQuery = 0;
}

void FrameTimer::warmUpOnce(const std::function<void()>& drawAndReadBack, const std::function<void()>& draw) {
    if (mWarmedUp) return;
    drawAndReadBack();
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    for (int drawn = 0; drawn < kWarmUpDraws || elapsed() < kWarmUpSeconds; ++drawn) {
        draw();
        glFinish();
    }
    mWarmedUp = true;
}

FrameTimes FrameTimer::time(const std::function<void()>& draw, int repeats, int warmup) {
    for (int i = 0; i < warmup; ++i) {
        draw();
        glFinish();
    }
    FrameTimes times;
    times.clock = mClock;
    times.wallMs.reserve(std::size_t(repeats));
    times.cpuMs.reserve(std::size_t(repeats));
    if (mQuery) times.gpuMs.reserve(std::size_t(repeats));
    for (int i = 0; i < repeats; ++i) {
        const double cpuStart = processCpuMs();
        const auto wallStart = std::chrono::steady_clock::now();
        if (mQuery) glBeginQuery(GL_TIME_ELAPSED, mQuery);
        draw();
        if (mQuery) glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        const auto wallStop = std::chrono::steady_clock::now();
        times.cpuMs.push_back(processCpuMs() - cpuStart);
        times.wallMs.push_back(std::chrono::duration<double, std::milli>(wallStop - wallStart).count());
        if (mQuery) {  // after glFinish the result is ready: reading it does not stall the next draw
            GLuint64 nanoseconds = 0;
            glGetQueryObjectui64v(mQuery, GL_QUERY_RESULT, &nanoseconds);
            times.gpuMs.push_back(double(nanoseconds) * 1e-6);
        }
    }
    return times;
}

}  // namespace lodopt::renderer
