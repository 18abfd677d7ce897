// Render-time estimates for one viewpoint: the API the optimizer's budget check and the
// scheduler use.
//
// A ViewTimeEstimator joins a FeatureTable (per-object, per-level features for one camera and
// render size) with a fitted TimeModel. estimateMs(combination) is O(objects);
// deltaMs(features, object, old, new) is O(1) given the current frame's features, for any
// model (linear or not), because features are additive and the model sees only their sums.
#pragma once

#include <memory>

#include "scenes/scene.hpp"
#include "timemodel/features.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

class ViewTimeEstimator {
public:
    // `model` must be fitted and non-null; it is shared, so feedback applied to it by its
    // owner shows in later estimates. `width`, `height` > 0: render size in pixels.
    ViewTimeEstimator(const scenes::Scene& scene, const scenes::Camera& camera, int width, int height,
                      std::shared_ptr<const TimeModel> model);

    const FeatureTable& table() const { return mTable; }
    const TimeModel& model() const { return *mModel; }

    // Predicted ms of a whole frame, O(objects). `combination` valid for the scene.
    double estimateMs(const scenes::Combination& combination) const;
    // Predicted ms for precomputed features (e.g. kept up to date with table().delta()).
    double estimateMs(const FrameFeatures& features) const { return mModel->estimateMs(features); }
    // Change of the prediction when `object` moves from `oldLevel` to `newLevel` in a frame
    // whose features are `current`, O(1). Levels valid or scenes::kNotDrawn.
    double deltaMs(const FrameFeatures& current, int object, int oldLevel, int newLevel) const;
    // The same from a combination (computes its features first: O(objects)).
    double deltaMs(const scenes::Combination& combination, int object, int newLevel) const;

private:
    FeatureTable mTable;
    std::shared_ptr<const TimeModel> mModel;
};

}  // namespace lodopt::timemodel
