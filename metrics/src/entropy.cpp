// Boundary and information entropy (GAPSO15 §2, eqs. 3-6) and the entropy fidelity.
//
// Defaults are Shannon entropies of histograms (bits): the Sobel 3x3 gradient magnitude of
// the interior pixels over the fixed range [0, 255 sqrt(20)], and the gray image rounded to
// 256 levels. The paper's literal forms (Roberts-cross -sum g log2 g; intensity shares
// p = x / sum x) are kept selectable for comparison; see docs/metrics.md for why they are
// not the default.
#include <algorithm>
#include <cmath>

#include "kernels.hpp"

namespace lodopt::metrics {

double boundaryEntropy(const ImageView& image, const MetricParameters& parameters) {
    validateParameters(parameters);
    detail::validateView(image, "image");
    const detail::GrayScale grayScale = detail::grayScale(parameters.grayWeights);
    std::vector<std::int32_t> gray;
    detail::grayImage(image, grayScale, gray);
    const int width = image.width, height = image.height;
    const std::ptrdiff_t stride = width;

    if (parameters.boundaryEntropyMode == EntropyMode::Paper) {
        // Sum of -g log2 g over pixels that have a right and a lower neighbour, pooled like
        // every map here (tiles, rows) so the incremental evaluator reproduces it exactly.
        if (width < 2 || height < 2) return 0.0;
        const double inverseScale = 1.0 / grayScale.scale;
        std::vector<double> terms(std::size_t(width - 1));
        double total = 0;
        for (int y = 0; y + 1 < height; ++y) {
            const std::int32_t* row = gray.data() + std::size_t(y) * width;
            for (int x = 0; x + 1 < width; ++x) terms[std::size_t(x)] = detail::robertsTerm(row + x, stride, inverseScale);
            total += detail::rowSum(terms.data(), width - 1, nullptr);
        }
        return total + 0.0;
    }

    // Interior pixels only: the Sobel operator needs all 8 neighbours, and padding would
    // invent edges at the border. Images under 3x3 have no interior: entropy 0.
    const detail::SobelBinning binning = detail::makeSobelBinning(parameters.boundaryHistogramBins, grayScale);
    if (width < 3 || height < 3) return 0.0;
    std::vector<std::uint64_t> histogram(std::size_t(binning.bins), 0);
    detail::LaneHistogram lanes;
    lanes.resize(binning.bins);
    std::vector<std::uint16_t> bins(static_cast<std::size_t>(width));
    for (int y = 1; y + 1 < height; ++y) {
        detail::sobelBinsRow(gray.data() + std::size_t(y) * width + 1, stride, width - 2, binning, bins.data());
        lanes.addRow(bins.data(), width - 2, 1);
    }
    lanes.mergeInto(histogram.data());
    const std::uint64_t interior = std::uint64_t(width - 2) * std::uint64_t(height - 2);
    return detail::histogramEntropy(histogram.data(), binning.bins, interior);
}

double informationEntropy(const ImageView& image, const MetricParameters& parameters) {
    validateParameters(parameters);
    detail::validateView(image, "image");
    const detail::GrayScale grayScale = detail::grayScale(parameters.grayWeights);
    std::vector<std::int32_t> gray(std::size_t(image.width));
    const std::uint64_t pixels = std::uint64_t(image.width) * std::uint64_t(image.height);

    if (parameters.informationEntropyMode == EntropyMode::Paper) {
        std::vector<double> terms(std::size_t(image.width));
        std::int64_t intensitySum = 0;
        double termSum = 0;
        for (int y = 0; y < image.height; ++y) {
            detail::grayRow(image.pixels + y * image.rowStride, image.channels, image.width, grayScale, gray.data());
            for (int x = 0; x < image.width; ++x) {
                intensitySum += gray[std::size_t(x)];
                terms[std::size_t(x)] = detail::intensityTerm(gray[std::size_t(x)]);
            }
            termSum += detail::rowSum(terms.data(), image.width, nullptr);
        }
        return detail::intensityShareEntropy(intensitySum, termSum, pixels);
    }

    std::array<std::uint64_t, 256> histogram{};
    detail::LaneHistogram lanes;
    lanes.resize(256);
    std::vector<std::uint8_t> bins(static_cast<std::size_t>(image.width));
    for (int y = 0; y < image.height; ++y) {
        detail::grayRow(image.pixels + y * image.rowStride, image.channels, image.width, grayScale, gray.data());
        detail::grayBinsRow(gray.data(), image.width, grayScale, bins.data());
        lanes.addRow(bins.data(), image.width, 1);
    }
    lanes.mergeInto(histogram.data());
    return detail::histogramEntropy(histogram.data(), 256, pixels);
}

double entropyFidelity(double candidate, double reference, double epsilon) {
    // |reference| rather than reference: the paper's literal boundary form can be negative.
    const double scale = std::max(std::abs(reference), epsilon);
    const double fidelity = 1.0 - std::abs(candidate - reference) / scale;
    // Written so that NaN (impossible from finite inputs, but cheap to rule out) maps to 0.
    return fidelity >= 0.0 ? std::min(fidelity, 1.0) : 0.0;
}

}  // namespace lodopt::metrics
