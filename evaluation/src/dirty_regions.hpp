// Which rectangles the fast path recomposites and re-scores after a level change.
//
// Recompositing works on the changed objects' bounding rectangles (every pixel that may have
// changed); re-scoring only on tight rectangles around the pixels that did change, merged
// where one update is cheaper than two. Any set of update rectangles that covers every
// changed pixel gives the same scores (the incremental metrics are bit-exact), so the merging
// below is purely a cost choice.
#pragma once

#include <cstdint>
#include <vector>

#include "renderer/renderer.hpp"

namespace lodopt::evaluation::detail {

renderer::PixelRect unite(const renderer::PixelRect& a, const renderer::PixelRect& b);

// Overlapping rectangles become their union, so no pixel is composited twice.
void mergeOverlapping(std::vector<renderer::PixelRect>& rects);

// What one IncrementalEvaluator::updateRect over a rectangle costs, in pixel-equivalents.
struct UpdateCostModel {
    int ssimReach = 10;       // SSIM window - 1: the windows reaching a pixel extend this far up and left
    int callOverhead = 400;   // re-pooling the map's rows and merging histograms, once per call
    std::uint64_t cost(const renderer::PixelRect& rect) const;
};

// Merges rectangles whose union costs no more to update than the two apart (nearby bands of
// one change, touching changes of two objects). The result still covers every input pixel.
void mergeCheaper(std::vector<renderer::PixelRect>& rects, const UpdateCostModel& model);

}  // namespace lodopt::evaluation::detail
