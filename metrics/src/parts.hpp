// PartCache internals (see incremental_evaluator.hpp for what parts are): the static analysis
// of which windows a part owns, and the per (part, state) entries the evaluators fill.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include "metrics/incremental_evaluator.hpp"

namespace lodopt::metrics {

// Which components a part cache covers for `parameters`: SSIM, and the two entropies in their
// histogram form (the paper's forms stay per pixel). makePartCache and setParts both use this.
struct PartCoverage {
    bool ssim = false, gray = false, sobel = false;
    bool operator==(const PartCoverage&) const = default;
};
inline PartCoverage partCoverage(const MetricParameters& parameters) {
    return {parameters.ssimWeight > 0,
            parameters.informationEntropyWeight > 0 && parameters.informationEntropyMode == EntropyMode::Histogram,
            parameters.boundaryEntropyWeight > 0 && parameters.boundaryEntropyMode == EntropyMode::Histogram};
}

class PartCache {
public:
    // A run of owned windows (or pixels) on one row: [x0, x1) on row y, map or image coordinates.
    struct Run {
        int y = 0, x0 = 0, x1 = 0;
    };
    struct Part {
        std::vector<Run> ssimRuns;  // owned SSIM windows, map coordinates, row-major
        UpdateRect ssimBounds;      // their bounding rectangle (map coordinates)
        std::size_t ssimWindows = 0;
        // Runs of map row ssimBounds.y0 + i: [ssimRowStart[i], ssimRowStart[i + 1]); the values
        // of run r start at ssimRunOffset[r] in an entry.
        std::vector<std::uint32_t> ssimRowStart, ssimRunOffset;
        std::vector<Run> grayRuns;   // owned pixels of the gray histogram
        std::vector<Run> sobelRuns;  // owned interior pixels of the Sobel histogram
    };
    // One (part, state): the owned SSIM values in run order and the owned pixels' histogram
    // counts, sparse (bin, count). Filled once, under `once`.
    struct Entry {
        std::vector<double> ssim;
        std::vector<std::pair<std::uint32_t, std::int64_t>> gray, sobel;
        std::once_flag once;
        std::atomic<bool> filled{false};
    };

    int width = 0, height = 0;
    // What the analysis covers, checked against an evaluator's parameters in setParts.
    bool ssimOn = false, grayOn = false, sobelOn = false;
    int ssimWindow = 0, mapWidth = 0, mapHeight = 0, sobelBins = 0;
    // Per image row, the runs of pixels whose gray (Sobel) histogram entry is NOT owned: the
    // per-pixel path visits only these. Rows: [grayFreeStart[y], grayFreeStart[y + 1]).
    std::vector<Run> grayFree, sobelFree;
    std::vector<std::uint32_t> grayFreeStart, sobelFreeStart;
    std::vector<Part> parts;
    std::vector<std::size_t> entryOffset;  // entries of part k: [entryOffset[k], entryOffset[k + 1])
    std::unique_ptr<Entry[]> entries;
    std::uint64_t liveSsimWindows = 0;

    // The runs of `runs` (indexed by `start`) on row y that overlap columns [x0, x1).
    static std::span<const Run> freeRuns(const std::vector<Run>& runs, const std::vector<std::uint32_t>& start, int y,
                                         int x0, int x1) {
        const Run* first = runs.data() + start[std::size_t(y)];
        const Run* last = runs.data() + start[std::size_t(y) + 1];
        first = std::partition_point(first, last, [x0](const Run& run) { return run.x1 <= x0; });
        const Run* end = std::partition_point(first, last, [x1](const Run& run) { return run.x0 < x1; });
        return {first, end};
    }

    Entry& entry(int part, int state) { return entries[entryOffset[std::size_t(part)] + std::size_t(state)]; }
    int states(int part) const { return int(entryOffset[std::size_t(part) + 1] - entryOffset[std::size_t(part)]); }

    // Windows reading several parts in map rectangle [x0, x1) x [y0, y1) (summed-area table).
    std::uint64_t liveWindows(int x0, int y0, int x1, int y1) const {
        const std::size_t stride = std::size_t(mapWidth) + 1;
        const auto at = [&](int x, int y) {
            return std::int64_t(mLiveTable[std::size_t(y) * stride + std::size_t(x)]);
        };
        return std::uint64_t(at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0));
    }
    void setLiveTable(std::vector<std::int32_t> table) { mLiveTable = std::move(table); }

private:
    std::vector<std::int32_t> mLiveTable;  // (mapWidth + 1) x (mapHeight + 1)
};

}  // namespace lodopt::metrics
