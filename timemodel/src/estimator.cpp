#include "timemodel/estimator.hpp"

#include <cassert>

namespace lodopt::timemodel {

ViewTimeEstimator::ViewTimeEstimator(const scenes::Scene& scene, const scenes::Camera& camera, int width, int height,
                                     std::shared_ptr<const TimeModel> model)
    : mTable(scene, camera, width, height), mModel(std::move(model)) {
    assert(mModel && mModel->fitted());
}

double ViewTimeEstimator::estimateMs(const scenes::Combination& combination) const {
    FrameFeatures features;
    mTable.features(combination, features);
    return mModel->estimateMs(features);
}

double ViewTimeEstimator::deltaMs(const FrameFeatures& current, int object, int oldLevel, int newLevel) const {
    if (oldLevel == newLevel) return 0.0;
    FrameFeatures changed = current;
    changed += mTable.contribution(object, newLevel);
    changed -= mTable.contribution(object, oldLevel);
    return mModel->estimateMs(changed) - mModel->estimateMs(current);
}

double ViewTimeEstimator::deltaMs(const scenes::Combination& combination, int object, int newLevel) const {
    assert(object >= 0 && object < static_cast<int>(combination.size()));
    FrameFeatures current;
    mTable.features(combination, current);
    return deltaMs(current, object, combination[object], newLevel);
}

}  // namespace lodopt::timemodel
