// SSIM: Wang, Bovik, Sheikh, Simoncelli, "Image quality assessment: from error visibility to
// structural similarity", IEEE TIP 13(4), 2004, eq. (13) with C3 = C2 / 2:
//   SSIM = (2 mx my + C1)(2 sxy + C2) / ((mx^2 + my^2 + C1)(sx^2 + sy^2 + C2)),
// local statistics weighted by a separable, normalised Gaussian window, over the windows
// lying fully inside the image (no padding), pooled by the mean.
//
// Why float64 with exact integer gray: float32 statistics miss a float64 computation by up
// to 1.5e-5 in mean SSIM on bright images (E[x^2] - mean^2 cancels); scaled integer gray
// makes x, x^2 and x y exact, so the only rounding is in the weighted sums.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>

#include "kernels.hpp"
#include "parts.hpp"

namespace lodopt::metrics {
namespace detail {

SsimKernel makeSsimKernel(const MetricParameters& parameters, int width, int height, const GrayScale& gray) {
    SsimKernel kernel;
    // Images smaller than the window get the largest odd window that fits (1x1 at least).
    int fits = std::min(width, height);
    if (fits % 2 == 0) --fits;
    kernel.window = std::max(1, std::min(parameters.ssimWindow, fits));
    kernel.radius = kernel.window / 2;
    // Same construction as scipy.ndimage's Gaussian kernel: exp(-x^2 / (2 sigma^2)) / sum.
    double sum = 0;
    for (int k = 0; k < kernel.window; ++k) {
        const double x = k - kernel.radius;
        kernel.weights[k] = std::exp(-0.5 / (parameters.ssimSigma * parameters.ssimSigma) * x * x);
        sum += kernel.weights[k];
    }
    for (int k = 0; k < kernel.window; ++k) kernel.weights[k] /= sum;
    // Statistics are in scaled gray units, so the constants are scaled by scale^2.
    const double range = parameters.ssimDynamicRange * gray.scale;
    kernel.c1 = (parameters.ssimK1 * range) * (parameters.ssimK1 * range);
    kernel.c2 = (parameters.ssimK2 * range) * (parameters.ssimK2 * range);
    kernel.mapWidth = width - kernel.window + 1;
    kernel.mapHeight = height - kernel.window + 1;
    return kernel;
}

void SsimScratch::reserve(const SsimKernel& kernel) {
    // Sized for the largest block this kernel's map can have: small images get small buffers.
    columns = std::min(kSsimBlockColumns, kernel.mapWidth);
    const int rows = std::min(kSsimBlockRows, kernel.mapHeight);
    const std::size_t in = std::size_t(columns + kernel.window - 1);
    const std::size_t horizontal = std::size_t(rows + kernel.window - 1) * columns;
    for (auto* v : {&inX, &inXX, &inXY}) v->assign(in, 0.0);
    for (auto* v : {&hX, &hXX, &hXY}) v->assign(horizontal, 0.0);
    for (auto* v : {&vX, &vXX, &vXY}) v->assign(std::size_t(columns), 0.0);
}

namespace {

// out[j] = sum_k w[k] in[j + k], as w[r] in[j + r] + sum_{k = r-1..0} w[k] (in[j+k] + in[j+2r-k]).
// Every element follows this order whatever `count` is, so a sub-range gives the same bits.
template <int R>
LODOPT_METRICS_INLINE void convolveFixed(const double* __restrict in, int count, const double* __restrict w,
                                         double* __restrict out) {
    for (int j = 0; j < count; ++j) {
        const double* p = in + j;
        double s = w[R] * p[R];
        for (int k = R - 1; k >= 0; --k) s += w[k] * (p[k] + p[2 * R - k]);
        out[j] = s;
    }
}

LODOPT_METRICS_INLINE void convolveAny(const double* __restrict in, int count, int radius, const double* __restrict w,
                                       double* __restrict out) {
    for (int j = 0; j < count; ++j) {
        const double* p = in + j;
        double s = w[radius] * p[radius];
        for (int k = radius - 1; k >= 0; --k) s += w[k] * (p[k] + p[2 * radius - k]);
        out[j] = s;
    }
}

// Vertical pass: rows of `in` are `stride` apart; same order as the horizontal pass.
template <int R>
LODOPT_METRICS_INLINE void convolveColumnsFixed(const double* __restrict in, std::size_t stride, int count,
                                                const double* __restrict w, double* __restrict out) {
    for (int j = 0; j < count; ++j) {
        const double* p = in + j;
        double s = w[R] * p[R * stride];
        for (int k = R - 1; k >= 0; --k) s += w[k] * (p[k * stride] + p[(2 * R - k) * stride]);
        out[j] = s;
    }
}

LODOPT_METRICS_INLINE void convolveColumnsAny(const double* __restrict in, std::size_t stride, int count, int radius,
                                              const double* __restrict w, double* __restrict out) {
    for (int j = 0; j < count; ++j) {
        const double* p = in + j;
        double s = w[radius] * p[radius * stride];
        for (int k = radius - 1; k >= 0; --k) s += w[k] * (p[k * stride] + p[(2 * radius - k) * stride]);
        out[j] = s;
    }
}

// The default 11x11 window gets an unrolled, vectorised path; other sizes the generic one.
constexpr int kDefaultRadius = 5;

LODOPT_METRICS_INLINE void convolve(const SsimKernel& kernel, const double* in, int count, double* out) {
    if (kernel.radius == kDefaultRadius) {
        convolveFixed<kDefaultRadius>(in, count, kernel.weights.data(), out);
    } else {
        convolveAny(in, count, kernel.radius, kernel.weights.data(), out);
    }
}

LODOPT_METRICS_INLINE void convolveColumns(const SsimKernel& kernel, const double* in, std::size_t stride, int count,
                                           double* out) {
    if (kernel.radius == kDefaultRadius) {
        convolveColumnsFixed<kDefaultRadius>(in, stride, count, kernel.weights.data(), out);
    } else {
        convolveColumnsAny(in, stride, count, kernel.radius, kernel.weights.data(), out);
    }
}

// One map row segment from the candidate's window sums and the reference's statistics.
// vx is computed as E[x^2] - mx^2 exactly like the reference's variance, so identical
// images give numerator == denominator and SSIM exactly 1.
LODOPT_METRICS_INLINE void ssimRow(const double* __restrict meanX, const double* __restrict squareX,
                                   const double* __restrict productXY, const double* __restrict meanY,
                                   const double* __restrict varianceY, int count, double c1, double c2,
                                   double* __restrict out) {
    for (int j = 0; j < count; ++j) {
        const double mx = meanX[j], my = meanY[j];
        const double varianceX = squareX[j] - mx * mx;
        const double covariance = productXY[j] - mx * my;
        const double numerator = (2 * mx * my + c1) * (2 * covariance + c2);
        const double denominator = (mx * mx + my * my + c1) * (varianceX + varianceY[j] + c2);
        const double s = numerator / denominator;
        out[j] = s > 1.0 ? 1.0 : (s < -1.0 ? -1.0 : s);
    }
}

// One block of map windows [bx, bx + columns) x [by, by + rows): the horizontal pass over
// rows + window - 1 image rows, then the vertical pass and the per-row output.
struct Block {
    int bx = 0, by = 0, columns = 0, rows = 0;
};

// Reference: mean and E[y^2] - mean^2; `mean`/`variance` point at the block's first window.
LODOPT_METRICS_CLONES void referenceBlock(const SsimKernel& kernel, SsimScratch& scratch, const std::int32_t* grayY,
                                          std::size_t grayStride, Block block, double* mean, double* variance,
                                          std::size_t statStride) {
    const int inputs = block.columns + kernel.window - 1;
    const std::size_t stride = std::size_t(scratch.columns);
    double* __restrict inX = scratch.inX.data();
    double* __restrict inXX = scratch.inXX.data();
    for (int r = 0; r < block.rows + kernel.window - 1; ++r) {
        const std::int32_t* y = grayY + std::size_t(block.by + r) * grayStride + block.bx;
        for (int c = 0; c < inputs; ++c) {
            const double v = y[c];
            inX[c] = v;
            inXX[c] = v * v;
        }
        convolve(kernel, inX, block.columns, scratch.hX.data() + r * stride);
        convolve(kernel, inXX, block.columns, scratch.hXX.data() + r * stride);
    }
    for (int i = 0; i < block.rows; ++i) {
        convolveColumns(kernel, scratch.hX.data() + i * stride, stride, block.columns, scratch.vX.data());
        convolveColumns(kernel, scratch.hXX.data() + i * stride, stride, block.columns, scratch.vXX.data());
        double* __restrict m = mean + std::size_t(i) * statStride;
        double* __restrict v = variance + std::size_t(i) * statStride;
        const double* __restrict vx = scratch.vX.data();
        const double* __restrict vxx = scratch.vXX.data();
        for (int j = 0; j < block.columns; ++j) {
            m[j] = vx[j];
            v[j] = vxx[j] - vx[j] * vx[j];
        }
    }
}

// Candidate: window sums of x, x^2 and x y, then SSIM against the reference statistics.
LODOPT_METRICS_CLONES void candidateBlock(const SsimKernel& kernel, SsimScratch& scratch, const std::int32_t* grayX,
                                          const std::int32_t* grayY, std::size_t grayStride, Block block,
                                          const double* mean, const double* variance, std::size_t statStride,
                                          double* map, std::size_t mapStride) {
    const int inputs = block.columns + kernel.window - 1;
    const std::size_t stride = std::size_t(scratch.columns);
    double* __restrict inX = scratch.inX.data();
    double* __restrict inXX = scratch.inXX.data();
    double* __restrict inXY = scratch.inXY.data();
    for (int r = 0; r < block.rows + kernel.window - 1; ++r) {
        const std::size_t at = std::size_t(block.by + r) * grayStride + block.bx;
        const std::int32_t* __restrict x = grayX + at;
        const std::int32_t* __restrict y = grayY + at;
        for (int c = 0; c < inputs; ++c) {
            const double vx = x[c];
            inX[c] = vx;
            inXX[c] = vx * vx;
            inXY[c] = vx * double(y[c]);
        }
        convolve(kernel, inX, block.columns, scratch.hX.data() + r * stride);
        convolve(kernel, inXX, block.columns, scratch.hXX.data() + r * stride);
        convolve(kernel, inXY, block.columns, scratch.hXY.data() + r * stride);
    }
    for (int i = 0; i < block.rows; ++i) {
        convolveColumns(kernel, scratch.hX.data() + i * stride, stride, block.columns, scratch.vX.data());
        convolveColumns(kernel, scratch.hXX.data() + i * stride, stride, block.columns, scratch.vXX.data());
        convolveColumns(kernel, scratch.hXY.data() + i * stride, stride, block.columns, scratch.vXY.data());
        ssimRow(scratch.vX.data(), scratch.vXX.data(), scratch.vXY.data(), mean + std::size_t(i) * statStride,
                variance + std::size_t(i) * statStride, block.columns, kernel.c1, kernel.c2,
                map + std::size_t(i) * mapStride);
    }
}

}  // namespace

void ssimReferenceStatistics(const std::int32_t* grayY, std::size_t grayStride, const SsimKernel& kernel, int mx0,
                             int my0, int mx1, int my1, SsimScratch& scratch, double* mean, double* variance,
                             std::size_t statStride) {
    assert(mx0 >= 0 && my0 >= 0 && mx1 <= kernel.mapWidth && my1 <= kernel.mapHeight);
    for (int by = my0; by < my1; by += kSsimBlockRows) {
        for (int bx = mx0; bx < mx1; bx += kSsimBlockColumns) {
            const Block block{bx, by, std::min(kSsimBlockColumns, mx1 - bx), std::min(kSsimBlockRows, my1 - by)};
            const std::size_t at = std::size_t(by - my0) * statStride + std::size_t(bx - mx0);
            referenceBlock(kernel, scratch, grayY, grayStride, block, mean + at, variance + at, statStride);
        }
    }
}

namespace {

// True when the candidate's and the reference's gray are equal over the inputs of map windows
// [cx, cx + columns) x [cy, cy + rows).
bool inputsEqual(const std::int32_t* grayX, const std::int32_t* grayY, std::size_t grayStride,
                 const SsimKernel& kernel, int cx, int cy, int columns, int rows) {
    const std::size_t bytes = std::size_t(columns + kernel.window - 1) * sizeof(std::int32_t);
    for (int r = 0; r < rows + kernel.window - 1; ++r) {
        const std::size_t at = std::size_t(cy + r) * grayStride + std::size_t(cx);
        if (std::memcmp(grayX + at, grayY + at, bytes) != 0) return false;
    }
    return true;
}

// The first value v in [lo, hi) with has(v), given that has is false below some value and true
// from it on, and true at hi - 1 at least.
template <class Predicate>
int firstWith(int lo, int hi, Predicate has) {
    while (lo + 1 < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (has(mid - 1)) hi = mid; else lo = mid;
    }
    return lo;
}

// The smallest sub-block of `block` holding all its live windows (it holds at least one):
// the horizontal pass then covers only those rows and columns. Binary searches on the
// summed-area table, each bound against the ones found before it.
Block trimToLive(const PartCache& live, Block block) {
    int x0 = block.bx, x1 = block.bx + block.columns, y0 = block.by, y1 = block.by + block.rows;
    y0 = firstWith(y0, y1, [&](int r) { return live.liveWindows(x0, y0, x1, r + 1) > 0; });
    // The last row: the first r (counting down from y1) with live windows in [r, y1).
    y1 = y1 - firstWith(0, y1 - y0, [&](int k) { return live.liveWindows(x0, y1 - 1 - k, x1, y1) > 0; });
    x0 = firstWith(x0, x1, [&](int c) { return live.liveWindows(x0, y0, c + 1, y1) > 0; });
    x1 = x1 - firstWith(0, x1 - x0, [&](int k) { return live.liveWindows(x1 - 1 - k, y0, x1, y1) > 0; });
    return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace

void ssimWindows(const std::int32_t* grayX, const std::int32_t* grayY, std::size_t grayStride,
                 const SsimKernel& kernel, int mx0, int my0, int mx1, int my1, const double* mean,
                 const double* variance, std::size_t statStride, SsimScratch& scratch, double* map,
                 std::size_t mapStride, const PartCache* liveOnly) {
    assert(mx0 >= 0 && my0 >= 0 && mx1 <= kernel.mapWidth && my1 <= kernel.mapHeight);
    // Windows whose inputs equal the reference's are exactly 1 without computing them: their
    // sums are the reference's bit for bit (same code, same inputs; x y = x x), so the
    // numerator equals the denominator. Renders share most of their background with the
    // reference, so cells of kSsimCellColumns windows are tested and the differing ones are
    // computed in runs of up to kSsimBlockColumns.
    // With parts, bands of fewer rows: a band without a window reading two parts is skipped
    // whole, and those windows lie in thin seams between objects.
    const int bandRows = liveOnly ? kSsimLiveBandRows : kSsimBlockRows;
    for (int by = my0; by < my1; by += bandRows) {
        const int rows = std::min(bandRows, my1 - by);
        const std::size_t out = std::size_t(by - my0) * mapStride;
        int runStart = mx0, runEnd = mx0;  // pending differing cells [runStart, runEnd)
        auto flush = [&] {
            if (runEnd <= runStart) return;
            Block block{runStart, by, runEnd - runStart, rows};
            if (liveOnly) block = trimToLive(*liveOnly, block);
            const std::size_t at = std::size_t(block.by - my0) * statStride + std::size_t(block.bx - mx0);
            const std::size_t mapAt = std::size_t(block.by - my0) * mapStride + std::size_t(block.bx - mx0);
            candidateBlock(kernel, scratch, grayX, grayY, grayStride, block, mean + at, variance + at, statStride,
                           map + mapAt, mapStride);
        };
        for (int cx = mx0; cx < mx1; cx += kSsimCellColumns) {
            const int columns = std::min(kSsimCellColumns, mx1 - cx);
            if (liveOnly && liveOnly->liveWindows(cx, by, cx + columns, by + rows) == 0) {
                flush();  // nothing here reads two parts: owned windows come from the cache
                runStart = runEnd = cx + columns;
                continue;
            }
            if (inputsEqual(grayX, grayY, grayStride, kernel, cx, by, columns, rows)) {
                flush();
                runStart = runEnd = cx + columns;
                for (int i = 0; i < rows; ++i) {
                    std::fill_n(map + out + std::size_t(i) * mapStride + std::size_t(cx - mx0), columns, 1.0);
                }
                continue;
            }
            if (runEnd - runStart + columns > kSsimBlockColumns) {
                flush();
                runStart = cx;
            }
            runEnd = cx + columns;
        }
        flush();
    }
}

}  // namespace detail

SsimMapSize ssimMapSize(int width, int height, const MetricParameters& parameters) {
    validateParameters(parameters);
    if (width < 1 || height < 1) {
        throw MetricError("image size " + std::to_string(width) + "x" + std::to_string(height) + " has no pixels");
    }
    const detail::SsimKernel kernel =
        detail::makeSsimKernel(parameters, width, height, detail::grayScale(parameters.grayWeights));
    return {kernel.mapWidth, kernel.mapHeight, kernel.window};
}

void ssimMap(const ImageView& candidate, const ImageView& reference, const MetricParameters& parameters,
             double* map, std::size_t mapStride) {
    validateParameters(parameters);
    detail::validatePair(candidate, reference);
    const detail::GrayScale gray = detail::grayScale(parameters.grayWeights);
    const detail::SsimKernel kernel = detail::makeSsimKernel(parameters, candidate.width, candidate.height, gray);
    assert(map != nullptr && mapStride >= std::size_t(kernel.mapWidth));
    std::vector<std::int32_t> grayX, grayY;
    detail::grayImage(candidate, gray, grayX);
    detail::grayImage(reference, gray, grayY);
    detail::SsimScratch scratch;
    scratch.reserve(kernel);
    // Reference statistics one band of rows at a time, so memory stays O(width).
    const std::size_t statStride = std::size_t(kernel.mapWidth);
    std::vector<double> mean(statStride * detail::kSsimBlockRows), variance(mean.size());
    const std::size_t grayStride = std::size_t(candidate.width);
    for (int y0 = 0; y0 < kernel.mapHeight; y0 += detail::kSsimBlockRows) {
        const int y1 = std::min(kernel.mapHeight, y0 + detail::kSsimBlockRows);
        detail::ssimReferenceStatistics(grayY.data(), grayStride, kernel, 0, y0, kernel.mapWidth, y1, scratch,
                                        mean.data(), variance.data(), statStride);
        detail::ssimWindows(grayX.data(), grayY.data(), grayStride, kernel, 0, y0, kernel.mapWidth, y1, mean.data(),
                            variance.data(), statStride, scratch, map + std::size_t(y0) * mapStride, mapStride);
    }
}

double poolMean(const double* map, int width, int height, std::size_t mapStride) {
    assert(map != nullptr && width >= 1 && height >= 1 && mapStride >= std::size_t(width));
    detail::SsimFixedTotal total = 0;
    for (int y = 0; y < height; ++y) total += detail::ssimFixedSum(map + std::size_t(y) * mapStride, width);
    return detail::ssimMeanFromFixed(total, std::uint64_t(width) * std::uint64_t(height));
}

double ssim(const ImageView& candidate, const ImageView& reference, const MetricParameters& parameters) {
    validateParameters(parameters);
    detail::validatePair(candidate, reference);
    const SsimMapSize size = ssimMapSize(candidate.width, candidate.height, parameters);
    std::vector<double> map(std::size_t(size.width) * size.height);
    ssimMap(candidate, reference, parameters, map.data(), std::size_t(size.width));
    return poolMean(map.data(), size.width, size.height, std::size_t(size.width));
}

}  // namespace lodopt::metrics
