// PartCache analysis: which part, if any, owns each SSIM window, Sobel neighbourhood and gray
// pixel. A window's owner combines its pixels' parts: constant pixels are neutral, one part
// stays that part, two different parts (or a shared pixel) make it shared. The combination is
// associative, so a window's owner is computed separably (rows, then columns).
#include "parts.hpp"

#include <algorithm>
#include <string>

#include "kernels.hpp"

namespace lodopt::metrics {

namespace {

std::int32_t combine(std::int32_t a, std::int32_t b) {
    if (a == kConstantPixel) return b;
    if (b == kConstantPixel || a == b) return a;
    return kSharedPixel;
}

// Owner of every window x window block whose top-left corner is (x, y), for the
// (width - window + 1) x (height - window + 1) positions.
std::vector<std::int32_t> windowOwners(std::span<const std::int32_t> pixels, int width, int height, int window) {
    const int outWidth = width - window + 1, outHeight = height - window + 1;
    if (outWidth <= 0 || outHeight <= 0) return {};
    std::vector<std::int32_t> rows(std::size_t(outWidth) * height);
    for (int y = 0; y < height; ++y) {
        const std::int32_t* in = pixels.data() + std::size_t(y) * width;
        std::int32_t* out = rows.data() + std::size_t(y) * outWidth;
        for (int x = 0; x < outWidth; ++x) {
            std::int32_t owner = kConstantPixel;
            for (int k = 0; k < window && owner != kSharedPixel; ++k) owner = combine(owner, in[x + k]);
            out[x] = owner;
        }
    }
    std::vector<std::int32_t> owners(std::size_t(outWidth) * outHeight);
    for (int y = 0; y < outHeight; ++y) {
        for (int x = 0; x < outWidth; ++x) {
            std::int32_t owner = kConstantPixel;
            for (int k = 0; k < window && owner != kSharedPixel; ++k) {
                owner = combine(owner, rows[std::size_t(y + k) * outWidth + x]);
            }
            owners[std::size_t(y) * outWidth + x] = owner;
        }
    }
    return owners;
}

// Appends each row's runs of equal owners >= 0 to their part's list; (offsetX, offsetY) moves
// grid coordinates to the run coordinates.
void collectRuns(std::span<const std::int32_t> owners, int width, int height, int offsetX, int offsetY,
                 std::vector<PartCache::Part>& parts, std::vector<PartCache::Run> PartCache::Part::*runs) {
    for (int y = 0; y < height; ++y) {
        const std::int32_t* row = owners.data() + std::size_t(y) * width;
        for (int x = 0; x < width;) {
            const std::int32_t owner = row[x];
            int end = x + 1;
            while (end < width && row[end] == owner) ++end;
            if (owner >= 0) (parts[std::size_t(owner)].*runs).push_back({y + offsetY, x + offsetX, end + offsetX});
            x = end;
        }
    }
}

}  // namespace

std::shared_ptr<PartCache> makePartCache(int width, int height, const MetricParameters& parameters,
                                         std::span<const std::int32_t> pixelParts, std::span<const int> stateCounts) {
    validateParameters(parameters);
    if (width < 1 || height < 1 || std::size_t(width) * std::size_t(height) != pixelParts.size()) {
        throw MetricError("part map has " + std::to_string(pixelParts.size()) + " values for a " +
                          std::to_string(width) + "x" + std::to_string(height) + " image");
    }
    const int partCount = int(stateCounts.size());
    for (int k = 0; k < partCount; ++k) {
        if (stateCounts[std::size_t(k)] < 1) {
            throw MetricError("part " + std::to_string(k) + " has " + std::to_string(stateCounts[std::size_t(k)]) +
                              " states (at least 1)");
        }
    }
    for (std::size_t p = 0; p < pixelParts.size(); ++p) {
        const std::int32_t part = pixelParts[p];
        if (part != kConstantPixel && part != kSharedPixel && (part < 0 || part >= partCount)) {
            throw MetricError("pixel " + std::to_string(p) + " names part " + std::to_string(part) + " of " +
                              std::to_string(partCount));
        }
    }

    auto cache = std::make_shared<PartCache>();
    PartCache& c = *cache;
    c.width = width;
    c.height = height;
    c.parts.resize(std::size_t(partCount));
    // Per pixel: bit kGrayOwned when a part owns its gray-histogram entry, kSobelOwned when a
    // part owns its Sobel bin; the complements become the per-pixel path's free runs below.
    constexpr std::uint8_t kGrayOwned = 1, kSobelOwned = 2;
    std::vector<std::uint8_t> ownedMask(pixelParts.size(), 0);
    const PartCoverage coverage = partCoverage(parameters);
    c.ssimOn = coverage.ssim;
    c.grayOn = coverage.gray;
    c.sobelOn = coverage.sobel;
    c.sobelBins = parameters.boundaryHistogramBins;

    if (c.ssimOn) {
        const detail::SsimKernel kernel =
            detail::makeSsimKernel(parameters, width, height, detail::grayScale(parameters.grayWeights));
        c.ssimWindow = kernel.window;
        c.mapWidth = kernel.mapWidth;
        c.mapHeight = kernel.mapHeight;
        const std::vector<std::int32_t> owners = windowOwners(pixelParts, width, height, kernel.window);
        collectRuns(owners, c.mapWidth, c.mapHeight, 0, 0, c.parts, &PartCache::Part::ssimRuns);
        const std::size_t stride = std::size_t(c.mapWidth) + 1;
        std::vector<std::int32_t> table(stride * (std::size_t(c.mapHeight) + 1), 0);
        for (int y = 0; y < c.mapHeight; ++y) {
            std::int32_t rowCount = 0;
            for (int x = 0; x < c.mapWidth; ++x) {
                rowCount += owners[std::size_t(y) * c.mapWidth + x] == kSharedPixel ? 1 : 0;
                table[std::size_t(y + 1) * stride + std::size_t(x + 1)] =
                    table[std::size_t(y) * stride + std::size_t(x + 1)] + rowCount;
            }
        }
        c.liveSsimWindows = std::uint64_t(table.back());
        c.setLiveTable(std::move(table));
        for (PartCache::Part& part : c.parts) {
            if (part.ssimRuns.empty()) continue;
            UpdateRect bounds{c.mapWidth, part.ssimRuns.front().y, 0, part.ssimRuns.back().y + 1};
            for (const PartCache::Run& run : part.ssimRuns) {
                bounds.x0 = std::min(bounds.x0, run.x0);
                bounds.x1 = std::max(bounds.x1, run.x1);
                part.ssimWindows += std::size_t(run.x1 - run.x0);
            }
            part.ssimBounds = bounds;
            part.ssimRowStart.assign(std::size_t(bounds.y1 - bounds.y0) + 1, 0);
            part.ssimRunOffset.reserve(part.ssimRuns.size());
            std::uint32_t offset = 0;
            for (const PartCache::Run& run : part.ssimRuns) {
                ++part.ssimRowStart[std::size_t(run.y - bounds.y0) + 1];
                part.ssimRunOffset.push_back(offset);
                offset += std::uint32_t(run.x1 - run.x0);
            }
            for (std::size_t i = 1; i < part.ssimRowStart.size(); ++i) part.ssimRowStart[i] += part.ssimRowStart[i - 1];
        }
    }
    if (c.grayOn) {
        collectRuns(pixelParts, width, height, 0, 0, c.parts, &PartCache::Part::grayRuns);
        for (std::size_t p = 0; p < pixelParts.size(); ++p) {
            if (pixelParts[p] >= 0) ownedMask[p] |= kGrayOwned;
        }
    }
    if (c.sobelOn && width >= 3 && height >= 3) {
        // Interior pixel (x, y) reads the 3x3 block whose corner is (x - 1, y - 1).
        const std::vector<std::int32_t> owners = windowOwners(pixelParts, width, height, 3);
        collectRuns(owners, width - 2, height - 2, 1, 1, c.parts, &PartCache::Part::sobelRuns);
        for (int y = 1; y + 1 < height; ++y) {
            for (int x = 1; x + 1 < width; ++x) {
                if (owners[std::size_t(y - 1) * (width - 2) + std::size_t(x - 1)] >= 0) {
                    ownedMask[std::size_t(y) * width + x] |= kSobelOwned;
                }
            }
        }
    }
    // The complements, per row: where the per-pixel path still has work.
    auto freeRuns = [&](std::uint8_t bit, std::vector<PartCache::Run>& runs, std::vector<std::uint32_t>& start) {
        start.assign(std::size_t(height) + 1, 0);
        for (int y = 0; y < height; ++y) {
            const std::uint8_t* row = ownedMask.data() + std::size_t(y) * width;
            for (int x = 0; x < width;) {
                if (row[x] & bit) {
                    ++x;
                    continue;
                }
                int end = x + 1;
                while (end < width && !(row[end] & bit)) ++end;
                runs.push_back({y, x, end});
                x = end;
            }
            start[std::size_t(y) + 1] = std::uint32_t(runs.size());
        }
    };
    freeRuns(kGrayOwned, c.grayFree, c.grayFreeStart);
    freeRuns(kSobelOwned, c.sobelFree, c.sobelFreeStart);
    c.entryOffset.assign(std::size_t(partCount) + 1, 0);
    for (int k = 0; k < partCount; ++k) {
        c.entryOffset[std::size_t(k) + 1] = c.entryOffset[std::size_t(k)] + std::size_t(stateCounts[std::size_t(k)]);
    }
    c.entries = std::make_unique<PartCache::Entry[]>(c.entryOffset.back());
    return cache;
}

PartCacheStats partCacheStats(const PartCache& cache) {
    PartCacheStats stats;
    stats.parts = int(cache.parts.size());
    stats.entries = cache.entryOffset.empty() ? 0 : cache.entryOffset.back();
    stats.liveSsimWindows = cache.liveSsimWindows;
    stats.bytes = (cache.grayFree.size() + cache.sobelFree.size()) * sizeof(PartCache::Run) +
                  (cache.grayFreeStart.size() + cache.sobelFreeStart.size()) * sizeof(std::uint32_t);
    for (const PartCache::Part& part : cache.parts) {
        stats.ownedSsimWindows += part.ssimWindows;
        for (const PartCache::Run& run : part.grayRuns) stats.ownedPixels += std::uint64_t(run.x1 - run.x0);
        stats.bytes += (part.ssimRuns.size() + part.grayRuns.size() + part.sobelRuns.size()) * sizeof(PartCache::Run);
    }
    for (std::uint64_t e = 0; e < stats.entries; ++e) {
        const PartCache::Entry& entry = cache.entries[e];
        if (!entry.filled.load(std::memory_order_acquire)) continue;
        ++stats.filledEntries;
        stats.bytes += entry.ssim.size() * sizeof(double) +
                       (entry.gray.size() + entry.sobel.size()) * sizeof(std::pair<std::uint32_t, std::int64_t>);
    }
    return stats;
}

}  // namespace lodopt::metrics
