// Parameter validation, float image conversion, and the fusion of the components into one
// fitness (GAPSO15 §2: "linear superposition of three indexes"; our fidelity mapping is in
// docs/metrics.md).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "kernels.hpp"
#include "prepared_reference.hpp"

namespace lodopt::metrics {

namespace {

template <class T>
[[noreturn]] void badParameter(const char* name, T value, const char* requirement) {
    std::ostringstream message;
    message << "metric parameter " << name << " = " << value << " is invalid: " << requirement;
    throw MetricError(message.str());
}

void checkPositive(const char* name, double value) {
    if (!(std::isfinite(value) && value > 0)) badParameter(name, value, "must be finite and > 0");
}

void checkWeight(const char* name, double value) {
    if (!(std::isfinite(value) && value >= 0)) badParameter(name, value, "must be finite and >= 0");
}

}  // namespace

ImageView makeImageView(const std::uint8_t* pixels, int width, int height, int channels) {
    return {pixels, width, height, channels, std::size_t(std::max(width, 0)) * std::size_t(std::max(channels, 0))};
}

ImageView convertFloatImage(const FloatImageView& image, std::vector<std::uint8_t>& storage) {
    if (image.width < 1 || image.height < 1 || (image.channels != 1 && image.channels != 3 && image.channels != 4) ||
        image.pixels == nullptr || image.rowStride < std::size_t(image.width) * image.channels) {
        throw MetricError("float image: " + std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                          std::to_string(image.channels) + " with row stride " + std::to_string(image.rowStride) +
                          " floats is not a valid image");
    }
    const std::size_t rowBytes = std::size_t(image.width) * image.channels;
    storage.resize(rowBytes * image.height);
    for (int y = 0; y < image.height; ++y) {
        const float* in = image.pixels + y * image.rowStride;
        std::uint8_t* out = storage.data() + y * rowBytes;
        for (std::size_t i = 0; i < rowBytes; ++i) {
            const float v = in[i];
            if (!std::isfinite(v)) {
                std::ostringstream message;
                message << "float image: pixel (" << i / image.channels << ", " << y << ") channel "
                        << i % image.channels << " is " << v << " (NaN and infinity cannot be scored)";
                throw MetricError(message.str());
            }
            // Round half up after clamping to the displayable range, like a framebuffer write.
            out[i] = std::uint8_t(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
        }
    }
    return makeImageView(storage.data(), image.width, image.height, image.channels);
}

void validateParameters(const MetricParameters& p) {
    if (p.grayWeights != GrayWeights::Paper && p.grayWeights != GrayWeights::Bt601 &&
        p.grayWeights != GrayWeights::Bt709) {
        badParameter("grayWeights", int(p.grayWeights), "must be Paper, Bt601 or Bt709");
    }
    if (p.ssimWindow < 1 || p.ssimWindow > detail::kSsimMaxWindow || p.ssimWindow % 2 == 0) {
        badParameter("ssimWindow", p.ssimWindow, "must be odd and within 1..63");
    }
    checkPositive("ssimSigma", p.ssimSigma);
    checkPositive("ssimK1", p.ssimK1);
    checkPositive("ssimK2", p.ssimK2);
    checkPositive("ssimDynamicRange", p.ssimDynamicRange);
    if (p.boundaryEntropyMode != EntropyMode::Histogram && p.boundaryEntropyMode != EntropyMode::Paper) {
        badParameter("boundaryEntropyMode", int(p.boundaryEntropyMode), "must be Histogram or Paper");
    }
    if (p.informationEntropyMode != EntropyMode::Histogram && p.informationEntropyMode != EntropyMode::Paper) {
        badParameter("informationEntropyMode", int(p.informationEntropyMode), "must be Histogram or Paper");
    }
    if (p.boundaryHistogramBins < 2 || p.boundaryHistogramBins > 65536) {
        badParameter("boundaryHistogramBins", p.boundaryHistogramBins, "must be within 2..65536");
    }
    checkPositive("entropyEpsilon", p.entropyEpsilon);
    if (p.matchTolerance < 0 || p.matchTolerance > 255) {
        badParameter("matchTolerance", p.matchTolerance, "must be within 0..255");
    }
    checkWeight("ssimWeight", p.ssimWeight);
    checkWeight("boundaryEntropyWeight", p.boundaryEntropyWeight);
    checkWeight("informationEntropyWeight", p.informationEntropyWeight);
    if (p.ssimWeight + p.boundaryEntropyWeight + p.informationEntropyWeight <= 0) {
        throw MetricError("metric parameters: at least one of ssimWeight, boundaryEntropyWeight and "
                          "informationEntropyWeight must be > 0 (all are 0)");
    }
}

void fuse(MetricResult& result, const MetricParameters& parameters) {
    double weighted = 0, weights = 0;
    if (result.ssimComputed) {
        result.ssimFidelity = std::clamp(result.ssim, 0.0, 1.0);
        weighted += parameters.ssimWeight * result.ssimFidelity;
        weights += parameters.ssimWeight;
    }
    EntropyComponent* entropies[2] = {&result.boundaryEntropy, &result.informationEntropy};
    const double entropyWeights[2] = {parameters.boundaryEntropyWeight, parameters.informationEntropyWeight};
    for (int i = 0; i < 2; ++i) {
        if (!entropies[i]->computed) continue;
        entropies[i]->fidelity =
            entropyFidelity(entropies[i]->candidate, entropies[i]->reference, parameters.entropyEpsilon);
        weighted += entropyWeights[i] * entropies[i]->fidelity;
        weights += entropyWeights[i];
    }
    // With every fidelity 1 the two sums are built by the same additions: fitness is exactly 1.
    result.fitness = weights > 0 ? std::clamp(weighted / weights, 0.0, 1.0) : 0.0;
}

MetricResult evaluate(const ImageView& candidate, const ImageView& reference, const MetricParameters& parameters) {
    validateParameters(parameters);
    detail::validatePair(candidate, reference);
    MetricResult result;
    if (parameters.ssimWeight > 0) {
        result.ssimComputed = true;
        result.ssim = ssim(candidate, reference, parameters);
    }
    if (parameters.boundaryEntropyWeight > 0) {
        result.boundaryEntropy.computed = true;
        result.boundaryEntropy.candidate = boundaryEntropy(candidate, parameters);
        result.boundaryEntropy.reference = boundaryEntropy(reference, parameters);
    }
    if (parameters.informationEntropyWeight > 0) {
        result.informationEntropy.computed = true;
        result.informationEntropy.candidate = informationEntropy(candidate, parameters);
        result.informationEntropy.reference = informationEntropy(reference, parameters);
    }
    if (parameters.computePrecisionRecall) {
        detail::setPrecisionRecall(result, precisionRecall(candidate, reference, parameters));
    }
    fuse(result, parameters);
    return result;
}

}  // namespace lodopt::metrics
