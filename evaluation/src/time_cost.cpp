#include "evaluation/time_cost.hpp"

#include <algorithm>
#include <cmath>

namespace lodopt::evaluation {

namespace {

// A model is fitted to measured times; guard the optimizer against a broken one.
double clampMs(double ms) { return std::isfinite(ms) ? std::max(ms, 0.0) : 0.0; }

}  // namespace

TimeModelCost::TimeModelCost(const ViewSetup& setup, FrameTimeEstimator estimator, const timemodel::FeatureSet& needed)
    : mTable(setup.scene(), setup.camera(), setup.width(), setup.height(), timemodel::FeatureTable::kDepthPassCells,
             needed),
      mEstimator(std::move(estimator)) {
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

double TimeModelCost::stepMs(const timemodel::FrameFeatures& before, std::size_t variable, int from, int to) const {
    const std::vector<timemodel::FrameFeatures>& options = mOptions[variable];
    return clampMs(mEstimator(before + (options[std::size_t(to)] - options[std::size_t(from)])));
}

double TimeModelCost::deltaMs(const optimizer::Combination& combination, int variable, int newLevel) const {
    const timemodel::FrameFeatures before = featuresOf(combination);
    const auto v = std::size_t(variable);
    return stepMs(before, v, combination[v], newLevel) - clampMs(mEstimator(before));
}

void TimeModelCost::deltasMs(const optimizer::Combination& combination, std::span<const int> newLevels,
                             std::span<double> deltas) const {
    // The combination's features are summed once for all the steps asked (summing them per
    // question was quadratic in the searched objects: most of a tune on the city's dense views).
    const timemodel::FrameFeatures before = featuresOf(combination);
    const double beforeMs = clampMs(mEstimator(before));
    for (std::size_t v = 0; v < combination.size(); ++v) {
        if (newLevels[v] == combination[v]) {
            deltas[v] = 0.0;
            continue;
        }
        deltas[v] = stepMs(before, v, combination[v], newLevels[v]) - beforeMs;
    }
}

}  // namespace lodopt::evaluation
