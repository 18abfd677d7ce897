// Tuning space and compass search for the scheduler's coefficients (see scheduler/tuning.hpp).
#include "scheduler/tuning.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include "timemodel/calibration.hpp"

namespace lodopt::scheduler {

const char* toString(ImportanceForm form) {
    return form == ImportanceForm::Extended ? "extended" : "published";
}

namespace {

double medianOrOne(std::vector<double>& values) {
    if (values.empty()) return 1.0;
    const std::size_t middle = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + middle, values.end());
    const double median = values[middle];
    return median > 0.0 && std::isfinite(median) ? median : 1.0;
}

}  // namespace

TermScales measureTermScales(const SceneIndex& index, const std::vector<scenes::Camera>& cameras) {
    std::vector<double> distance, area, pixels, center;
    FrameObjects frame;
    for (const scenes::Camera& camera : cameras) {
        index.beginFrame(camera, frame);
        for (int o = 0; o < index.objectCount(); ++o) {
            if (!index.observe(o, frame)) continue;
            const ImportanceTerms terms = importanceTerms(frame.views[o]);
            distance.push_back(terms.distance);
            area.push_back(terms.area);
            pixels.push_back(terms.pixels);
            center.push_back(terms.center);
        }
    }
    return {medianOrOne(distance), medianOrOne(area), medianOrOne(pixels), medianOrOne(center)};
}

TuningSpace::TuningSpace(ImportanceForm form, TermScales scales, int thresholdCount)
    : mForm(form), mScales(scales), mThresholdCount(thresholdCount) {
    assert(thresholdCount >= 1);
    auto add = [&](const char* name, double low, double high, double step) {
        mNames.push_back(name);
        mLower.push_back(low);
        mUpper.push_back(high);
        mSteps.push_back(step);
    };
    add("area_share", -7.0, 7.0, 1.0);
    if (form == ImportanceForm::Extended) {
        // Wide first steps: the extended terms start switched off at the lower bound.
        add("pixels_share", -7.0, 4.0, 4.0);
        add("center_share", -7.0, 4.0, 4.0);
    }
    add("first_threshold", std::log(0.5), std::log(2000.0), 0.7);
    add("threshold_ratio", std::log(1.05), std::log(8.0), 0.3);
    add("benchmark_scale", -3.0, 3.0, 0.5);
}

std::vector<double> TuningSpace::pointOf(const SchedulerCoefficients& c) const {
    std::vector<double> x;
    const double a1 = std::max(c.importance.alpha1, 1e-12) * mScales.distance;
    auto share = [&](double alpha, double scale) { return alpha > 0.0 ? std::log(alpha * scale / a1) : -1e9; };
    x.push_back(share(c.importance.alpha2, mScales.area));
    if (mForm == ImportanceForm::Extended) {
        x.push_back(share(c.importance.alpha3, mScales.pixels));
        x.push_back(share(c.importance.alpha4, mScales.center));
    }
    const std::vector<double>& t = c.thresholds.values;
    const double first = t.empty() ? 4.0 : t.front();
    double ratio = 2.0;
    if (t.size() >= 2) ratio = std::pow(t.back() / t.front(), 1.0 / double(t.size() - 1));
    x.push_back(std::log(first));
    x.push_back(std::log(ratio));
    x.push_back(std::log(c.benchmark.view ? 1.0 : c.benchmark.scale));
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::clamp(x[i], mLower[i], mUpper[i]);
    return x;
}

SchedulerCoefficients TuningSpace::coefficientsAt(const std::vector<double>& x) const {
    assert(int(x.size()) == dimension());
    std::size_t i = 0;
    SchedulerCoefficients c;
    ImportanceCoefficients& a = c.importance;
    a.alpha1 = 1.0 / mScales.distance;
    a.alpha2 = std::exp(x[i++]) / mScales.area;
    a.alpha3 = 0.0;
    a.alpha4 = 0.0;
    if (mForm == ImportanceForm::Extended) {
        a.alpha3 = std::exp(x[i++]) / mScales.pixels;
        a.alpha4 = std::exp(x[i++]) / mScales.center;
    }
    const double sum = a.alpha1 + a.alpha2 + a.alpha3 + a.alpha4;
    a.alpha1 /= sum;
    a.alpha2 /= sum;
    a.alpha3 /= sum;
    a.alpha4 /= sum;
    const double first = std::exp(x[i++]);
    const double ratio = std::exp(x[i++]);
    c.thresholds = DistanceThresholds::geometric(first, ratio, mThresholdCount);
    c.benchmark.scale = std::exp(x[i++]);
    return c;
}

PatternSearchResult patternSearch(const std::function<double(const std::vector<double>&)>& objective,
                                  std::vector<double> start, const std::vector<double>& lower,
                                  const std::vector<double>& upper, std::vector<double> steps,
                                  const PatternSearchOptions& options) {
    const std::size_t n = start.size();
    assert(lower.size() == n && upper.size() == n && steps.size() == n && options.maxEvaluations >= 1);
    PatternSearchResult result;
    result.best = std::move(start);
    result.bestValue = objective(result.best);
    result.evaluations = 1;
    result.bestByEvaluation.push_back(result.bestValue);
    const std::vector<double> initialSteps = steps;
    timemodel::SplitMix64 rng(options.seed);
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    auto finished = [&] {
        if (result.evaluations >= options.maxEvaluations) return true;
        for (std::size_t i = 0; i < n; ++i) {
            if (steps[i] >= initialSteps[i] / 64.0) return false;
        }
        return true;
    };
    while (!finished()) {
        for (std::size_t i = n; i > 1; --i) std::swap(order[i - 1], order[std::size_t(rng.below(int(i)))]);
        bool improved = false;
        for (std::size_t k = 0; k < n && !improved && result.evaluations < options.maxEvaluations; ++k) {
            const std::size_t i = order[k];
            for (double sign : {1.0, -1.0}) {
                if (result.evaluations >= options.maxEvaluations) break;
                std::vector<double> trial = result.best;
                trial[i] = std::clamp(trial[i] + sign * steps[i], lower[i], upper[i]);
                if (trial[i] == result.best[i]) continue;  // at the bound
                const double value = objective(trial);
                ++result.evaluations;
                if (value > result.bestValue) {
                    result.best = std::move(trial);
                    result.bestValue = value;
                    improved = true;
                }
                result.bestByEvaluation.push_back(result.bestValue);
                if (improved) break;
            }
        }
        if (!improved) {
            for (double& step : steps) step *= 0.5;
        }
    }
    return result;
}

}  // namespace lodopt::scheduler
