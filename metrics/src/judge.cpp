// Butteraugli through libjxl's C API (jxl/butteraugli.h): 8-bit sRGB in, the distance map out,
// pooled by libjxl's own p-norm and maximum.
#include "metrics/judge.hpp"

#include <jxl/butteraugli.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "kernels.hpp"

namespace lodopt::metrics {

namespace {

constexpr int kMaxDisplayScale = 16;
constexpr int kSmallestSide = 8;  // pixels: what butteraugli measures at all

template <typename T>
[[noreturn]] void badJudgeParameter(const char* name, T value, const char* requirement) {
    std::ostringstream message;
    message << "judge parameter " << name << " = " << value << " is invalid: " << requirement;
    throw MetricError(message.str());
}

// The image as tightly packed RGB (gray replicated, alpha dropped), each pixel repeated
// `scale` times on both axes: what a display shows of it.
std::vector<std::uint8_t> displayedRgb(const ImageView& image, int scale) {
    const std::size_t width = std::size_t(image.width) * scale;
    const std::size_t height = std::size_t(image.height) * scale;
    std::vector<std::uint8_t> rgb(width * height * 3);
    for (std::size_t y = 0; y < height; ++y) {
        const std::uint8_t* row = image.pixels + (y / scale) * image.rowStride;
        std::uint8_t* out = rgb.data() + y * width * 3;
        for (std::size_t x = 0; x < width; ++x) {
            const std::uint8_t* pixel = row + (x / scale) * image.channels;
            for (int c = 0; c < 3; ++c) out[x * 3 + c] = image.channels == 1 ? pixel[0] : pixel[c];
        }
    }
    return rgb;
}

struct ApiDeleter {
    void operator()(JxlButteraugliApi* api) const { JxlButteraugliApiDestroy(api); }
};
struct ResultDeleter {
    void operator()(JxlButteraugliResult* result) const { JxlButteraugliResultDestroy(result); }
};

}  // namespace

void validateJudgeParameters(const JudgeParameters& p) {
    if (!(std::isfinite(p.intensityTargetNits) && p.intensityTargetNits > 0)) {
        badJudgeParameter("intensityTargetNits", p.intensityTargetNits, "must be finite and > 0");
    }
    if (!(std::isfinite(p.hfAsymmetry) && p.hfAsymmetry > 0)) {
        badJudgeParameter("hfAsymmetry", p.hfAsymmetry, "must be finite and > 0");
    }
    if (!(std::isfinite(p.pnorm) && p.pnorm >= 1)) badJudgeParameter("pnorm", p.pnorm, "must be finite and >= 1");
    if (p.displayScale < 1 || p.displayScale > kMaxDisplayScale) {
        badJudgeParameter("displayScale", p.displayScale, "must be within 1..16");
    }
}

JudgeResult judge(const ImageView& candidate, const ImageView& reference, const JudgeParameters& parameters) {
    detail::validatePair(candidate, reference);
    validateJudgeParameters(parameters);
    // libjxl's butteraugli answers 0 for any image narrower or lower than 8 pixels, however
    // different: such an image is shown larger, by the smallest factor that reaches 8.
    const int smallest = std::min(candidate.width, candidate.height);
    const int scale = std::max(parameters.displayScale, (kSmallestSide + smallest - 1) / smallest);
    const std::uint32_t width = std::uint32_t(candidate.width) * scale;
    const std::uint32_t height = std::uint32_t(candidate.height) * scale;
    const std::vector<std::uint8_t> referenceRgb = displayedRgb(reference, scale);
    const std::vector<std::uint8_t> candidateRgb = displayedRgb(candidate, scale);

    std::unique_ptr<JxlButteraugliApi, ApiDeleter> api(JxlButteraugliApiCreate(nullptr));
    if (!api) throw std::runtime_error("butteraugli: libjxl could not create its API object");
    JxlButteraugliApiSetIntensityTarget(api.get(), float(parameters.intensityTargetNits));
    JxlButteraugliApiSetHFAsymmetry(api.get(), float(parameters.hfAsymmetry));
    // 8-bit samples are read as sRGB-encoded (libjxl linearises them itself).
    const JxlPixelFormat format{3, JXL_TYPE_UINT8, JXL_NATIVE_ENDIAN, 0};
    std::unique_ptr<JxlButteraugliResult, ResultDeleter> result(
        JxlButteraugliCompute(api.get(), width, height, &format, referenceRgb.data(), referenceRgb.size(), &format,
                              candidateRgb.data(), candidateRgb.size()));
    if (!result) {
        throw std::runtime_error("butteraugli: libjxl failed on a " + std::to_string(width) + "x" +
                                 std::to_string(height) + " image pair");
    }
    JudgeResult out;
    out.width = candidate.width;
    out.height = candidate.height;
    out.distance = JxlButteraugliResultGetDistance(result.get(), float(parameters.pnorm));
    out.maxDistance = JxlButteraugliResultGetMaxDistance(result.get());
    if (parameters.keepDistanceMap) {
        const float* map = nullptr;
        std::uint32_t rowStride = 0;  // floats
        JxlButteraugliResultGetDistmap(result.get(), &map, &rowStride);
        out.distanceMap.assign(std::size_t(candidate.width) * candidate.height, 0.0f);
        const float share = 1.0f / float(scale * scale);
        for (std::uint32_t y = 0; y < height; ++y) {
            for (std::uint32_t x = 0; x < width; ++x) {
                out.distanceMap[std::size_t(y / scale) * candidate.width + x / scale] += map[y * rowStride + x] * share;
            }
        }
    }
    return out;
}

}  // namespace lodopt::metrics
