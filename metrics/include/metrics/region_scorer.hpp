// Scores of sets of windows that add up to the whole image's metrics.
//
// Every metric the fused fitness uses in its default form is a sum over windows: SSIM is the
// mean of per-window values (pooled in fixed point, so sums are exact and order-free), and
// both entropies are functions of histograms, which are sums of per-pixel counts. A caller
// that knows which windows depend on which of its parts (the fast path: each window's value
// is a function of the levels of the objects whose layers reach it) can score each set of
// windows on its own, keep the score, and later add up the kept scores of a partition of
// every window and pixel. result() of those totals equals a from-scratch evaluate() of the
// whole image to the bit: per-window values come from the same kernels, and all sums are
// integers.
//
// Covered: SSIM and the two entropies in histogram form, without precision/recall
// (supports()). The paper's entropy forms are real-valued per-pixel sums and stay with
// IncrementalEvaluator.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "metrics/metrics.hpp"

namespace lodopt::metrics {

// Exact fixed-point SSIM sums: each window counts round(v * 2^40); a 65536^2 image has 2^32
// windows, so totals need more than 64 bits.
__extension__ typedef __int128 SsimFixedSum;

// A run of windows or pixels on one row: [x0, x1) on row y.
struct WindowRun {
    int y = 0, x0 = 0, x1 = 0;
};

// A set of windows: SSIM map windows (map coordinates), pixels of the gray histogram and
// interior pixels of the Sobel histogram (image coordinates). Runs sorted by row, then column.
struct WindowSet {
    std::vector<WindowRun> ssim, gray, sobel;
};

// A nonzero histogram count: (bin, count).
using BinCount = std::pair<std::uint16_t, std::uint32_t>;

// A set's score: the SSIM windows' fixed-point sum and the nonzero histogram counts.
struct WindowSetScore {
    SsimFixedSum ssim = 0;
    std::vector<BinCount> gray, sobel;
    std::size_t bytes() const { return sizeof(*this) + (gray.capacity() + sobel.capacity()) * sizeof(gray[0]); }
};

// The sum of the scores of disjoint sets.
struct WindowTotals {
    SsimFixedSum ssim = 0;
    std::vector<std::int64_t> gray, sobel;
    // Adds (sign +1) or removes (sign -1) a score.
    void add(const WindowSetScore& score, int sign) { add(score.ssim, score.gray, score.sobel, sign); }
    // The same from a score kept elsewhere (a caller's packed copy).
    void add(SsimFixedSum setSsim, std::span<const BinCount> setGray, std::span<const BinCount> setSobel, int sign);
};

class RegionScorer {
public:
    // True when every fused component of `parameters` is a sum over windows (see above).
    static bool supports(const MetricParameters& parameters);

    // Copies what it needs of `reference` (validated; throws MetricError, also when
    // !supports(parameters)).
    RegionScorer(const ImageView& reference, const MetricParameters& parameters);
    ~RegionScorer();
    RegionScorer(RegionScorer&&) noexcept;
    RegionScorer& operator=(RegionScorer&&) noexcept;

    // Working memory of one thread: the candidate's gray image as loadPixels last wrote it,
    // and scratch. About 4 bytes per pixel plus a band of the SSIM map.
    class Work;
    struct WorkDeleter {
        void operator()(Work* work) const;
    };
    using WorkPtr = std::unique_ptr<Work, WorkDeleter>;
    WorkPtr makeWork() const;

    // Loads the pixels of [x0, x1) x [y0, y1) of `candidate` (the reference's size and
    // channel count) into `work`.
    void loadPixels(Work& work, const ImageView& candidate, int x0, int y0, int x1, int y1) const;
    // Scores `set` from the gray values in `work`, which must be loaded over every pixel the
    // set's windows read (SSIM: the window; Sobel: the 3x3 neighbourhood).
    void score(Work& work, const WindowSet& set, WindowSetScore& out) const;
    // Scores several sets at once (outs[k] for sets[k]), the same values as score() gives each:
    // the SSIM windows of all of them are computed band by band in shared rectangles, so
    // windows of sets that interleave are not computed again for each set, nor the margin each
    // computed rectangle needs.
    void scoreMany(Work& work, std::span<const WindowSet* const> sets, std::span<WindowSetScore* const> outs) const;

    // Zero totals of the right histogram sizes.
    WindowTotals emptyTotals() const;
    // The metrics of an image whose every SSIM window, gray pixel and interior pixel is in
    // exactly one of the sets added to `totals` (the caller's promise).
    MetricResult result(const WindowTotals& totals) const;

    int width() const;
    int height() const;
    SsimMapSize ssimMapSize() const;  // width and height 0 when SSIM is not computed
    int sobelBins() const;            // 0 when the boundary entropy is not computed
    int grayBins() const;             // 256, or 0 when the information entropy is not computed

private:
    void histograms(Work& work, const WindowSet& set, WindowSetScore& out) const;
    struct State;
    std::unique_ptr<State> mState;
};

}  // namespace lodopt::metrics
