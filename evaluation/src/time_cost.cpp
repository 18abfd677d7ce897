#include "evaluation/time_cost.hpp"

#include <algorithm>
#include <cmath>

namespace lodopt::evaluation {

TimeModelCost::TimeModelCost(const ViewSetup& setup, FrameTimeEstimator estimator)
    : mSetup(setup),
      mTable(setup.scene(), setup.camera(), setup.width(), setup.height()),
      mEstimator(std::move(estimator)) {}

double TimeModelCost::predictSceneMs(const scenes::Combination& combination) const {
    const double ms = mEstimator(mTable.features(combination));
    // A model is fitted to measured times; guard the optimizer against a broken one.
    return std::isfinite(ms) ? std::max(ms, 0.0) : 0.0;
}

double TimeModelCost::predictMs(const optimizer::Combination& combination) const {
    return predictSceneMs(mSetup.toScene(combination));
}

double TimeModelCost::deltaMs(const optimizer::Combination& combination, int variable, int newLevel) const {
    const scenes::Combination levels = mSetup.toScene(combination);
    const int object = mSetup.variableObjects()[variable];
    const int oldLevel = levels[object];
    const int level = mSetup.objects()[object].optionLevels[newLevel];
    timemodel::FrameFeatures before = mTable.features(levels);
    timemodel::FrameFeatures after = before + mTable.delta(object, oldLevel, level);
    auto clampMs = [](double ms) { return std::isfinite(ms) ? std::max(ms, 0.0) : 0.0; };
    return clampMs(mEstimator(after)) - clampMs(mEstimator(before));
}

}  // namespace lodopt::evaluation
