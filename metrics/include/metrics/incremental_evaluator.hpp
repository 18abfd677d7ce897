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
// incremental path, histograms and counts are integers, and map sums are re-pooled per tile
// and row in a fixed order, so after any sequence of updates result() equals a from-scratch
// evaluate() of the final image (to the bit, and tested to 1e-9).
//
// Memory: about 40 bytes per pixel with every component on (SSIM alone: 32). No allocation
// after construction: setCandidate, updateRect and result never allocate. One evaluator is
// not safe to use from two threads at once; use one per thread.
#pragma once

#include <memory>

#include "metrics/metrics.hpp"

namespace lodopt::metrics {

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
