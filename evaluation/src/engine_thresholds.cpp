#include "evaluation/engine_thresholds.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "scenes/engine_lod.hpp"
#include "scheduler/screen_thresholds.hpp"

namespace lodopt::evaluation {

namespace {

double agreement(std::span<const double> thresholds, const std::vector<scheduler::ThresholdSample>& samples) {
    double total = 0.0, agreeing = 0.0;
    for (const scheduler::ThresholdSample& s : samples) {
        total += s.weight;
        if (scheduler::levelForScreenSize(thresholds, s.screenSize) == s.level) agreeing += s.weight;
    }
    return total > 0.0 ? agreeing / total : NAN;
}

void setConventions(const scenes::Object& object, ObjectThresholds& r, const ThresholdSettings& settings) {
    const scenes::Bounds bounds = scenes::worldBounds(object, 0);
    r.unityRelativeHeight.clear();
    r.unrealScreenSize.clear();
    r.switchDistance.clear();
    r.babylonCoverage.clear();
    r.unrealHysteresis.clear();
    for (double t : r.screenSize) {
        r.unityRelativeHeight.push_back(scenes::unityRelativeHeight(t, bounds));
        r.unrealScreenSize.push_back(scenes::unrealScreenSize(t));
        r.switchDistance.push_back(scenes::switchDistance(t, bounds, settings.fovYDegrees));
        r.babylonCoverage.push_back(scenes::babylonScreenCoverage(t, settings.aspect));
        r.unrealHysteresis.push_back(scenes::unrealScreenSize(t) * settings.hysteresis / (1.0 - settings.hysteresis));
    }
}

}  // namespace

bool isHeldOutView(std::size_t view, int holdoutEvery) {
    return holdoutEvery > 0 && int(view % std::size_t(holdoutEvery)) == holdoutEvery - 1;
}

namespace {

// A sample's spread of costs: what the worst level costs over the best.
double spread(const scheduler::PricedSample& sample) {
    const auto [low, high] = std::minmax_element(sample.levelCost.begin(), sample.levelCost.end());
    return *high - *low;
}

}  // namespace

std::vector<ObjectThresholds> fitEngineThresholds(const scenes::Scene& scene, std::span<const ViewChoices> views,
                                                  const ThresholdSettings& settings,
                                                  std::span<const ViewLevelCosts> costs) {
    const std::size_t objects = scene.objects.size();
    if (!costs.empty() && costs.size() != views.size()) {
        throw std::invalid_argument("fitEngineThresholds: one level-cost entry per view, or none");
    }
    std::vector<std::vector<scheduler::PricedSample>> fitting(objects);
    std::vector<std::vector<scheduler::ThresholdSample>> fittingChoices(objects), heldOut(objects);
    for (std::size_t v = 0; v < views.size(); ++v) {
        const ViewChoices& view = views[v];
        if (view.levels.size() != objects || view.screenSizes.size() != objects) {
            throw std::invalid_argument("fitEngineThresholds: view " + std::to_string(v) +
                                        " needs one level and one screen size per object");
        }
        const bool held = isHeldOutView(v, settings.holdoutEvery);
        if (!held && !costs.empty() && costs[v].levelCost.size() != view.searched.size()) {
            throw std::invalid_argument("fitEngineThresholds: view " + std::to_string(v) +
                                        " needs level costs for each searched object");
        }
        for (std::size_t entry = 0; entry < view.searched.size(); ++entry) {
            const int object = view.searched[entry];
            if (object < 0 || std::size_t(object) >= objects) {
                throw std::invalid_argument("fitEngineThresholds: view " + std::to_string(v) + " names object " +
                                            std::to_string(object));
            }
            const auto i = std::size_t(object);
            const double size = view.screenSizes[i];
            if (!(size > 0.0) || !std::isfinite(size)) continue;
            const scheduler::ThresholdSample sample{size, view.levels[i], size * size};
            if (held) {
                heldOut[i].push_back(sample);
                continue;
            }
            fittingChoices[i].push_back(sample);
            const int levels = int(scene.objects[i].levels.size());
            scheduler::PricedSample priced{size, std::vector<double>(std::size_t(levels))};
            if (costs.empty()) {
                for (int k = 0; k < levels; ++k) priced.levelCost[std::size_t(k)] = sample.weight * std::abs(k - sample.level);
            } else {
                priced.levelCost = costs[v].levelCost[entry];
                if (priced.levelCost.size() != std::size_t(levels)) {
                    throw std::invalid_argument("fitEngineThresholds: view " + std::to_string(v) +
                                                ": level costs of object " + std::to_string(object) +
                                                " do not have one value per level");
                }
            }
            fitting[i].push_back(std::move(priced));
        }
    }
    // The pooled samples of all objects with the same level count: the shared rule each object's
    // own samples are weighed against.
    std::map<int, std::vector<scheduler::PricedSample>> pooled;
    for (std::size_t i = 0; i < objects; ++i) {
        std::vector<scheduler::PricedSample>& list = pooled[int(scene.objects[i].levels.size())];
        list.insert(list.end(), fitting[i].begin(), fitting[i].end());
    }
    std::vector<ObjectThresholds> results(objects);
    for (std::size_t i = 0; i < objects; ++i) {
        ObjectThresholds& r = results[i];
        const scenes::Object& object = scene.objects[i];
        r.object = int(i);
        r.levelCount = int(object.levels.size());
        std::vector<scheduler::PricedSample> samples = fitting[i];
        const auto shared = pooled.find(r.levelCount);
        if (shared != pooled.end() && !shared->second.empty() && (samples.empty() || settings.priorSamples > 0.0)) {
            double own = 0.0, all = 0.0;
            for (const scheduler::PricedSample& sample : samples) own += spread(sample);
            for (const scheduler::PricedSample& sample : shared->second) all += spread(sample);
            // The pool weighs as much as priorSamples of the object's own average sample (all of
            // it when the object has none).
            const double scale = samples.empty() || !(own > 0.0) || !(all > 0.0)
                                     ? 1.0
                                     : settings.priorSamples * own / double(samples.size()) / all;
            for (scheduler::PricedSample sample : shared->second) {
                for (double& cost : sample.levelCost) cost *= scale;
                samples.push_back(std::move(sample));
            }
        }
        const scheduler::ThresholdFit fit = scheduler::fitScreenThresholdsToCosts(samples, r.levelCount);
        r.fitted = !fitting[i].empty();
        r.fittedScreenSize = fit.thresholds;
        r.screenSize = fit.thresholds;
        r.fitSamples = int(fitting[i].size());
        r.heldOutSamples = int(heldOut[i].size());
        r.fitAgreement = agreement(r.screenSize, fittingChoices[i]);
        r.heldOutAgreement = agreement(r.screenSize, heldOut[i]);
        setConventions(object, r, settings);
    }
    return results;
}

void applyLodBias(const scenes::Scene& scene, std::vector<ObjectThresholds>& results, double bias,
                  const ThresholdSettings& settings) {
    if (!(bias > 0.0) || !std::isfinite(bias)) throw std::invalid_argument("applyLodBias: the bias must be > 0");
    for (ObjectThresholds& r : results) {
        r.lodBias = bias;
        r.screenSize.clear();
        for (double t : r.fittedScreenSize) r.screenSize.push_back(t / bias);
        setConventions(scene.objects.at(std::size_t(r.object)), r, settings);
    }
}

}  // namespace lodopt::evaluation
