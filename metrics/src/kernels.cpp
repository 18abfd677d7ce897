// Shared kernels: image validation, exact integer gray, pooling, histogram entropy.
#include "kernels.hpp"

#include <algorithm>
#include <string>

namespace lodopt::metrics::detail {

namespace {
constexpr int kMaxSide = 65536;
}

void validateView(const ImageView& view, const char* what) {
    // The message strings are built only on failure: validation runs in allocation-free paths.
    auto name = [what] { return std::string(what); };
    if (view.width < 1 || view.width > kMaxSide || view.height < 1 || view.height > kMaxSide) {
        throw MetricError(name() + ": size " + std::to_string(view.width) + "x" + std::to_string(view.height) +
                          " is not within 1..65536 pixels per side");
    }
    if (view.channels != 1 && view.channels != 3 && view.channels != 4) {
        throw MetricError(name() + ": " + std::to_string(view.channels) + " channels (expected 1, 3 or 4)");
    }
    if (view.pixels == nullptr) throw MetricError(name() + ": no pixel data");
    if (view.rowStride < std::size_t(view.width) * view.channels) {
        throw MetricError(name() + ": row stride " + std::to_string(view.rowStride) + " bytes is shorter than a row (" +
                          std::to_string(std::size_t(view.width) * view.channels) + " bytes)");
    }
}

void validatePair(const ImageView& candidate, const ImageView& reference) {
    validateView(candidate, "candidate image");
    validateView(reference, "reference image");
    if (candidate.width != reference.width || candidate.height != reference.height) {
        throw MetricError("candidate image is " + std::to_string(candidate.width) + "x" +
                          std::to_string(candidate.height) + " but the reference is " +
                          std::to_string(reference.width) + "x" + std::to_string(reference.height));
    }
    if (candidate.channels != reference.channels) {
        throw MetricError("candidate image has " + std::to_string(candidate.channels) +
                          " channels but the reference has " + std::to_string(reference.channels));
    }
}

GrayScale grayScale(GrayWeights weights) {
    auto make = [](std::int32_t r, std::int32_t g, std::int32_t b, std::int32_t scale) {
        return GrayScale{r, g, b, scale, 1.0 / scale};
    };
    switch (weights) {
        case GrayWeights::Paper:
            return make(30, 59, 11, 100);
        case GrayWeights::Bt601:
            return make(299, 587, 114, 1000);
        case GrayWeights::Bt709:
            return make(2126, 7152, 722, 10000);
    }
    throw MetricError("unknown gray weights value " + std::to_string(int(weights)));
}

namespace {
template <int Channels>
void grayRowFixed(const std::uint8_t* __restrict pixels, int count, std::int32_t r, std::int32_t g, std::int32_t b,
                  std::int32_t* __restrict out) {
    for (int i = 0; i < count; ++i) {
        const std::uint8_t* p = pixels + i * Channels;
        out[i] = r * p[0] + g * p[1] + b * p[2];
    }
}
}  // namespace

LODOPT_METRICS_CLONES void grayRow(const std::uint8_t* pixels, int channels, int count, const GrayScale& gray,
                                   std::int32_t* out) {
    // Weights copied to locals: `out` could otherwise alias them and block vectorisation.
    const std::int32_t r = gray.r, g = gray.g, b = gray.b, scale = gray.scale;
    if (channels == 1) {
        for (int i = 0; i < count; ++i) out[i] = std::int32_t(pixels[i]) * scale;
    } else if (channels == 3) {
        grayRowFixed<3>(pixels, count, r, g, b, out);
    } else {
        grayRowFixed<4>(pixels, count, r, g, b, out);
    }
}

LODOPT_METRICS_CLONES void grayBinsRow(const std::int32_t* scaledGray, int count, const GrayScale& gray,
                                       std::uint8_t* out) {
    const GrayScale local = gray;  // no aliasing with `out`
    for (int i = 0; i < count; ++i) out[i] = std::uint8_t(grayBin(scaledGray[i], local));
}

void grayImage(const ImageView& image, const GrayScale& gray, std::vector<std::int32_t>& out) {
    out.resize(std::size_t(image.width) * image.height);
    for (int y = 0; y < image.height; ++y) {
        grayRow(image.pixels + y * image.rowStride, image.channels, image.width, gray,
                out.data() + std::size_t(y) * image.width);
    }
}

double tileSum(const double* values, int count) {
    // Four interleaved accumulators: fast, and the order is fixed by `count` alone.
    double a0 = 0, a1 = 0, a2 = 0, a3 = 0;
    int i = 0;
    for (; i + 4 <= count; i += 4) {
        a0 += values[i];
        a1 += values[i + 1];
        a2 += values[i + 2];
        a3 += values[i + 3];
    }
    for (; i < count; ++i) a0 += values[i];
    return (a0 + a1) + (a2 + a3);
}

double sequentialSum(const double* values, int count) {
    double sum = 0;
    for (int i = 0; i < count; ++i) sum += values[i];
    return sum;
}

double rowSum(const double* row, int width, double* tileSums) {
    double sum = 0;
    for (int t = 0, x = 0; x < width; ++t, x += kPoolTile) {
        const double tile = tileSum(row + x, std::min(kPoolTile, width - x));
        if (tileSums) tileSums[t] = tile;
        sum += tile;
    }
    return sum;
}

LODOPT_METRICS_CLONES std::int64_t ssimFixedSum(const double* values, int count) {
    std::int64_t sum = 0;
    for (int i = 0; i < count; ++i) sum += ssimFixed(values[i]);
    return sum;
}

template <typename TileSum, typename Total>
void TiledMap<TileSum, Total>::resize(int width, int height) {
    mWidth = std::max(width, 0);
    mHeight = std::max(height, 0);
    mTiles = poolTiles(mWidth);
    mValues.assign(std::size_t(mWidth) * mHeight, 0.0);
    mTileSums.assign(std::size_t(mTiles) * mHeight, TileSum(0));
    mRowSums.assign(std::size_t(mHeight), TileSum(0));
    mTotal = 0;
}
template class TiledMap<std::int64_t, SsimFixedTotal>;
template class TiledMap<double, double>;

namespace {

// [x0, x1) x [y0, y1) clipped to a width x height map; false when nothing is left.
bool clipRect(int& x0, int& y0, int& x1, int& y1, int width, int height) {
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, width);
    y1 = std::min(y1, height);
    return x0 < x1 && y0 < y1;
}

}  // namespace

template <>
void FixedPooledMap::refresh(int x0, int y0, int x1, int y1) {
    if (!clipRect(x0, y0, x1, y1, mWidth, mHeight)) return;
    const int t0 = x0 / kPoolTile, t1 = (x1 - 1) / kPoolTile + 1;
    for (int y = y0; y < y1; ++y) {
        std::int64_t* tiles = mTileSums.data() + std::size_t(y) * mTiles;
        const double* values = mValues.data() + std::size_t(y) * mWidth;
        std::int64_t row = mRowSums[std::size_t(y)];
        for (int t = t0; t < t1; ++t) {
            const int x = t * kPoolTile;
            const std::int64_t tile = ssimFixedSum(values + x, std::min(kPoolTile, mWidth - x));
            row += tile - tiles[t];  // integers: updating the sums in place is exact
            tiles[t] = tile;
        }
        mTotal += row - mRowSums[std::size_t(y)];
        mRowSums[std::size_t(y)] = row;
    }
}

template <>
void PooledMap::refresh(int x0, int y0, int x1, int y1) {
    if (!clipRect(x0, y0, x1, y1, mWidth, mHeight)) return;
    const int t0 = x0 / kPoolTile, t1 = (x1 - 1) / kPoolTile + 1;
    for (int y = y0; y < y1; ++y) {
        double* tiles = mTileSums.data() + std::size_t(y) * mTiles;
        const double* values = mValues.data() + std::size_t(y) * mWidth;
        for (int t = t0; t < t1; ++t) {
            const int x = t * kPoolTile;
            tiles[t] = tileSum(values + x, std::min(kPoolTile, mWidth - x));
        }
        // Same order as rowSum: the tiles left to right.
        mRowSums[std::size_t(y)] = sequentialSum(tiles, mTiles);
    }
    mTotal = sequentialSum(mRowSums.data(), mHeight);
}

double histogramEntropy(const std::uint64_t* counts, int bins, std::uint64_t total) {
    if (total == 0) return 0.0;
    const double inverseTotal = 1.0 / double(total);
    double entropy = 0;
    for (int i = 0; i < bins; ++i) {
        if (counts[i] == 0) continue;
        const double p = double(counts[i]) * inverseTotal;
        entropy -= p * std::log2(p);
    }
    // Each term is >= 0 but rounding may step a hair past the bounds; -0 becomes +0.
    return std::clamp(entropy, 0.0, std::log2(double(bins))) + 0.0;
}

SobelBinning makeSobelBinning(int bins, const GrayScale& gray) {
    // 255 sqrt(20) is the largest Sobel magnitude of 8-bit data (gx = 1020, gy = 510).
    return {bins, double(bins) / (255.0 * std::sqrt(20.0) * gray.scale)};
}

LODOPT_METRICS_CLONES void sobelBinsRow(const std::int32_t* center, std::ptrdiff_t stride, int count,
                                        const SobelBinning& binning, std::uint16_t* out) {
    const std::int32_t* __restrict up = center - stride;
    const std::int32_t* __restrict mid = center;
    const std::int32_t* __restrict down = center + stride;
    const double scale = binning.scale;
    const int last = binning.bins - 1;
    for (int x = 0; x < count; ++x) {
        // |gx|, |gy| <= 1020 * 10000 fit int32; their squares and sum are exact in double.
        const std::int32_t gx = (up[x + 1] + 2 * mid[x + 1] + down[x + 1]) - (up[x - 1] + 2 * mid[x - 1] + down[x - 1]);
        const std::int32_t gy = (down[x - 1] + 2 * down[x] + down[x + 1]) - (up[x - 1] + 2 * up[x] + up[x + 1]);
        const double dx = gx, dy = gy;
        const int bin = int(std::sqrt(dx * dx + dy * dy) * scale);
        out[x] = std::uint16_t(bin < last ? bin : last);
    }
}

void LaneHistogram::resize(int bins) {
    mBins = bins;
    // Four lanes while merging them stays cheap next to an update; one for huge histograms.
    mLaneCount = bins <= 4096 ? 4 : 1;
    mLanes.assign(std::size_t(mLaneCount) * bins, 0);
}

void LaneHistogram::mergeInto(std::uint64_t* histogram) {
    for (int lane = 0; lane < mLaneCount; ++lane) {
        std::int64_t* counts = mLanes.data() + std::size_t(lane) * mBins;
        for (int b = 0; b < mBins; ++b) {
            histogram[b] += std::uint64_t(counts[b]);  // modular: a negative change subtracts
            counts[b] = 0;
        }
    }
}

namespace {
// Two passes per chunk of pixels so both vectorise: per byte, flags "candidate differs from
// the background" (1), "reference differs from the background" (2), "difference above the
// tolerance" (4); then per pixel, the OR of its channels' flags decides the class.
template <int Channels>
void classifyRowFixed(const std::uint8_t* candidate, const std::uint8_t* reference, int count, const CoverageRule& rule,
                      std::uint8_t* out) {
    constexpr int kChunk = 64;
    std::uint8_t background[kChunk * Channels];
    for (int i = 0; i < kChunk * Channels; ++i) background[i] = rule.background[std::size_t(i % Channels)];
    const std::uint8_t tolerance = std::uint8_t(rule.tolerance);
    std::uint8_t flags[kChunk * Channels];
    for (int x0 = 0; x0 < count; x0 += kChunk) {
        const int n = std::min(kChunk, count - x0);
        const std::uint8_t* __restrict p = candidate + std::size_t(x0) * Channels;
        const std::uint8_t* __restrict q = reference + std::size_t(x0) * Channels;
        for (int i = 0; i < n * Channels; ++i) {
            const std::uint8_t a = p[i], b = q[i], g = background[i];
            const std::uint8_t difference = a > b ? std::uint8_t(a - b) : std::uint8_t(b - a);
            flags[i] = std::uint8_t((a != g) | ((b != g) << 1) | ((difference > tolerance) << 2));
        }
        std::uint8_t* __restrict o = out + x0;
        for (int x = 0; x < n; ++x) {
            std::uint8_t f = 0;
            for (int c = 0; c < Channels; ++c) f |= flags[x * Channels + c];
            // Covered in both and matching: TP. Otherwise FP if covered in the candidate, FN if
            // covered in the reference: bits 1 and 2 of f shifted onto kFalsePositive/Negative.
            o[x] = f == 3 ? std::uint8_t(kTruePositive) : std::uint8_t((f & 3) << 1);
        }
    }
}
}  // namespace

void classifyRow(const std::uint8_t* candidate, const std::uint8_t* reference, int count, const CoverageRule& rule,
                 std::uint8_t* out) {
    switch (rule.channels) {
        case 1:
            classifyRowFixed<1>(candidate, reference, count, rule, out);
            break;
        case 3:
            classifyRowFixed<3>(candidate, reference, count, rule, out);
            break;
        default:
            classifyRowFixed<4>(candidate, reference, count, rule, out);
            break;
    }
}

double intensityShareEntropy(std::int64_t intensitySum, double termSum, std::uint64_t pixelCount) {
    // An all-black image has no intensity to share: entropy 0 instead of 0 / 0.
    if (intensitySum <= 0 || pixelCount == 0) return 0.0;
    const double sum = double(intensitySum);
    const double entropy = std::log2(sum) - termSum / sum;
    return std::clamp(entropy, 0.0, std::log2(double(pixelCount))) + 0.0;
}

CoverageRule makeCoverageRule(const MetricParameters& parameters, int channels, const GrayScale& gray) {
    CoverageRule rule;
    rule.channels = channels;
    rule.tolerance = parameters.matchTolerance;
    rule.background = parameters.background;
    if (channels == 1) {
        const std::uint8_t* bg = parameters.background.data();
        rule.background[0] = std::uint8_t(grayBin(gray.r * bg[0] + gray.g * bg[1] + gray.b * bg[2], gray));
    }
    return rule;
}

}  // namespace lodopt::metrics::detail
