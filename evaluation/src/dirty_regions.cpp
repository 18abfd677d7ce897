// Dirty-rectangle merging for the fast evaluation path.
#include "dirty_regions.hpp"

#include <algorithm>
#include <cstddef>

namespace lodopt::evaluation::detail {

namespace {

bool overlaps(const renderer::PixelRect& a, const renderer::PixelRect& b) {
    return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1;
}

void uniteAll(std::vector<renderer::PixelRect>& rects) {
    for (std::size_t i = 1; i < rects.size(); ++i) rects[0] = unite(rects[0], rects[i]);
    rects.resize(1);
}

// Merges some pair i < j that `shouldMerge` accepts into i; false when no pair qualifies.
template <typename Predicate>
bool mergeOnePair(std::vector<renderer::PixelRect>& rects, Predicate shouldMerge) {
    for (std::size_t i = 0; i < rects.size(); ++i) {
        for (std::size_t j = i + 1; j < rects.size(); ++j) {
            if (!shouldMerge(rects[i], rects[j])) continue;
            rects[i] = unite(rects[i], rects[j]);
            rects.erase(rects.begin() + std::ptrdiff_t(j));
            return true;
        }
    }
    return false;
}

// Past this many rectangles the pairwise search costs more than it can save.
constexpr std::size_t kPairwiseLimit = 32;
// How many of the last kept rectangles the first merging pass tries.
constexpr std::size_t kLookBack = 6;

}  // namespace

renderer::PixelRect unite(const renderer::PixelRect& a, const renderer::PixelRect& b) {
    if (a.empty()) return b;
    if (b.empty()) return a;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

void mergeOverlapping(std::vector<renderer::PixelRect>& rects) {
    if (rects.size() > kPairwiseLimit) {  // many changes: one bounding rectangle is cheaper than the merge
        uniteAll(rects);
        return;
    }
    while (mergeOnePair(rects, overlaps)) {
    }
}

std::uint64_t UpdateCostModel::cost(const renderer::PixelRect& rect) const {
    if (rect.empty()) return 0;
    return std::uint64_t(rect.width() + ssimReach) * std::uint64_t(rect.height() + ssimReach) +
           std::uint64_t(callOverhead);
}

void mergeCheaper(std::vector<renderer::PixelRect>& rects, const UpdateCostModel& model) {
    auto cheaperTogether = [&](const renderer::PixelRect& a, const renderer::PixelRect& b) {
        return model.cost(unite(a, b)) <= model.cost(a) + model.cost(b);
    };
    // One pass first, each rectangle against the last few kept: the composite reports bands
    // top to bottom and clusters left to right, so a cluster's neighbour above is among them.
    std::size_t kept = 0;
    for (std::size_t i = 0; i < rects.size(); ++i) {
        bool merged = false;
        for (std::size_t j = kept; j > 0 && j + kLookBack > kept && !merged; --j) {
            merged = cheaperTogether(rects[j - 1], rects[i]);
            if (merged) rects[j - 1] = unite(rects[j - 1], rects[i]);
        }
        if (!merged) rects[kept++] = rects[i];
    }
    rects.resize(kept);
    if (rects.size() > kPairwiseLimit) return;  // overlaps only cost time, never exactness
    while (mergeOnePair(rects, cheaperTogether)) {
    }
}

}  // namespace lodopt::evaluation::detail
