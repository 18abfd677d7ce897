#include "evaluation/engine_thresholds.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scenes/engine_lod.hpp"
#include "scheduler/screen_thresholds.hpp"

namespace lodopt::evaluation {

namespace {

bool isHeldOut(std::size_t view, int every) { return every > 0 && int(view % std::size_t(every)) == every - 1; }

double agreement(std::span<const double> thresholds, const std::vector<scheduler::ThresholdSample>& samples) {
    double total = 0.0, agreeing = 0.0;
    for (const scheduler::ThresholdSample& s : samples) {
        total += s.weight;
        if (scheduler::levelForScreenSize(thresholds, s.screenSize) == s.level) agreeing += s.weight;
    }
    return total > 0.0 ? agreeing / total : NAN;
}

}  // namespace

std::vector<ObjectThresholds> fitEngineThresholds(const scenes::Scene& scene, std::span<const ViewChoices> views,
                                                  const ThresholdSettings& settings) {
    const std::size_t objects = scene.objects.size();
    std::vector<std::vector<scheduler::ThresholdSample>> fitting(objects), heldOut(objects);
    for (std::size_t v = 0; v < views.size(); ++v) {
        const ViewChoices& view = views[v];
        if (view.levels.size() != objects || view.screenSizes.size() != objects) {
            throw std::invalid_argument("fitEngineThresholds: view " + std::to_string(v) +
                                        " needs one level and one screen size per object");
        }
        for (int object : view.searched) {
            if (object < 0 || std::size_t(object) >= objects) {
                throw std::invalid_argument("fitEngineThresholds: view " + std::to_string(v) + " names object " +
                                            std::to_string(object));
            }
            const double size = view.screenSizes[std::size_t(object)];
            if (!(size > 0.0) || !std::isfinite(size)) continue;
            const scheduler::ThresholdSample sample{size, view.levels[std::size_t(object)], size * size};
            (isHeldOut(v, settings.holdoutEvery) ? heldOut : fitting)[std::size_t(object)].push_back(sample);
        }
    }
    std::vector<ObjectThresholds> results(objects);
    for (std::size_t i = 0; i < objects; ++i) {
        ObjectThresholds& r = results[i];
        const scenes::Object& object = scene.objects[i];
        r.object = int(i);
        r.levelCount = int(object.levels.size());
        const scheduler::ThresholdFit fit = scheduler::fitScreenThresholds(fitting[i], r.levelCount);
        r.fitted = !fitting[i].empty();
        r.screenSize = fit.thresholds;
        r.fitSamples = int(fitting[i].size());
        r.heldOutSamples = int(heldOut[i].size());
        r.fitAgreement = r.fitted ? fit.agreement : NAN;
        r.heldOutAgreement = agreement(r.screenSize, heldOut[i]);
        const scenes::Bounds bounds = scenes::worldBounds(object, 0);
        for (double t : r.screenSize) {
            r.unityRelativeHeight.push_back(scenes::unityRelativeHeight(t, bounds));
            r.unrealScreenSize.push_back(scenes::unrealScreenSize(t));
            r.switchDistance.push_back(scenes::switchDistance(t, bounds, settings.fovYDegrees));
            r.babylonCoverage.push_back(scenes::babylonScreenCoverage(t, settings.aspect));
        }
    }
    return results;
}

}  // namespace lodopt::evaluation
