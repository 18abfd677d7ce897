// Incremental evaluation: keeps the reference statistics and the candidate's per-pixel state
// and updates them from a dirty rectangle (see the header for the exactness argument).
//
// The state starts as "candidate = all-black gray, nothing counted": histograms hold every
// pixel in bin 0, classes and counts are 0, maps are 0. That state is consistent, so the
// constructor's setCandidate(reference) and every later setCandidate are updates of the
// whole image rectangle: one code path for full and incremental evaluation (a whole-image
// update restarts the integer counts instead of subtracting each old pixel first).
#include "metrics/incremental_evaluator.hpp"

#include <algorithm>
#include <mutex>
#include <string>

#include "kernels.hpp"
#include "parts.hpp"
#include "prepared_reference.hpp"

namespace lodopt::metrics {

namespace {
// A region whose share of live windows is above this computes whole (chosen on the forest and
// harbor walks, docs/optimizer.md "The owned-window cache").
constexpr std::uint64_t kLiveShareNumerator = 1, kLiveShareDenominator = 2;
}  // namespace

struct IncrementalEvaluator::State : detail::PreparedReference {
    bool precisionRecallOn = false;

    std::vector<std::int32_t> candidateGray, rowGray;
    std::vector<std::uint16_t> rowBins;
    std::vector<std::uint8_t> rowClasses, rowGrayBins;

    detail::FixedPooledMap ssimMap;
    detail::SsimScratch scratch;

    std::vector<std::uint16_t> sobelBins;           // per pixel (interior ones used)
    std::vector<std::uint64_t> boundaryHistogram;   // Histogram mode
    detail::LaneHistogram boundaryLanes;
    std::uint64_t interiorPixels = 0;
    detail::PooledMap robertsTerms;                 // Paper mode

    std::array<std::uint64_t, 256> grayHistogram{};  // Histogram mode
    detail::LaneHistogram grayLanes;
    detail::PooledMap intensityTerms;               // Paper mode
    std::int64_t intensitySum = 0;

    detail::CoverageRule coverage;
    std::vector<std::uint8_t> referencePixels;  // packed rows
    std::vector<std::uint8_t> classes;          // PixelClass bits per pixel
    std::uint64_t truePositives = 0, falsePositives = 0, falseNegatives = 0;

    // Parts (setParts): the shared cache, each part's current state, and scratch.
    std::shared_ptr<PartCache> parts;
    std::vector<int> partStates;
    std::vector<std::int64_t> denseHistogram;   // filling an entry's histograms

    void checkCandidate(const ImageView& candidate) const;
    // Fills `entry` from the current image, which shows `part` in the entry's state.
    void fillEntry(int part, PartCache::Entry& entry);
    void applyEntry(const PartCache::Entry& entry, std::int64_t sign);
    // Map windows whose inputs lie in pixel rectangle `r` (clipped to the map).
    UpdateRect ssimReach(const UpdateRect& r) const;
    // Copies `entry`'s values of the part's owned windows inside map rectangle `region`.
    void copyOwnedSsim(int part, const PartCache::Entry& entry, const UpdateRect& region);
    void update(const ImageView& candidate, int x0, int y0, int x1, int y1);
    void updatePixels(const ImageView& candidate, int x0, int y0, int x1, int y1, bool replace);
    void updateBoundary(int x0, int y0, int x1, int y1, bool replace);
    void updateSsim(int x0, int y0, int x1, int y1);
};

IncrementalEvaluator::IncrementalEvaluator(const ImageView& reference, const MetricParameters& parameters)
    : mState(std::make_unique<State>()) {
    State& s = *mState;
    detail::prepareReference(reference, parameters, s, s.scratch);
    s.precisionRecallOn = parameters.computePrecisionRecall;
    const std::size_t pixels = std::size_t(s.width) * s.height;

    s.candidateGray.assign(pixels, 0);
    s.rowGray.assign(std::size_t(s.width), 0);
    if (s.ssimOn) s.ssimMap.resize(s.kernel.mapWidth, s.kernel.mapHeight);
    if (s.boundaryOn) {
        if (parameters.boundaryEntropyMode == EntropyMode::Histogram) {
            s.sobelBins.assign(pixels, 0);
            s.boundaryHistogram.assign(std::size_t(s.sobel.bins), 0);
            s.interiorPixels = std::uint64_t(std::max(s.width - 2, 0)) * std::uint64_t(std::max(s.height - 2, 0));
            s.boundaryHistogram[0] = s.interiorPixels;  // an all-zero gray image has no edges
            s.boundaryLanes.resize(s.sobel.bins);
            s.rowBins.assign(std::size_t(s.width), 0);
        } else if (s.width >= 2 && s.height >= 2) {
            s.robertsTerms.resize(s.width - 1, s.height - 1);
        }
    }
    if (s.informationOn) {
        if (parameters.informationEntropyMode == EntropyMode::Histogram) {
            s.grayHistogram[0] = pixels;
            s.grayLanes.resize(256);
            s.rowGrayBins.assign(std::size_t(s.width), 0);
        } else {
            s.intensityTerms.resize(s.width, s.height);
        }
    }
    if (s.precisionRecallOn) {
        s.coverage = detail::makeCoverageRule(parameters, s.channels, s.grayScale);
        const std::size_t rowBytes = std::size_t(s.width) * s.channels;
        s.referencePixels.resize(rowBytes * s.height);
        for (int y = 0; y < s.height; ++y) {
            std::copy_n(reference.pixels + y * reference.rowStride, rowBytes, s.referencePixels.data() + y * rowBytes);
        }
        s.classes.assign(pixels, 0);
        s.rowClasses.assign(std::size_t(s.width), 0);
    }
    setCandidate(reference);
}

IncrementalEvaluator::~IncrementalEvaluator() = default;
IncrementalEvaluator::IncrementalEvaluator(IncrementalEvaluator&&) noexcept = default;
IncrementalEvaluator& IncrementalEvaluator::operator=(IncrementalEvaluator&&) noexcept = default;

void IncrementalEvaluator::setCandidate(const ImageView& candidate) {
    mState->checkCandidate(candidate);
    mState->parts.reset();  // a whole new image: the per-pixel state is rebuilt for every pixel
    mState->update(candidate, 0, 0, mState->width, mState->height);
}

void IncrementalEvaluator::setParts(std::shared_ptr<PartCache> cache, const ImageView& candidate,
                                    std::span<const int> states) {
    State& s = *mState;
    if (!cache) throw MetricError("no part cache");
    const PartCache& c = *cache;
    const PartCoverage coverage = partCoverage(s.parameters);
    if (c.width != s.width || c.height != s.height || !(PartCoverage{c.ssimOn, c.grayOn, c.sobelOn} == coverage) ||
        (coverage.ssim && c.ssimWindow != s.kernel.window) || (coverage.sobel && c.sobelBins != s.sobel.bins)) {
        throw MetricError("the part cache was made for another image size or metric parameters");
    }
    if (states.size() != c.parts.size()) {
        throw MetricError(std::to_string(states.size()) + " part states for " + std::to_string(c.parts.size()) + " parts");
    }
    for (std::size_t k = 0; k < states.size(); ++k) {
        if (states[k] < 0 || states[k] >= c.states(int(k))) {
            throw MetricError("part " + std::to_string(k) + " state " + std::to_string(states[k]) + " out of range");
        }
    }
    setCandidate(candidate);  // every per-pixel value current, parts dropped
    s.parts = std::move(cache);
    s.partStates.assign(states.begin(), states.end());
    s.denseHistogram.assign(std::size_t(s.parts->sobelOn ? std::max(s.sobel.bins, 256) : 256), 0);
    for (int k = 0; k < int(s.partStates.size()); ++k) {
        PartCache::Entry& entry = s.parts->entry(k, s.partStates[std::size_t(k)]);
        std::call_once(entry.once, [&] { s.fillEntry(k, entry); });
    }
}

bool IncrementalEvaluator::hasParts() const { return mState->parts != nullptr; }

void IncrementalEvaluator::update(const ImageView& candidate, std::span<const UpdateRect> rects,
                                  std::span<const PartMove> moves) {
    State& s = *mState;
    s.checkCandidate(candidate);
    if (!s.parts) {
        if (!moves.empty()) throw MetricError("part moves given to an evaluator without parts");
        for (const UpdateRect& r : rects) updateRect(candidate, r.x0, r.y0, r.x1, r.y1);
        return;
    }
    PartCache& c = *s.parts;
    for (const PartMove& move : moves) {
        if (move.part < 0 || move.part >= int(c.parts.size()) || move.state < 0 || move.state >= c.states(move.part)) {
            throw MetricError("part move " + std::to_string(move.part) + " -> " + std::to_string(move.state) +
                              " out of range");
        }
    }
    // 1. Pixels: the gray image must be current before an entry is filled from it.
    auto clipped = [&](const UpdateRect& r) {
        return UpdateRect{std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, s.width), std::min(r.y1, s.height)};
    };
    for (const UpdateRect& rect : rects) {
        const UpdateRect r = clipped(rect);
        if (r.x0 >= r.x1 || r.y0 >= r.y1) continue;
        s.updatePixels(candidate, r.x0, r.y0, r.x1, r.y1, false);
        if (s.boundaryOn) s.updateBoundary(r.x0, r.y0, r.x1, r.y1, false);
    }
    // 2. Moved parts: histogram counts swapped, owned SSIM windows copied where their inputs
    // changed (an owned window no changed pixel reaches has the same value in both states).
    for (std::size_t m = 0; m < moves.size(); ++m) {
        const PartMove& move = moves[m];
        // A part listed twice ends in its last state: only that one may be filled from the image.
        bool later = false;
        for (std::size_t n = m + 1; n < moves.size() && !later; ++n) later = moves[n].part == move.part;
        int& current = s.partStates[std::size_t(move.part)];
        if (later || current == move.state) continue;
        PartCache::Entry& before = c.entry(move.part, current);
        PartCache::Entry& after = c.entry(move.part, move.state);
        std::call_once(after.once, [&] { s.fillEntry(move.part, after); });
        s.applyEntry(before, -1);
        s.applyEntry(after, 1);
        if (s.ssimOn) {
            for (const UpdateRect& rect : rects) {
                const UpdateRect r = clipped(rect);
                if (r.x0 < r.x1 && r.y0 < r.y1) s.copyOwnedSsim(move.part, after, s.ssimReach(r));
            }
        }
        current = move.state;
    }
    // 3. Windows reading several parts, and the map's pooled sums over each rectangle.
    if (s.ssimOn) {
        for (const UpdateRect& rect : rects) {
            const UpdateRect r = clipped(rect);
            if (r.x0 < r.x1 && r.y0 < r.y1) s.updateSsim(r.x0, r.y0, r.x1, r.y1);
        }
    }
}

void IncrementalEvaluator::updateRect(const ImageView& candidate, int x0, int y0, int x1, int y1) {
    mState->checkCandidate(candidate);
    mState->update(candidate, std::max(x0, 0), std::max(y0, 0), std::min(x1, mState->width),
                   std::min(y1, mState->height));
}

void IncrementalEvaluator::State::checkCandidate(const ImageView& candidate) const {
    detail::validateView(candidate, "candidate image");
    if (candidate.width != width || candidate.height != height || candidate.channels != channels) {
        throw MetricError("candidate image is " + std::to_string(candidate.width) + "x" +
                          std::to_string(candidate.height) + " with " + std::to_string(candidate.channels) +
                          " channels but the reference is " + std::to_string(width) + "x" + std::to_string(height) +
                          " with " + std::to_string(channels));
    }
}

void IncrementalEvaluator::State::update(const ImageView& candidate, int x0, int y0, int x1, int y1) {
    if (x0 >= x1 || y0 >= y1) return;
    // A whole-image update restarts the counts instead of subtracting every old pixel: the
    // per-pixel values come from the same functions, and counts are integers, so both ways
    // give the same histograms.
    // With parts the histograms hold owned counts the per-pixel path does not know: never restart.
    const bool replace = !parts && x0 == 0 && y0 == 0 && x1 == width && y1 == height;
    // Order matters: the gray image must be current before Sobel and SSIM read it.
    updatePixels(candidate, x0, y0, x1, y1, replace);
    if (boundaryOn) updateBoundary(x0, y0, x1, y1, replace);
    if (ssimOn) updateSsim(x0, y0, x1, y1);
}

void IncrementalEvaluator::State::updatePixels(const ImageView& candidate, int x0, int y0, int x1, int y1,
                                               bool replace) {
    const bool histogram = informationOn && parameters.informationEntropyMode == EntropyMode::Histogram;
    const bool intensity = informationOn && !histogram;
    const std::size_t rowBytes = std::size_t(width) * channels;
    const int count = x1 - x0;
    std::int64_t tp = 0, fp = 0, fn = 0;
    const detail::GrayScale gray = grayScale;  // a local: no aliasing with the histogram lanes
    if (replace) {
        grayHistogram.fill(0);
        intensitySum = 0;
        truePositives = falsePositives = falseNegatives = 0;
    }
    for (int y = y0; y < y1; ++y) {
        const std::uint8_t* row = candidate.pixels + y * candidate.rowStride + std::size_t(x0) * channels;
        detail::grayRow(row, channels, count, gray, rowGray.data());
        std::int32_t* stored = candidateGray.data() + std::size_t(y) * width + x0;
        if (histogram && parts && parts->grayOn) {
            // Only pixels no part owns: the owned ones are counted in the parts' entries.
            for (const PartCache::Run& run : parts->freeRuns(parts->grayFree, parts->grayFreeStart, y, x0, x1)) {
                const int a = std::max(run.x0, x0), b = std::min(run.x1, x1);
                detail::grayBinsRow(stored + (a - x0), b - a, gray, rowGrayBins.data());
                grayLanes.addRow(rowGrayBins.data(), b - a, -1);
                detail::grayBinsRow(rowGray.data() + (a - x0), b - a, gray, rowGrayBins.data());
                grayLanes.addRow(rowGrayBins.data(), b - a, 1);
            }
        } else if (histogram) {
            if (!replace) {
                detail::grayBinsRow(stored, count, gray, rowGrayBins.data());
                grayLanes.addRow(rowGrayBins.data(), count, -1);
            }
            detail::grayBinsRow(rowGray.data(), count, gray, rowGrayBins.data());
            grayLanes.addRow(rowGrayBins.data(), count, 1);
        }
        if (intensity) {
            double* terms = intensityTerms.row(y) + x0;
            for (int i = 0; i < count; ++i) {
                const std::int32_t value = rowGray[std::size_t(i)];
                intensitySum += std::int64_t(value) - (replace ? 0 : stored[i]);
                terms[i] = detail::intensityTerm(value);
            }
        }
        std::copy_n(rowGray.data(), count, stored);
        if (precisionRecallOn) {
            detail::classifyRow(row, referencePixels.data() + y * rowBytes + std::size_t(x0) * channels, count,
                                coverage, rowClasses.data());
            std::uint8_t* __restrict before = classes.data() + std::size_t(y) * width + x0;
            const std::uint8_t* __restrict now = rowClasses.data();
            // Bit counting (vectorises): each class bit adds to its counter, the old one subtracts.
            for (int i = 0; i < count; ++i) {
                const int bits = now[i];
                tp += bits & detail::kTruePositive;
                fp += (bits & detail::kFalsePositive) >> 1;
                fn += (bits & detail::kFalseNegative) >> 2;
            }
            if (!replace) {
                for (int i = 0; i < count; ++i) {
                    const int bits = before[i];
                    tp -= bits & detail::kTruePositive;
                    fp -= (bits & detail::kFalsePositive) >> 1;
                    fn -= (bits & detail::kFalseNegative) >> 2;
                }
            }
            std::copy_n(now, count, before);
        }
    }
    if (histogram) grayLanes.mergeInto(grayHistogram.data());
    if (intensity) intensityTerms.refresh(x0, y0, x1, y1);
    // Modular arithmetic: a negative change subtracts.
    truePositives += std::uint64_t(tp);
    falsePositives += std::uint64_t(fp);
    falseNegatives += std::uint64_t(fn);
}

void IncrementalEvaluator::State::updateBoundary(int x0, int y0, int x1, int y1, bool replace) {
    const std::ptrdiff_t stride = width;
    if (parameters.boundaryEntropyMode == EntropyMode::Histogram) {
        // A changed pixel moves the Sobel magnitude of its 8 neighbours: grow by 1, keep interior.
        const int bx0 = std::max(x0 - 1, 1), bx1 = std::min(x1 + 1, width - 1);
        const int by0 = std::max(y0 - 1, 1), by1 = std::min(y1 + 1, height - 1);
        if (bx0 >= bx1 || by0 >= by1) return;
        const int count = bx1 - bx0;
        if (replace) std::fill(boundaryHistogram.begin(), boundaryHistogram.end(), 0);
        const bool owned = parts && parts->sobelOn;
        for (int y = by0; y < by1; ++y) {
            if (owned) {
                // Only pixels no part owns: the owned ones are counted in the parts' entries.
                for (const PartCache::Run& run : parts->freeRuns(parts->sobelFree, parts->sobelFreeStart, y, bx0, bx1)) {
                    const int a = std::max(run.x0, bx0), b = std::min(run.x1, bx1);
                    const std::size_t at = std::size_t(y) * width + a;
                    detail::sobelBinsRow(candidateGray.data() + at, stride, b - a, sobel, rowBins.data());
                    std::uint16_t* bins = sobelBins.data() + at;
                    boundaryLanes.addRow(bins, b - a, -1);
                    boundaryLanes.addRow(rowBins.data(), b - a, 1);
                    std::copy_n(rowBins.data(), b - a, bins);
                }
                continue;
            }
            const std::size_t at = std::size_t(y) * width + bx0;
            detail::sobelBinsRow(candidateGray.data() + at, stride, count, sobel, rowBins.data());
            std::uint16_t* bins = sobelBins.data() + at;
            if (!replace) boundaryLanes.addRow(bins, count, -1);
            boundaryLanes.addRow(rowBins.data(), count, 1);
            std::copy_n(rowBins.data(), count, bins);
        }
        boundaryLanes.mergeInto(boundaryHistogram.data());
        return;
    }
    if (robertsTerms.empty()) return;
    // The Roberts term at (x, y) reads (x + 1, y + 1): pixels up to one left/above change.
    const int rx0 = std::max(x0 - 1, 0), rx1 = std::min(x1, width - 1);
    const int ry0 = std::max(y0 - 1, 0), ry1 = std::min(y1, height - 1);
    const double inverseScale = 1.0 / grayScale.scale;
    for (int y = ry0; y < ry1; ++y) {
        const std::int32_t* gray = candidateGray.data() + std::size_t(y) * width;
        double* terms = robertsTerms.row(y);
        for (int x = rx0; x < rx1; ++x) terms[x] = detail::robertsTerm(gray + x, stride, inverseScale);
    }
    robertsTerms.refresh(rx0, ry0, rx1, ry1);
}

void IncrementalEvaluator::State::updateSsim(int x0, int y0, int x1, int y1) {
    const UpdateRect reach = ssimReach({x0, y0, x1, y1});
    const int mx0 = reach.x0, mx1 = reach.x1, my0 = reach.y0, my1 = reach.y1;
    if (mx0 >= mx1 || my0 >= my1) return;
    const std::size_t mapStride = std::size_t(kernel.mapWidth);
    const std::size_t origin = std::size_t(my0) * mapStride + std::size_t(mx0);
    // With parts, only the windows reading several parts need computing; where they are most of
    // the region, computing it whole in tall blocks is cheaper than picking them out (the owned
    // windows computed on the way get the values the cache holds).
    const PartCache* liveOnly = nullptr;
    if (parts && parts->ssimOn) {
        const std::uint64_t area = std::uint64_t(mx1 - mx0) * std::uint64_t(my1 - my0);
        if (parts->liveWindows(mx0, my0, mx1, my1) * kLiveShareDenominator <= area * kLiveShareNumerator) {
            liveOnly = parts.get();
        }
    }
    detail::ssimWindows(candidateGray.data(), referenceGray.data(), std::size_t(width), kernel, mx0, my0, mx1, my1,
                        referenceMean.data() + origin, referenceVariance.data() + origin, mapStride, scratch,
                        ssimMap.row(my0) + mx0, mapStride, liveOnly);
    ssimMap.refresh(mx0, my0, mx1, my1);
}

void IncrementalEvaluator::State::fillEntry(int part, PartCache::Entry& entry) {
    const PartCache::Part& owned = parts->parts[std::size_t(part)];
    if (parts->ssimOn && owned.ssimWindows > 0) {
        // Every window of the bounding rectangle from the current gray (correct values for all
        // of them), then the owned ones gathered in run order.
        const UpdateRect& b = owned.ssimBounds;
        const std::size_t mapStride = std::size_t(kernel.mapWidth);
        const std::size_t origin = std::size_t(b.y0) * mapStride + std::size_t(b.x0);
        detail::ssimWindows(candidateGray.data(), referenceGray.data(), std::size_t(width), kernel, b.x0, b.y0, b.x1,
                            b.y1, referenceMean.data() + origin, referenceVariance.data() + origin, mapStride, scratch,
                            ssimMap.row(b.y0) + b.x0, mapStride);
        ssimMap.refresh(b.x0, b.y0, b.x1, b.y1);
        entry.ssim.resize(owned.ssimWindows);
        double* out = entry.ssim.data();
        for (const PartCache::Run& run : owned.ssimRuns) {
            out = std::copy(ssimMap.row(run.y) + run.x0, ssimMap.row(run.y) + run.x1, out);
        }
    }
    auto sparse = [&](int bins, std::vector<std::pair<std::uint32_t, std::int64_t>>& out) {
        for (int b = 0; b < bins; ++b) {
            if (denseHistogram[std::size_t(b)] != 0) out.emplace_back(std::uint32_t(b), denseHistogram[std::size_t(b)]);
            denseHistogram[std::size_t(b)] = 0;
        }
    };
    if (parts->grayOn && !owned.grayRuns.empty()) {
        for (const PartCache::Run& run : owned.grayRuns) {
            const int count = run.x1 - run.x0;
            detail::grayBinsRow(candidateGray.data() + std::size_t(run.y) * width + run.x0, count, grayScale,
                                rowGrayBins.data());
            for (int i = 0; i < count; ++i) ++denseHistogram[rowGrayBins[std::size_t(i)]];
        }
        sparse(256, entry.gray);
    }
    if (parts->sobelOn && !owned.sobelRuns.empty()) {
        for (const PartCache::Run& run : owned.sobelRuns) {
            const int count = run.x1 - run.x0;
            detail::sobelBinsRow(candidateGray.data() + std::size_t(run.y) * width + run.x0, width, count, sobel,
                                 rowBins.data());
            for (int i = 0; i < count; ++i) ++denseHistogram[rowBins[std::size_t(i)]];
        }
        sparse(sobel.bins, entry.sobel);
    }
    entry.filled.store(true, std::memory_order_release);
}

void IncrementalEvaluator::State::applyEntry(const PartCache::Entry& entry, std::int64_t sign) {
    // Modular arithmetic: a negative change subtracts.
    for (const auto& [bin, count] : entry.gray) grayHistogram[bin] += std::uint64_t(sign * count);
    for (const auto& [bin, count] : entry.sobel) boundaryHistogram[bin] += std::uint64_t(sign * count);
}

UpdateRect IncrementalEvaluator::State::ssimReach(const UpdateRect& r) const {
    // Map (mx, my) covers pixels [mx, mx + window): windows reaching back window - 1 pixels.
    return {std::max(r.x0 - kernel.window + 1, 0), std::max(r.y0 - kernel.window + 1, 0),
            std::min(r.x1, kernel.mapWidth), std::min(r.y1, kernel.mapHeight)};
}

void IncrementalEvaluator::State::copyOwnedSsim(int part, const PartCache::Entry& entry, const UpdateRect& region) {
    const PartCache::Part& owned = parts->parts[std::size_t(part)];
    if (owned.ssimWindows == 0) return;
    const UpdateRect& b = owned.ssimBounds;
    const int y0 = std::max(region.y0, b.y0), y1 = std::min(region.y1, b.y1);
    const int x0 = std::max(region.x0, b.x0), x1 = std::min(region.x1, b.x1);
    if (x0 >= x1 || y0 >= y1) return;
    // No re-pooling here: updateSsim re-pools the same region right after.
    for (int y = y0; y < y1; ++y) {
        double* row = ssimMap.row(y);
        const std::size_t i = std::size_t(y - b.y0);
        for (std::uint32_t r = owned.ssimRowStart[i]; r < owned.ssimRowStart[i + 1]; ++r) {
            const PartCache::Run& run = owned.ssimRuns[r];
            const int a = std::max(run.x0, x0), e = std::min(run.x1, x1);
            if (a < e) std::copy_n(entry.ssim.data() + owned.ssimRunOffset[r] + (a - run.x0), e - a, row + a);
        }
    }
}

MetricResult IncrementalEvaluator::result() const {
    const State& s = *mState;
    MetricResult result;
    if (s.ssimOn) {
        result.ssimComputed = true;
        result.ssim = detail::ssimMeanFromFixed(s.ssimMap.total(),
                                                std::uint64_t(s.kernel.mapWidth) * std::uint64_t(s.kernel.mapHeight));
    }
    if (s.boundaryOn) {
        result.boundaryEntropy.computed = true;
        result.boundaryEntropy.reference = s.boundaryReference;
        result.boundaryEntropy.candidate =
            s.parameters.boundaryEntropyMode == EntropyMode::Histogram
                ? detail::histogramEntropy(s.boundaryHistogram.data(), s.sobel.bins, s.interiorPixels)
                : s.robertsTerms.total() + 0.0;
    }
    if (s.informationOn) {
        result.informationEntropy.computed = true;
        result.informationEntropy.reference = s.informationReference;
        const std::uint64_t pixels = std::uint64_t(s.width) * std::uint64_t(s.height);
        result.informationEntropy.candidate =
            s.parameters.informationEntropyMode == EntropyMode::Histogram
                ? detail::histogramEntropy(s.grayHistogram.data(), 256, pixels)
                : detail::intensityShareEntropy(s.intensitySum, s.intensityTerms.total(), pixels);
    }
    if (s.precisionRecallOn) {
        detail::setPrecisionRecall(result,
                                   precisionRecallFromCounts(s.truePositives, s.falsePositives, s.falseNegatives));
    }
    fuse(result, s.parameters);
    return result;
}

const MetricParameters& IncrementalEvaluator::parameters() const { return mState->parameters; }
int IncrementalEvaluator::width() const { return mState->width; }
int IncrementalEvaluator::height() const { return mState->height; }
int IncrementalEvaluator::channels() const { return mState->channels; }
const double* IncrementalEvaluator::ssimMap() const {
    return mState->ssimOn ? mState->ssimMap.values() : nullptr;
}
SsimMapSize IncrementalEvaluator::ssimMapSize() const {
    const State& s = *mState;
    if (!s.ssimOn) return metrics::ssimMapSize(s.width, s.height, s.parameters);
    return {s.kernel.mapWidth, s.kernel.mapHeight, s.kernel.window};
}

}  // namespace lodopt::metrics
