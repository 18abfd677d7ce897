// Per-object screen-size switch thresholds fitted to the optimizer's choices over many views
// (what `lodopt thresholds` runs on a sweep), in every engine's convention.
//
// For each object, every fitting view that searched it gives a sample: its screen size there,
// the level the optimizer chose, and a weight, the square of the screen size (the object's share
// of the view's pixels, up to a constant: a wrong level on an object that fills the view costs
// more than on a speck). scheduler::fitScreenThresholds gives the thresholds; views held out of
// the fit (every holdoutEvery-th view) measure how well the rule predicts choices it has not
// seen. Objects no fitting view searched keep the halving chain 1, 1/2, 1/4, ... (`fitted`
// false). docs/thresholds.md.
#pragma once

#include <span>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::evaluation {

// One view's optimizer answer as a sweep records it (per scene object).
struct ViewChoices {
    std::vector<int> levels;
    std::vector<double> screenSizes;
    std::vector<int> searched;  // object indices the search chose for
};

struct ThresholdSettings {
    double fovYDegrees = 45.0;  // for the distance conventions
    double aspect = 1.0;        // view width / height, for Babylon.js's coverage
    int holdoutEvery = 4;       // views k with k % holdoutEvery == holdoutEvery - 1 are held out; 0: none
};

struct ObjectThresholds {
    int object = 0;
    int levelCount = 1;
    bool fitted = false;
    std::vector<double> screenSize;  // levelCount - 1 thresholds, non-increasing
    int fitSamples = 0;
    int heldOutSamples = 0;
    double fitAgreement = 0.0;      // weighted share of fitting samples the rule reproduces
    double heldOutAgreement = 0.0;  // the same on held-out samples (NaN without any)
    // The thresholds in the engines' conventions (scenes/engine_lod.hpp), same order.
    std::vector<double> unityRelativeHeight;
    std::vector<double> unrealScreenSize;
    std::vector<double> switchDistance;  // three.js LOD distances, Babylon.js addLODLevel distances
    std::vector<double> babylonCoverage;
};

// One result per scene object. Throws std::invalid_argument when a view's vectors do not have
// one entry per object or name an object out of range.
std::vector<ObjectThresholds> fitEngineThresholds(const scenes::Scene& scene, std::span<const ViewChoices> views,
                                                  const ThresholdSettings& settings);

}  // namespace lodopt::evaluation
