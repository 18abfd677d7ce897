// The optimizer's Cost for one prepared view: the time model's prediction for the scene
// combination that an optimizer combination stands for (skipped objects at their fixed level).
//
// Features come from a timemodel::FeatureTable built once per view (per-object, per-level
// contributions). The skipped objects never change, so their sum is taken once: a prediction
// is a sum over the optimizer's variables plus one model evaluation (the search calls it for
// every candidate and every repair step; summing all the scene's objects each time took an
// eighth of a forest search). deltasMs sums a combination's features once for all the steps
// asked from it. The scheduler keeps its frame's features the same way, as a sum it updates
// one level change at a time (scheduler::SceneIndex contributions, FrameScheduler::setLevel).
#pragma once

#include <functional>

#include "evaluation/evaluation.hpp"
#include "timemodel/features.hpp"

namespace lodopt::evaluation {

// Milliseconds predicted for a frame's features (a fitted time model).
using FrameTimeEstimator = std::function<double(const timemodel::FrameFeatures&)>;

class TimeModelCost final : public optimizer::Cost {
public:
    // Reads `setup` here only (the table keeps its own contributions); `estimator` returns
    // finite milliseconds >= 0 and reads only the features in `needed` (its model's
    // readFeatures(): the table skips the work of the others).
    TimeModelCost(const ViewSetup& setup, FrameTimeEstimator estimator,
                  const timemodel::FeatureSet& needed = timemodel::everyFeature());

    double predictMs(const optimizer::Combination& combination) const override;
    // O(searched objects) per call: ask deltasMs for several steps from one combination.
    double deltaMs(const optimizer::Combination& combination, int variable, int newLevel) const override;
    void deltasMs(const optimizer::Combination& combination, std::span<const int> newLevels,
                  std::span<double> deltas) const override;

    double predictSceneMs(const scenes::Combination& combination) const;
    const timemodel::FeatureTable& table() const { return mTable; }

private:
    timemodel::FrameFeatures featuresOf(const optimizer::Combination& combination) const;
    // The prediction after `variable` moves from option `from` to `to` in a frame of `before`.
    double stepMs(const timemodel::FrameFeatures& before, std::size_t variable, int from, int to) const;

    timemodel::FeatureTable mTable;
    FrameTimeEstimator mEstimator;
    timemodel::FrameFeatures mFixed;                             // frame constant + skipped objects
    std::vector<std::vector<timemodel::FrameFeatures>> mOptions;  // [variable][option] contribution
};

}  // namespace lodopt::evaluation
