#include "report_images.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "cli_common.hpp"
#include "metrics/metrics.hpp"

namespace lodopt::cli {
namespace {

using Stops = std::array<std::uint32_t, 9>;  // 0xRRGGBB at 0, 1/8, ..., 1
// Matplotlib's magma and inferno (van der Walt & Smith), sampled at nine points: perceptually
// uniform and readable in gray print.
constexpr Stops kMagma = {0x000004, 0x1c1044, 0x4f127b, 0x812581, 0xb5367a, 0xe55064, 0xfb8761, 0xfec287, 0xfcfdbf};
constexpr Stops kInferno = {0x000004, 0x1f0c48, 0x550f6d, 0x88226a, 0xba3655, 0xe35933, 0xf98e09, 0xf8c932, 0xfcffa4};

void colorAt(const Stops& stops, double t, std::uint8_t* rgba) {
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * double(stops.size() - 1);
    const std::size_t i = std::min(std::size_t(t), stops.size() - 2);
    const double f = t - double(i);
    for (int c = 0; c < 3; ++c) {
        const int shift = 16 - 8 * c;
        const double a = double((stops[i] >> shift) & 0xff), b = double((stops[i + 1] >> shift) & 0xff);
        rgba[c] = std::uint8_t(std::lround(a + (b - a) * f));
    }
    rgba[3] = 255;
}

std::string css(const Stops& stops) {
    std::string out;
    char text[16];
    for (std::size_t i = 0; i < stops.size(); ++i) {
        std::snprintf(text, sizeof(text), "#%06x", unsigned(stops[i]));
        out += (i ? ", " : "") + std::string(text);
    }
    return out;
}

renderer::Frame blankFrame(int width, int height) {
    renderer::Frame frame;
    frame.width = width;
    frame.height = height;
    frame.rgba.assign(std::size_t(width) * height * 4, 128);
    for (std::size_t i = 3; i < frame.rgba.size(); i += 4) frame.rgba[i] = 255;
    frame.depth.assign(std::size_t(width) * height, 1.0f);
    return frame;
}

}  // namespace

std::string magmaCss() {
    return css(kMagma);
}
std::string infernoCss() {
    return css(kInferno);
}

renderer::Frame loadRgbaImage(const std::string& path) {
    renderer::LoadedImage image;
    try {
        image = renderer::readImage(path);
    } catch (const std::exception& error) {
        throw UsageError(error.what());
    }
    renderer::Frame frame = blankFrame(image.width, image.height);
    const std::size_t count = std::size_t(image.width) * image.height;
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t* in = &image.pixels[i * image.channels];
        std::uint8_t* out = &frame.rgba[i * 4];
        if (image.channels == 1) {
            out[0] = out[1] = out[2] = in[0];
        } else {
            out[0] = in[0];
            out[1] = in[1];
            out[2] = in[2];
        }
        out[3] = 255;
    }
    return frame;
}

DifferenceMaps differenceMaps(const renderer::Frame& candidate, const renderer::Frame& reference,
                              const std::string& what) {
    if (candidate.width != reference.width || candidate.height != reference.height) {
        throw UsageError(what + ": " + std::to_string(candidate.width) + "x" + std::to_string(candidate.height) +
                         " differs from the reference's " + std::to_string(reference.width) + "x" +
                         std::to_string(reference.height));
    }
    const int width = candidate.width, height = candidate.height;
    DifferenceMaps maps;
    const metrics::MetricParameters parameters;
    const metrics::ImageView candidateView = metrics::makeImageView(candidate.rgba.data(), width, height, 4);
    const metrics::ImageView referenceView = metrics::makeImageView(reference.rgba.data(), width, height, 4);

    const metrics::SsimMapSize size = metrics::ssimMapSize(width, height, parameters);
    std::vector<double> map(std::size_t(size.width) * size.height);
    metrics::ssimMap(candidateView, referenceView, parameters, map.data(), std::size_t(size.width));
    maps.meanSsim = metrics::poolMean(map.data(), size.width, size.height, std::size_t(size.width));
    const double lowest = *std::min_element(map.begin(), map.end());
    maps.ssimLow = std::clamp(std::floor(lowest / 0.05) * 0.05, -1.0, 0.9);
    maps.ssimMap = blankFrame(width, height);
    const int offset = size.window / 2;
    for (int y = 0; y < size.height; ++y) {
        for (int x = 0; x < size.width; ++x) {
            const double v = map[std::size_t(y) * size.width + x];
            colorAt(kMagma, (v - maps.ssimLow) / (1.0 - maps.ssimLow),
                    &maps.ssimMap.rgba[(std::size_t(y + offset) * width + (x + offset)) * 4]);
        }
    }

    std::vector<int> difference(std::size_t(width) * height);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < difference.size(); ++i) {
        int largest = 0;
        for (int c = 0; c < 3; ++c)
            largest = std::max(largest, std::abs(int(candidate.rgba[i * 4 + c]) - int(reference.rgba[i * 4 + c])));
        difference[i] = largest;
        maps.largestDifference = std::max(maps.largestDifference, largest);
        changed += largest > 0;
    }
    maps.changedShare = difference.empty() ? 0.0 : double(changed) / double(difference.size());
    maps.differenceHigh = std::max(16, maps.largestDifference);
    maps.difference = blankFrame(width, height);
    for (std::size_t i = 0; i < difference.size(); ++i) {
        colorAt(kInferno, double(difference[i]) / maps.differenceHigh, &maps.difference.rgba[i * 4]);
    }
    return maps;
}

JudgeMap judgeMap(const renderer::Frame& candidate, const renderer::Frame& reference,
                  const metrics::JudgeParameters& parameters, const std::string& what) {
    if (candidate.width != reference.width || candidate.height != reference.height) {
        throw UsageError(what + ": " + std::to_string(candidate.width) + "x" + std::to_string(candidate.height) +
                         " differs from the reference's " + std::to_string(reference.width) + "x" +
                         std::to_string(reference.height));
    }
    const int width = candidate.width, height = candidate.height;
    metrics::JudgeParameters withMap = parameters;
    withMap.keepDistanceMap = true;
    const metrics::JudgeResult result =
        metrics::judge(metrics::makeImageView(candidate.rgba.data(), width, height, 4),
                       metrics::makeImageView(reference.rgba.data(), width, height, 4), withMap);
    JudgeMap map;
    map.distance = result.distance;
    map.maxDistance = result.maxDistance;
    map.high = std::max(1.0, std::ceil(result.maxDistance));
    map.heat = blankFrame(width, height);
    for (std::size_t i = 0; i < result.distanceMap.size(); ++i) {
        colorAt(kInferno, double(result.distanceMap[i]) / map.high, &map.heat.rgba[i * 4]);
    }
    return map;
}

}  // namespace lodopt::cli
