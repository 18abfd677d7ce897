// Incremental evaluation of many candidates against one reference.
//
// An optimizer's candidates usually differ from the previously evaluated image only inside
// the screen rectangles of a few objects. The evaluator keeps the reference statistics
// (gray image, per-window mean and variance, entropies) and the candidate's state (gray
// image, SSIM map with its tile and row sums, per-pixel Sobel bins and the two histograms,
// per-pixel precision/recall classes with their counts). updateRect recomputes only what a
// changed rectangle can reach: the SSIM windows overlapping it, the Sobel pixels within one
// pixel of it, the histogram entries and classes inside it.
//
// Exactness: every per-pixel value is computed by the same code in the full and the
// incremental path, histograms and counts are integers, and the SSIM map is pooled in fixed
// point (exact integer sums; the paper's real-valued entropy terms per tile and row in a fixed
// order), so after any sequence of updates result() equals a from-scratch evaluate() of the
// final image (to the bit, and tested to 1e-9).
//
// Memory: about 40 bytes per pixel with every component on (SSIM alone: 32). No allocation
// after construction: setCandidate, updateRect and result never allocate. One evaluator is
// not safe to use from two threads at once; use one per thread.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "metrics/metrics.hpp"

namespace lodopt::metrics {

// --- Parts: windows that depend on one part of the image only -----------------------------
//
// A caller whose image is made of parts that change independently (the fast path: one part
// per searched object, whose state is its level) can declare which part each pixel depends
// on. A window (an SSIM window, a Sobel 3x3 neighbourhood, a pixel of the gray histogram) that
// reads only pixels of one part k and pixels that never change is *owned* by k: its value is a
// function of k's state alone. The evaluator then never recomputes owned windows in an
// update: the first time part k is seen in state s, its owned SSIM values and its owned
// pixels' gray and Sobel histograms are computed and kept in a PartCache; afterwards a move of
// k to s copies the values and swaps the histogram counts. Only windows that read several
// parts are computed per update. Every value, cached or live, comes from the same kernels as
// a from-scratch evaluation, so results stay bit-identical to evaluate().
//
// A PartCache is shared by every evaluator of one reference, size and parameter set (the fast
// path's states): entries are filled once, by whichever evaluator needs one first, under a
// per-entry once_flag, so evaluators on several threads may share it.

// pixelParts values besides a part index.
constexpr std::int32_t kConstantPixel = -1;  // no part's state ever changes this pixel
constexpr std::int32_t kSharedPixel = -2;    // several parts' states may change it

class PartCache;

// Analyses the partition (window ownership for the metrics `parameters` compute) and reserves
// the entries: `pixelParts` has width * height values (rows packed), each kConstantPixel,
// kSharedPixel or a part index in [0, stateCounts.size()); part k has stateCounts[k] >= 1
// states. Throws MetricError on a bad size or value. Memory: 8 bytes per owned SSIM window per
// state, plus two histograms per part and state.
std::shared_ptr<PartCache> makePartCache(int width, int height, const MetricParameters& parameters,
                                         std::span<const std::int32_t> pixelParts, std::span<const int> stateCounts);

// Statistics of a cache, for reports and tests.
struct PartCacheStats {
    int parts = 0;
    std::uint64_t entries = 0, filledEntries = 0;
    std::uint64_t ownedSsimWindows = 0, liveSsimWindows = 0;  // owned by a part, reading several
    std::uint64_t ownedPixels = 0;                             // gray histogram pixels owned
    std::uint64_t bytes = 0;
};
PartCacheStats partCacheStats(const PartCache& cache);

// A part's new state in IncrementalEvaluator::update.
struct PartMove {
    int part = 0;
    int state = 0;
};

// A pixel rectangle [x0, x1) x [y0, y1).
struct UpdateRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

class IncrementalEvaluator {
public:
    // Copies what it needs of `reference` (validated; throws MetricError) and validates
    // `parameters`. The initial candidate is the reference itself (fitness 1).
    IncrementalEvaluator(const ImageView& reference, const MetricParameters& parameters);
    ~IncrementalEvaluator();
    IncrementalEvaluator(IncrementalEvaluator&&) noexcept;
    IncrementalEvaluator& operator=(IncrementalEvaluator&&) noexcept;
    IncrementalEvaluator(const IncrementalEvaluator&) = delete;
    IncrementalEvaluator& operator=(const IncrementalEvaluator&) = delete;

    // Replaces the whole candidate. `candidate` has the reference's size and channel count
    // (else MetricError).
    void setCandidate(const ImageView& candidate);

    // The candidate changed only inside [x0, x1) x [y0, y1) (pixels, top-left origin);
    // `candidate` is the whole new image and must equal the previous one outside the
    // rectangle (not checked: that is the caller's promise). The rectangle is clipped to the
    // image; an empty one changes nothing.
    void updateRect(const ImageView& candidate, int x0, int y0, int x1, int y1);

    // Declares the parts (see PartCache above): the current candidate must be the image of
    // the parts in `states` (one per part; the caller's promise). From now on use update();
    // setCandidate drops the parts. Precision/recall, and the paper's entropy forms, are kept
    // per pixel as before (only SSIM and the histogram entropies use the cache).
    void setParts(std::shared_ptr<PartCache> cache, const ImageView& candidate, std::span<const int> states);
    bool hasParts() const;
    // The candidate changed only inside `rects` (every changed pixel in one of them; they may
    // overlap and are clipped) and the parts in `moves` are now in the given states. Without
    // parts, `moves` must be empty and this is updateRect for each rectangle. A part listed
    // twice ends in its last listed state.
    void update(const ImageView& candidate, std::span<const UpdateRect> rects, std::span<const PartMove> moves);

    // Every computed component of the current candidate, its fidelities and the fitness.
    MetricResult result() const;

    const MetricParameters& parameters() const;
    int width() const;
    int height() const;
    int channels() const;
    // The candidate's SSIM map (ssimMapSize(width(), height(), parameters()) values, rows
    // packed), or nullptr when SSIM is not computed.
    const double* ssimMap() const;
    SsimMapSize ssimMapSize() const;

private:
    struct State;
    std::unique_ptr<State> mState;
};

}  // namespace lodopt::metrics
