// Per-object screen-size switch thresholds fitted to the optimizer's choices over many views
// (what `lodopt thresholds` runs on a sweep), in every engine's convention.
//
// For each object, every fitting view that searched it gives a sample at its screen size there,
// priced per level: by what drawing each level instead of the optimizer's costs at that view in
// fitness, time converted at the view's exchange rate (level_costs.hpp, measured), or else by the
// level error weighted by the square of the screen size (the object's share of the view's pixels
// up to a constant). scheduler::fitScreenThresholdsToCosts gives the thresholds that minimise
// the summed price. Objects no fitting view searched take the rule fitted to the pooled samples
// of every object with as many levels (`fitted` false; the halving chain 1, 1/2, 1/4, ... where
// no object of that level count was searched). Optionally (`priorSamples` > 0) every object's
// own samples are weighed against that pool too, which counts as `priorSamples` of the object's
// own average sample: an object seen in a few views only then leans on the shared rule instead of
// being pinned by those few. Views held out of the fit (every holdoutEvery-th view) measure how well the rule
// predicts choices it has not seen. docs/thresholds.md.
#pragma once

#include <span>
#include <vector>

#include "scenes/scene.hpp"
#include "scheduler/switch_control.hpp"

namespace lodopt::evaluation {

// One view's optimizer answer as a sweep records it (per scene object).
struct ViewChoices {
    std::vector<int> levels;
    std::vector<double> screenSizes;
    std::vector<int> searched;  // object indices the search chose for
};

bool isHeldOutView(std::size_t view, int holdoutEvery);

// What drawing each level costs at one view, per entry of its `searched` (level_costs.hpp:
// lambda dT - dF, in fitness, 0 at the answer's level).
struct ViewLevelCosts {
    double lambda = 0.0;  // the view's exchange rate, fitness per millisecond
    std::vector<std::vector<double>> levelCost;
};

struct ThresholdSettings {
    double fovYDegrees = 45.0;  // for the distance conventions
    double aspect = 1.0;        // view width / height, for Babylon.js's coverage
    int holdoutEvery = 4;       // views k with k % holdoutEvery == holdoutEvery - 1 are held out; 0: none
    // The switch band engines with one apply (three.js LOD.addLevel's hysteresis, Unreal's
    // skeletal LODHysteresis), as a fraction of the switch distance: an object that went coarser
    // at distance d goes finer again only closer than d (1 - hysteresis). The default is the
    // scheduler's switch-control margin (scheduler::SwitchControlParameters::raiseMargin).
    // How much the shared rule (every object with the same level count, pooled) weighs in each
    // searched object's fit, in the object's own average samples; 0: each object alone (objects
    // never searched still take the shared rule). 0 by default: with measured level costs the
    // pool lowered the held-out fitness on every sweep measured (docs/thresholds.md).
    double priorSamples = 0.0;
    double hysteresis = scheduler::SwitchControlParameters{}.raiseMargin;  // [0, 1)
};

struct ObjectThresholds {
    int object = 0;
    int levelCount = 1;
    bool fitted = false;
    std::vector<double> fittedScreenSize;  // levelCount - 1 thresholds, non-increasing, as fitted
    double lodBias = 1.0;                  // applied by applyLodBias
    std::vector<double> screenSize;        // fittedScreenSize / lodBias: what the engine is given
    int fitSamples = 0;
    int heldOutSamples = 0;
    double fitAgreement = 0.0;      // weighted share of fitting samples the rule reproduces
    double heldOutAgreement = 0.0;  // the same on held-out samples (NaN without any)
    // The thresholds in the engines' conventions (scenes/engine_lod.hpp), same order.
    std::vector<double> unityRelativeHeight;
    std::vector<double> unrealScreenSize;
    std::vector<double> switchDistance;  // three.js LOD distances, Babylon.js addLODLevel distances
    std::vector<double> babylonCoverage;
    // Unreal's LODHysteresis per switch (screen size above the threshold an object must reach to
    // go finer again): the same band as `hysteresis` of the distance, t h / (1 - h).
    std::vector<double> unrealHysteresis;
};

// One result per scene object. With `costs` (one per view; held-out views' may be empty), each
// fitting sample is priced by its view's level costs (scheduler::fitScreenThresholdsToCosts);
// without, by the level error weighted by the screen size squared. Throws std::invalid_argument
// when a view's vectors do not have one entry per object or name an object out of range, or a
// fitting view's costs do not have one list of level costs per searched object.
std::vector<ObjectThresholds> fitEngineThresholds(const scenes::Scene& scene, std::span<const ViewChoices> views,
                                                  const ThresholdSettings& settings,
                                                  std::span<const ViewLevelCosts> costs = {});

// Scales every object's thresholds to fittedScreenSize / bias (a global LOD bias baked into the
// exported values, so engines keep theirs at 1) and recomputes the engine conventions.
// bias > 0, finite.
void applyLodBias(const scenes::Scene& scene, std::vector<ObjectThresholds>& results, double bias,
                  const ThresholdSettings& settings);

}  // namespace lodopt::evaluation
