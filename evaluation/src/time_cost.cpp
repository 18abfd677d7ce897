#include "evaluation/time_cost.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace lodopt::evaluation {

namespace {

// A model is fitted to measured times; guard the optimizer against a broken one.
double clampMs(double ms) { return std::isfinite(ms) ? std::max(ms, 0.0) : 0.0; }

}  // namespace

TimeModelCost::TimeModelCost(const ViewSetup& setup, FrameTimeEstimator estimator, const timemodel::FeatureSet& needed)
    : mTable(setup.scene(), setup.camera(), setup.width(), setup.height(), timemodel::FeatureTable::kDepthPassCells,
             needed),
      mEstimator(std::move(estimator)),
      mId(nextId()) {
    const std::vector<int>& variables = setup.variableObjects();
    scenes::Combination fixedOnly = setup.toScene(optimizer::Combination(variables.size(), 0));
    for (int object : variables) fixedOnly[std::size_t(object)] = scenes::kNotDrawn;
    mFixed = mTable.features(fixedOnly);
    for (int object : variables) {
        std::vector<timemodel::FrameFeatures> options;
        for (int level : setup.objects()[std::size_t(object)].optionLevels) {
            options.push_back(mTable.contribution(object, level));
        }
        mOptions.push_back(std::move(options));
    }
}

timemodel::FrameFeatures TimeModelCost::featuresOf(const optimizer::Combination& combination) const {
    timemodel::FrameFeatures features = mFixed;
    for (std::size_t v = 0; v < combination.size(); ++v) features += mOptions[v][std::size_t(combination[v])];
    return features;
}

double TimeModelCost::predictSceneMs(const scenes::Combination& combination) const {
    return clampMs(mEstimator(mTable.features(combination)));
}

double TimeModelCost::predictMs(const optimizer::Combination& combination) const {
    return clampMs(mEstimator(featuresOf(combination)));
}

std::uint64_t TimeModelCost::nextId() {
    static std::atomic<std::uint64_t> counter{0};
    return ++counter;
}

double TimeModelCost::deltaMs(const optimizer::Combination& combination, int variable, int newLevel) const {
    // The repair asks for every variable's step from one combination: its features are summed
    // once per combination, not once per question (that was quadratic in the searched objects:
    // most of a tune on the city's dense views). Per thread, since a cost may be shared; keyed
    // by an id no other cost ever has, not by the address, which a later cost may reuse.
    struct Memo {
        std::uint64_t cost = 0;
        optimizer::Combination combination;
        timemodel::FrameFeatures features;
        double ms = 0.0;
    };
    thread_local Memo memo;
    if (memo.cost != mId || memo.combination != combination) {
        memo.cost = mId;
        memo.combination = combination;
        memo.features = featuresOf(combination);
        memo.ms = clampMs(mEstimator(memo.features));
    }
    const std::vector<timemodel::FrameFeatures>& options = mOptions[std::size_t(variable)];
    const timemodel::FrameFeatures after =
        memo.features + (options[std::size_t(newLevel)] - options[std::size_t(combination[std::size_t(variable)])]);
    return clampMs(mEstimator(after)) - memo.ms;
}

}  // namespace lodopt::evaluation
