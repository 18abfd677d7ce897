// RegionScorer: scores of window sets (see the header). Per-window values come from the same
// kernels as evaluate() (ssimWindows, sobelBinsRow, grayBinsRow), and every sum is an integer,
// so a partition's totals give evaluate()'s bits.
#include "metrics/region_scorer.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "kernels.hpp"
#include "prepared_reference.hpp"

namespace lodopt::metrics {

namespace {
// SSIM windows of a set are computed in bands of this many map rows, over each band's
// column extent (a set is often a thin seam between objects: short bands waste less).
constexpr int kBandRows = 16;
// scoreMany joins the runs of one band into one computed rectangle when they are at most this
// many columns apart: a separate rectangle costs its own horizontal-pass margin (window - 1
// columns) and a call.
constexpr int kJoinColumns = 16;
}  // namespace

void WindowTotals::add(SsimFixedSum setSsim, std::span<const BinCount> setGray, std::span<const BinCount> setSobel,
                       int sign) {
    ssim += sign > 0 ? setSsim : -setSsim;
    for (const auto& [bin, count] : setGray) gray[bin] += sign * std::int64_t(count);
    for (const auto& [bin, count] : setSobel) sobel[bin] += sign * std::int64_t(count);
}

struct RegionScorer::State : detail::PreparedReference {};

class RegionScorer::Work {
public:
    std::vector<std::int32_t> gray;  // the candidate, as loaded
    std::vector<double> band;        // kBandRows map rows
    detail::SsimScratch scratch;
    std::vector<std::uint8_t> grayBins;
    std::vector<std::uint16_t> sobelBins;
    std::array<std::uint32_t, 256> grayCounts{};
    std::vector<std::uint32_t> sobelCounts;
    std::vector<std::size_t> cursors;  // scoreMany: per set, its first SSIM run not yet summed
    std::vector<WindowRun> bandRuns;   // scoreMany: one band's runs of every set
};

bool RegionScorer::supports(const MetricParameters& parameters) {
    return !parameters.computePrecisionRecall &&
           (parameters.boundaryEntropyWeight <= 0 || parameters.boundaryEntropyMode == EntropyMode::Histogram) &&
           (parameters.informationEntropyWeight <= 0 || parameters.informationEntropyMode == EntropyMode::Histogram);
}

RegionScorer::RegionScorer(const ImageView& reference, const MetricParameters& parameters)
    : mState(std::make_unique<State>()) {
    validateParameters(parameters);
    if (!supports(parameters)) {
        throw MetricError("region scores need the histogram entropies and no precision/recall");
    }
    detail::SsimScratch scratch;
    detail::prepareReference(reference, parameters, *mState, scratch);
}

RegionScorer::~RegionScorer() = default;
RegionScorer::RegionScorer(RegionScorer&&) noexcept = default;
RegionScorer& RegionScorer::operator=(RegionScorer&&) noexcept = default;

int RegionScorer::width() const { return mState->width; }
int RegionScorer::height() const { return mState->height; }
SsimMapSize RegionScorer::ssimMapSize() const {
    const State& s = *mState;
    return s.ssimOn ? SsimMapSize{s.kernel.mapWidth, s.kernel.mapHeight, s.kernel.window} : SsimMapSize{0, 0, 0};
}
int RegionScorer::sobelBins() const { return mState->boundaryOn ? mState->sobel.bins : 0; }
int RegionScorer::grayBins() const { return mState->informationOn ? 256 : 0; }

void RegionScorer::WorkDeleter::operator()(Work* work) const { delete work; }

RegionScorer::WorkPtr RegionScorer::makeWork() const {
    const State& s = *mState;
    WorkPtr work(new Work);
    work->gray.assign(std::size_t(s.width) * s.height, 0);
    if (s.ssimOn) {
        work->band.assign(std::size_t(kBandRows) * s.kernel.mapWidth, 0.0);
        work->scratch.reserve(s.kernel);
    }
    work->grayBins.assign(std::size_t(s.width), 0);
    work->sobelBins.assign(std::size_t(s.width), 0);
    work->sobelCounts.assign(std::size_t(std::max(s.sobel.bins, 1)), 0);
    return work;
}

void RegionScorer::loadPixels(Work& work, const ImageView& candidate, int x0, int y0, int x1, int y1) const {
    const State& s = *mState;
    detail::validateView(candidate, "candidate image");
    if (candidate.width != s.width || candidate.height != s.height || candidate.channels != s.channels) {
        throw MetricError("candidate image is " + std::to_string(candidate.width) + "x" +
                          std::to_string(candidate.height) + "x" + std::to_string(candidate.channels) +
                          ", the reference " + std::to_string(s.width) + "x" + std::to_string(s.height) + "x" +
                          std::to_string(s.channels));
    }
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, s.width);
    y1 = std::min(y1, s.height);
    for (int y = y0; y < y1; ++y) {
        detail::grayRow(candidate.pixels + y * candidate.rowStride + std::ptrdiff_t(x0) * s.channels, s.channels,
                        x1 - x0, s.grayScale, work.gray.data() + std::size_t(y) * s.width + x0);
    }
}

void RegionScorer::score(Work& work, const WindowSet& set, WindowSetScore& out) const {
    const State& s = *mState;
    out.ssim = 0;
    out.gray.clear();
    out.sobel.clear();
    const std::size_t stride = std::size_t(s.width);
    if (s.ssimOn) {
        const std::size_t mapWidth = std::size_t(s.kernel.mapWidth);
        // Runs of one band of kBandRows rows: compute the band's extent, then sum the runs.
        for (std::size_t i = 0; i < set.ssim.size();) {
            const int band = set.ssim[i].y / kBandRows;
            std::size_t j = i;
            int x0 = set.ssim[i].x0, x1 = set.ssim[i].x1;
            while (j < set.ssim.size() && set.ssim[j].y / kBandRows == band) {
                x0 = std::min(x0, set.ssim[j].x0);
                x1 = std::max(x1, set.ssim[j].x1);
                ++j;
            }
            const int y0 = set.ssim[i].y, y1 = set.ssim[j - 1].y + 1;
            const std::size_t at = std::size_t(y0) * mapWidth + std::size_t(x0);
            detail::ssimWindows(work.gray.data(), s.referenceGray.data(), stride, s.kernel, x0, y0, x1, y1,
                                s.referenceMean.data() + at, s.referenceVariance.data() + at, mapWidth,
                                work.scratch, work.band.data(), mapWidth);
            for (; i < j; ++i) {
                const WindowRun& run = set.ssim[i];
                out.ssim += detail::ssimFixedSum(work.band.data() + std::size_t(run.y - y0) * mapWidth +
                                                     std::size_t(run.x0 - x0),
                                                 run.x1 - run.x0);
            }
        }
    }
    histograms(work, set, out);
}

void RegionScorer::histograms(Work& work, const WindowSet& set, WindowSetScore& out) const {
    const State& s = *mState;
    out.gray.clear();
    out.sobel.clear();
    const std::size_t stride = std::size_t(s.width);
    if (s.informationOn) {
        for (const WindowRun& run : set.gray) {
            detail::grayBinsRow(work.gray.data() + std::size_t(run.y) * stride + run.x0, run.x1 - run.x0, s.grayScale,
                                work.grayBins.data());
            for (int k = 0; k < run.x1 - run.x0; ++k) ++work.grayCounts[work.grayBins[std::size_t(k)]];
        }
        for (std::size_t b = 0; b < work.grayCounts.size(); ++b) {
            if (work.grayCounts[b] == 0) continue;
            out.gray.emplace_back(std::uint16_t(b), work.grayCounts[b]);
            work.grayCounts[b] = 0;
        }
    }
    if (s.boundaryOn) {
        for (const WindowRun& run : set.sobel) {
            detail::sobelBinsRow(work.gray.data() + std::size_t(run.y) * stride + run.x0, std::ptrdiff_t(stride),
                                 run.x1 - run.x0, s.sobel, work.sobelBins.data());
            for (int k = 0; k < run.x1 - run.x0; ++k) ++work.sobelCounts[work.sobelBins[std::size_t(k)]];
        }
        for (std::size_t b = 0; b < work.sobelCounts.size(); ++b) {
            if (work.sobelCounts[b] == 0) continue;
            out.sobel.emplace_back(std::uint16_t(b), work.sobelCounts[b]);
            work.sobelCounts[b] = 0;
        }
    }
}

void RegionScorer::scoreMany(Work& work, std::span<const WindowSet* const> sets,
                             std::span<WindowSetScore* const> outs) const {
    const State& s = *mState;
    if (sets.size() != outs.size()) throw MetricError("scoreMany: as many scores as sets are needed");
    if (sets.size() == 1) {
        score(work, *sets[0], *outs[0]);
        return;
    }
    for (WindowSetScore* out : outs) out->ssim = 0;
    if (s.ssimOn) {
        const std::size_t mapWidth = std::size_t(s.kernel.mapWidth);
        const std::size_t stride = std::size_t(s.width);
        work.cursors.assign(sets.size(), 0);
        for (;;) {
            // The next band any set has runs in, and all those runs.
            int band = -1;
            for (std::size_t k = 0; k < sets.size(); ++k) {
                if (work.cursors[k] == sets[k]->ssim.size()) continue;
                const int b = sets[k]->ssim[work.cursors[k]].y / kBandRows;
                if (band < 0 || b < band) band = b;
            }
            if (band < 0) break;
            work.bandRuns.clear();
            for (std::size_t k = 0; k < sets.size(); ++k) {
                const std::vector<WindowRun>& runs = sets[k]->ssim;
                for (std::size_t j = work.cursors[k]; j < runs.size() && runs[j].y / kBandRows == band; ++j) {
                    work.bandRuns.push_back(runs[j]);
                }
            }
            std::sort(work.bandRuns.begin(), work.bandRuns.end(),
                      [](const WindowRun& a, const WindowRun& b) { return a.x0 < b.x0; });
            // Clusters of runs less than kJoinColumns apart: one rectangle of windows each,
            // written at its place in the band buffer (row y at (y - bandTop) * mapWidth).
            const int bandTop = band * kBandRows;
            for (std::size_t i = 0; i < work.bandRuns.size();) {
                int x0 = work.bandRuns[i].x0, x1 = work.bandRuns[i].x1;
                int y0 = work.bandRuns[i].y, y1 = work.bandRuns[i].y + 1;
                std::size_t j = i + 1;
                while (j < work.bandRuns.size() && work.bandRuns[j].x0 <= x1 + kJoinColumns) {
                    x1 = std::max(x1, work.bandRuns[j].x1);
                    y0 = std::min(y0, work.bandRuns[j].y);
                    y1 = std::max(y1, work.bandRuns[j].y + 1);
                    ++j;
                }
                const std::size_t at = std::size_t(y0) * mapWidth + std::size_t(x0);
                detail::ssimWindows(work.gray.data(), s.referenceGray.data(), stride, s.kernel, x0, y0, x1, y1,
                                    s.referenceMean.data() + at, s.referenceVariance.data() + at, mapWidth,
                                    work.scratch, work.band.data() + std::size_t(y0 - bandTop) * mapWidth + x0,
                                    mapWidth);
                i = j;
            }
            for (std::size_t k = 0; k < sets.size(); ++k) {
                const std::vector<WindowRun>& runs = sets[k]->ssim;
                std::size_t& j = work.cursors[k];
                for (; j < runs.size() && runs[j].y / kBandRows == band; ++j) {
                    outs[k]->ssim += detail::ssimFixedSum(
                        work.band.data() + std::size_t(runs[j].y - bandTop) * mapWidth + std::size_t(runs[j].x0),
                        runs[j].x1 - runs[j].x0);
                }
            }
        }
    }
    for (std::size_t k = 0; k < sets.size(); ++k) histograms(work, *sets[k], *outs[k]);
}

WindowTotals RegionScorer::emptyTotals() const {
    WindowTotals totals;
    totals.gray.assign(256, 0);
    totals.sobel.assign(std::size_t(std::max(mState->sobel.bins, 1)), 0);
    return totals;
}

MetricResult RegionScorer::result(const WindowTotals& totals) const {
    const State& s = *mState;
    MetricResult result;
    // Histograms of a partition hold non-negative counts; as unsigned, the same values.
    auto counts = [](const std::vector<std::int64_t>& histogram) {
        return reinterpret_cast<const std::uint64_t*>(histogram.data());
    };
    if (s.ssimOn) {
        result.ssimComputed = true;
        result.ssim = detail::ssimMeanFromFixed(totals.ssim, std::uint64_t(s.kernel.mapWidth) *
                                                                 std::uint64_t(s.kernel.mapHeight));
    }
    if (s.boundaryOn) {
        result.boundaryEntropy.computed = true;
        result.boundaryEntropy.reference = s.boundaryReference;
        const std::uint64_t interior =
            std::uint64_t(std::max(s.width - 2, 0)) * std::uint64_t(std::max(s.height - 2, 0));
        result.boundaryEntropy.candidate = detail::histogramEntropy(counts(totals.sobel), s.sobel.bins, interior);
    }
    if (s.informationOn) {
        result.informationEntropy.computed = true;
        result.informationEntropy.reference = s.informationReference;
        const std::uint64_t pixels = std::uint64_t(s.width) * std::uint64_t(s.height);
        result.informationEntropy.candidate = detail::histogramEntropy(counts(totals.gray), 256, pixels);
    }
    fuse(result, s.parameters);
    return result;
}

}  // namespace lodopt::metrics
