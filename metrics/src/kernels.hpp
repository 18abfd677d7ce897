// Per-pixel kernels shared by the one-shot functions and IncrementalEvaluator.
//
// Exactness rests on one rule: a value (gray pixel, SSIM window, Sobel bin, pooled sum) is
// computed by exactly one function here, with a fixed order of operations that does not
// depend on which rectangle is being processed. Both paths call these functions, so they
// produce the same bits.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "metrics/metrics.hpp"

// The hot loops are compiled for AVX-512, AVX2 and baseline x86-64 and picked at load time
// (GCC/Clang target_clones). Contraction into FMA is off for this library (CMake), so every
// clone rounds identically: only the speed differs.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(LODOPT_NO_TARGET_CLONES)
#define LODOPT_METRICS_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define LODOPT_METRICS_CLONES
#endif
#if defined(__GNUC__) || defined(__clang__)
#define LODOPT_METRICS_INLINE inline __attribute__((always_inline))
#else
#define LODOPT_METRICS_INLINE inline
#endif

namespace lodopt::metrics {
class PartCache;
}

namespace lodopt::metrics::detail {

// --- Images and gray ----------------------------------------------------------------------

// Throws MetricError when `view` is not a usable image; `what` names it ("candidate image").
void validateView(const ImageView& view, const char* what);
// Both valid, same width, height and channel count; throws MetricError otherwise.
void validatePair(const ImageView& candidate, const ImageView& reference);

// Gray scaled by `scale` (a power of ten) so it is an exact integer:
// gray * scale = r R + g G + b B (gray images: scale V).
struct GrayScale {
    std::int32_t r = 30, g = 59, b = 11, scale = 100;
    double inverseScale = 1.0 / 100;  // for grayBin
};
GrayScale grayScale(GrayWeights weights);
// Scaled gray of `count` pixels starting at `pixels` (interleaved, `channels` bytes each).
void grayRow(const std::uint8_t* pixels, int channels, int count, const GrayScale& gray, std::int32_t* out);
// Whole image into `out` (width * height values, rows packed).
void grayImage(const ImageView& image, const GrayScale& gray, std::vector<std::int32_t>& out);

// Histogram bin 0..255 of a scaled gray value: the gray value rounded half up, i.e.
// floor((n + s/2) / s). Computed as floor((n + s/2 + 0.5) * fl(1/s)): the true quotient's
// fraction lies in [0.5/s, 1 - 0.5/s], far wider than the ~1e-13 rounding error, so the
// result is exact, and unlike an integer division it vectorises.
inline int grayBin(std::int32_t scaledGray, const GrayScale& gray) {
    return int((double(scaledGray) + (double(gray.scale / 2) + 0.5)) * gray.inverseScale);
}
// grayBin of `count` values.
void grayBinsRow(const std::int32_t* scaledGray, int count, const GrayScale& gray, std::uint8_t* out);

// --- Pooling ------------------------------------------------------------------------------

// Map sums are pooled as: tiles of kPoolTile columns (4 interleaved accumulators), then the
// row's tiles in order, then the rows in order. A changed rectangle re-pools only its tiles.
constexpr int kPoolTile = 64;
inline int poolTiles(int width) {
    return (width + kPoolTile - 1) / kPoolTile;
}
double tileSum(const double* values, int count);
// Sum of one row of `width` values; writes its tile sums to `tileSums` when not null.
double rowSum(const double* row, int width, double* tileSums);
double sequentialSum(const double* values, int count);

// SSIM windows are pooled in fixed point: a value v in [-1, 1] counts as the integer nearest
// to v * 2^40. Integer sums do not depend on their order, so every partition of the map (tiles
// and rows, the fast path's groups of windows, owned and live windows) adds up to the same
// bits; the rounding moves the mean by at most 2^-41.
constexpr double kSsimFixedScale = 1099511627776.0;  // 2^40
// round(v * 2^40) by the 1.5 * 2^52 trick (round to nearest even, and it vectorises, unlike
// llrint): exact for |v * 2^40| < 2^51. Contraction is off for this library, so no FMA.
inline std::int64_t ssimFixed(double value) {
    constexpr double kMagic = 6755399441055744.0;  // 1.5 * 2^52
    const double shifted = value * kSsimFixedScale + kMagic;
    std::int64_t bits, magicBits;
    std::memcpy(&bits, &shifted, sizeof bits);
    std::memcpy(&magicBits, &kMagic, sizeof magicBits);
    return bits - magicBits;
}
// Sum of ssimFixed over `count` values (|sum| < 2^63 for count < 2^23: a row or a tile).
std::int64_t ssimFixedSum(const double* values, int count);
// Totals over more windows than that (a 65536^2 image has 2^32) need 128 bits.
__extension__ typedef __int128 SsimFixedTotal;
// Mean SSIM from a fixed-point total over `windows` windows.
inline double ssimMeanFromFixed(SsimFixedTotal total, std::uint64_t windows) {
    return double(total) / kSsimFixedScale / double(windows);
}

// A map of per-pixel values kept with its tile and row sums, so that a changed rectangle
// re-pools only its tiles. Two kinds: the SSIM map in fixed point (FixedPooledMap: integer
// sums updated in place, exact) and the paper's entropy terms (PooledMap: a changed row and
// the total re-summed in one order, so the sum never depends on the order of the updates).
template <typename TileSum, typename Total>
class TiledMap {
public:
    void resize(int width, int height);  // all values 0
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    double* row(int y) { return mValues.data() + std::size_t(y) * mWidth; }
    const double* values() const { return mValues.data(); }
    bool empty() const { return mWidth <= 0 || mHeight <= 0; }
    // Re-pools the tiles touching [x0, x1) in rows [y0, y1) after their values changed.
    void refresh(int x0, int y0, int x1, int y1);
    Total total() const { return mTotal; }

private:
    int mWidth = 0, mHeight = 0, mTiles = 0;
    std::vector<double> mValues;
    std::vector<TileSum> mTileSums, mRowSums;
    Total mTotal = 0;
};
using FixedPooledMap = TiledMap<std::int64_t, SsimFixedTotal>;
using PooledMap = TiledMap<double, double>;

// --- SSIM ---------------------------------------------------------------------------------

// Processing block of the separable filter: at most kSsimBlockRows map rows by
// kSsimBlockColumns map columns. The vertical pass reads window rows of three quantities:
// 11 x 3 x 128 doubles = 33 KiB stay in a 48 KiB L1 (256 columns measured slower).
constexpr int kSsimBlockRows = 64;
constexpr int kSsimBlockColumns = 128;
// Windows are compared with the reference in cells of kSsimBlockRows x kSsimCellColumns.
constexpr int kSsimCellColumns = 64;
// Row bands of the live-window pass (parts): shorter, to skip more (chosen on the forest and
// harbor walks, docs/optimizer.md "The owned-window cache").
constexpr int kSsimLiveBandRows = 16;
constexpr int kSsimMaxWindow = 63;

// Everything the per-window computation needs; constants are in scaled gray units.
struct SsimKernel {
    int window = 11;  // effective (odd) window side
    int radius = 5;
    std::array<double, kSsimMaxWindow> weights{};  // normalised Gaussian, symmetric
    double c1 = 0, c2 = 0;                         // (K1 L scale)^2, (K2 L scale)^2
    int mapWidth = 0, mapHeight = 0;
};
SsimKernel makeSsimKernel(const MetricParameters& parameters, int width, int height, const GrayScale& gray);

// Working memory of the SSIM blocks, allocated once per kernel.
struct SsimScratch {
    int columns = 0;                      // widest block: min(kSsimBlockColumns, map width)
    std::vector<double> inX, inXX, inXY;  // one image row segment
    std::vector<double> hX, hXX, hXY;     // horizontal pass, block rows + window - 1 rows
    std::vector<double> vX, vXX, vXY;     // vertical pass, one map row segment
    void reserve(const SsimKernel& kernel);
};

// Reference statistics of map windows [mx0, mx1) x [my0, my1): mean and population variance
// (E[y^2] - mean^2) of gray `grayY` (image rows `grayStride` values apart). `mean` and
// `variance` point at the element for (mx0, my0); rows are `statStride` apart.
void ssimReferenceStatistics(const std::int32_t* grayY, std::size_t grayStride, const SsimKernel& kernel, int mx0,
                             int my0, int mx1, int my1, SsimScratch& scratch, double* mean, double* variance,
                             std::size_t statStride);

// SSIM of windows [mx0, mx1) x [my0, my1) of gray `grayX` against `grayY`, whose statistics
// `mean`/`variance` (as above, pointing at (mx0, my0)) were computed by
// ssimReferenceStatistics. `map` points at (mx0, my0), rows `mapStride` apart.
// With `liveOnly`, only windows that read several of its parts are computed (the others keep
// their map values: the caller sets owned windows from the cache).
void ssimWindows(const std::int32_t* grayX, const std::int32_t* grayY, std::size_t grayStride, const SsimKernel& kernel,
                 int mx0, int my0, int mx1, int my1, const double* mean, const double* variance, std::size_t statStride,
                 SsimScratch& scratch, double* map, std::size_t mapStride, const PartCache* liveOnly = nullptr);

// --- Entropies ----------------------------------------------------------------------------

// Shannon entropy in bits of `bins` counts summing to `total` (0 for an empty histogram),
// clamped to [0, log2 bins].
double histogramEntropy(const std::uint64_t* counts, int bins, std::uint64_t total);

// Sobel bins of interior pixels: magnitude sqrt(gx^2 + gy^2) of the 3x3 Sobel operator on
// scaled gray, mapped linearly from [0, 255 sqrt(20) scale] onto `bins` bins (the top value
// goes into the last bin).
struct SobelBinning {
    int bins = 256;
    double scale = 0;  // bins / (255 sqrt(20) grayScale)
};
SobelBinning makeSobelBinning(int bins, const GrayScale& gray);
// Bins of `count` consecutive interior pixels starting at `center` (gray rows `stride` apart).
void sobelBinsRow(const std::int32_t* center, std::ptrdiff_t stride, int count, const SobelBinning& binning,
                  std::uint16_t* out);

// Histogram changes accumulated in interleaved lanes, then merged: consecutive pixels hit
// different copies, which breaks the store-to-load chain that runs of equal values (a flat
// background) would otherwise form on one counter. Integer counts: the order is irrelevant.
class LaneHistogram {
public:
    void resize(int bins);
    // Counts (+1 or -1 each) of `count` consecutive pixels' bins.
    template <class Bin>
    void addRow(const Bin* bins, int count, std::int64_t delta) {
        std::int64_t* lane0 = mLanes.data();
        if (mLaneCount == 1) {
            for (int i = 0; i < count; ++i) lane0[bins[i]] += delta;
            return;
        }
        std::int64_t* lane1 = lane0 + mBins;
        std::int64_t* lane2 = lane1 + mBins;
        std::int64_t* lane3 = lane2 + mBins;
        int i = 0;
        for (; i + 4 <= count; i += 4) {
            lane0[bins[i]] += delta;
            lane1[bins[i + 1]] += delta;
            lane2[bins[i + 2]] += delta;
            lane3[bins[i + 3]] += delta;
        }
        for (; i < count; ++i) lane0[bins[i]] += delta;
    }
    // histogram[b] += sum of the lanes' changes to b; the lanes return to zero.
    void mergeInto(std::uint64_t* histogram);

private:
    int mBins = 0, mLaneCount = 1;  // lane count: a power of two
    std::vector<std::int64_t> mLanes;
};

// GAPSO15 eq. (3)-(4) term -g log2 g of the Roberts cross at `p` (needs p's right and lower
// neighbours), g in gray levels.
inline double robertsTerm(const std::int32_t* p, std::ptrdiff_t stride, double inverseScale) {
    const double a = double(p[0] - p[stride + 1]);
    const double b = double(p[stride] - p[1]);
    const double g = std::sqrt(a * a + b * b) * inverseScale;
    return g > 0 ? -g * std::log2(g) : 0.0;
}

// GAPSO15 eq. (5)-(6) with p = x / S: H = log2 S - (sum x log2 x) / S. The per-pixel term
// x log2 x uses scaled gray; the entropy is scale-free.
inline double intensityTerm(std::int32_t scaledGray) {
    return scaledGray > 0 ? double(scaledGray) * std::log2(double(scaledGray)) : 0.0;
}
double intensityShareEntropy(std::int64_t intensitySum, double termSum, std::uint64_t pixelCount);

// --- Precision / recall -------------------------------------------------------------------

enum PixelClass : std::uint8_t { kTruePositive = 1, kFalsePositive = 2, kFalseNegative = 4 };

struct CoverageRule {
    int channels = 4;
    std::array<std::uint8_t, 4> background{};  // gray images: background[0] = its gray
    int tolerance = 8;
};
CoverageRule makeCoverageRule(const MetricParameters& parameters, int channels, const GrayScale& gray);

// PixelClass bits of `count` pixels (interleaved, rule.channels bytes each).
void classifyRow(const std::uint8_t* candidate, const std::uint8_t* reference, int count, const CoverageRule& rule,
                 std::uint8_t* out);

}  // namespace lodopt::metrics::detail
