// Naming and summarizing frame times (renderer.hpp FrameClock, FrameTimes).
#include <algorithm>
#include <cctype>

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

}  // namespace lodopt::renderer
