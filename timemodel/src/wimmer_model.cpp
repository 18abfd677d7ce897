// CITY17 after Wimmer & Wonka 2003: RT = RT_system + max(RT_cpu, RT_gpu),
// RT_gpu = c1·#transformed_vertices + c2·#pixels, RT_cpu = c3·#matrices + c4·#bounding_boxes
// + c5·#textures (draw calls). The papers fit the constants "by regression"; a max of two
// linear terms is fitted here by alternating between assigning each sample to the regime that
// dominates it and a non-negative least-squares fit of that assignment (a max-affine fit),
// from several starting assignments, keeping the lowest relative error of the max model.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "least_squares.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

namespace {

enum Column : std::size_t { kSystem = 0, kGpuVertices, kGpuPixels, kCpuMatrices, kCpuBoxes, kCpuDrawCalls, kColumns };

double relativeObjective(const WimmerModel& model, const std::vector<Sample>& samples) {
    double sum = 0.0;
    for (const Sample& s : samples) {
        const double e = (model.estimateMs(s.features) - s.measuredMs) / s.measuredMs;
        sum += e * e;
    }
    return sum;
}

// A fixed, portable sequence for the random starting assignments (SplitMix64).
std::uint64_t splitMix(std::uint64_t& state) {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

}  // namespace

std::vector<std::string> WimmerModel::coefficientNames() const {
    return {"system_ms", "vertices", "pixels", "matrices", "bounding_boxes", "draw_calls"};
}

double WimmerModel::gpuMs(const FrameFeatures& f) const {
    return mCoefficients[kGpuVertices] * f[Feature::kVertices] + mCoefficients[kGpuPixels] * f[Feature::kPixels];
}

double WimmerModel::cpuMs(const FrameFeatures& f) const {
    return mCoefficients[kCpuMatrices] * f[Feature::kMatrices] + mCoefficients[kCpuBoxes] * f[Feature::kBoundingBoxes] +
           mCoefficients[kCpuDrawCalls] * f[Feature::kDrawCalls];
}

FeatureSet WimmerModel::readFeatures() const {
    if (!fitted()) return everyFeature();
    FeatureSet read;
    for (Feature f :
         {Feature::kVertices, Feature::kPixels, Feature::kMatrices, Feature::kBoundingBoxes, Feature::kDrawCalls}) {
        read.set(std::size_t(f));
    }
    return read;
}

double WimmerModel::estimateCalibratedMs(const FrameFeatures& features) const {
    return mCoefficients[kSystem] + std::max(cpuMs(features), gpuMs(features));
}

FitReport WimmerModel::fitValidated(const std::vector<Sample>& samples) {
    const std::size_t n = samples.size();
    const std::vector<std::string> names = coefficientNames();
    const std::vector<std::size_t> order = {kSystem, kGpuVertices, kGpuPixels, kCpuDrawCalls, kCpuMatrices, kCpuBoxes};
    std::vector<double> target(n), weights(n);
    for (std::size_t r = 0; r < n; ++r) {
        target[r] = samples[r].measuredMs;
        weights[r] = 1.0 / samples[r].measuredMs;
    }

    // Starting assignments (true = CPU-bound): all GPU, all CPU, splits by how draw-call
    // heavy a frame is relative to its vertex and pixel load, and a few pseudo-random ones.
    std::vector<std::vector<bool>> starts = {std::vector<bool>(n, false), std::vector<bool>(n, true)};
    {
        double meanDraw = 0.0, meanVertices = 0.0, meanPixels = 0.0;
        for (const Sample& s : samples) {
            meanDraw += s.features[Feature::kDrawCalls];
            meanVertices += s.features[Feature::kVertices];
            meanPixels += s.features[Feature::kPixels];
        }
        auto norm = [](double value, double mean) { return mean > 0.0 ? value / mean : 0.0; };
        std::vector<double> ratio(n);
        for (std::size_t r = 0; r < n; ++r) {
            const FrameFeatures& f = samples[r].features;
            ratio[r] = norm(f[Feature::kDrawCalls], meanDraw) /
                       (norm(f[Feature::kVertices], meanVertices) + norm(f[Feature::kPixels], meanPixels) + 1e-9);
        }
        std::vector<double> sorted = ratio;
        std::sort(sorted.begin(), sorted.end());
        for (double q : {0.25, 0.5, 0.75}) {
            const double threshold = sorted[std::size_t(q * double(n - 1))];
            std::vector<bool> start(n);
            for (std::size_t r = 0; r < n; ++r) start[r] = ratio[r] > threshold;
            starts.push_back(std::move(start));
        }
        std::uint64_t state = 0x5EED;
        for (int k = 0; k < 4; ++k) {
            std::vector<bool> start(n);
            for (std::size_t r = 0; r < n; ++r) start[r] = (splitMix(state) >> 63) != 0;
            starts.push_back(std::move(start));
        }
    }

    double bestObjective = std::numeric_limits<double>::infinity();
    std::vector<double> bestCoefficients;
    FitReport bestReport;
    std::size_t bestCpuBound = 0;
    for (const std::vector<bool>& start : starts) {
        std::vector<bool> cpuBound = start;
        detail::CheckedFit fit;
        int rounds = 0;
        for (; rounds < 50; ++rounds) {
            detail::Matrix design(n, kColumns);
            for (std::size_t r = 0; r < n; ++r) {
                const FrameFeatures& f = samples[r].features;
                design.at(r, kSystem) = 1.0;
                if (cpuBound[r]) {
                    design.at(r, kCpuMatrices) = f[Feature::kMatrices];
                    design.at(r, kCpuBoxes) = f[Feature::kBoundingBoxes];
                    design.at(r, kCpuDrawCalls) = f[Feature::kDrawCalls];
                } else {
                    design.at(r, kGpuVertices) = f[Feature::kVertices];
                    design.at(r, kGpuPixels) = f[Feature::kPixels];
                }
            }
            fit = detail::fitNonNegative(design, target, weights, order, names, kSystem);
            mCoefficients = fit.coefficients;
            std::vector<bool> next(n);
            for (std::size_t r = 0; r < n; ++r) next[r] = cpuMs(samples[r].features) > gpuMs(samples[r].features);
            if (next == cpuBound) break;
            cpuBound = std::move(next);
        }
        const double objective = relativeObjective(*this, samples);
        if (objective < bestObjective) {
            bestObjective = objective;
            bestCoefficients = mCoefficients;
            bestReport = FitReport{};
            bestReport.notes = fit.notes;
            bestReport.conditionNumber = fit.conditionNumber;
            bestReport.iterations = rounds + 1;
            bestCpuBound = 0;
            for (const Sample& s : samples) bestCpuBound += cpuMs(s.features) > gpuMs(s.features) ? 1 : 0;
        }
    }
    mCoefficients = bestCoefficients;
    bestReport.notes.push_back(std::to_string(bestCpuBound) + " of " + std::to_string(n) +
                               " samples CPU-bound under the fit, the rest GPU-bound");
    return bestReport;
}

}  // namespace lodopt::timemodel
