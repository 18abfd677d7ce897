#include "evaluation/level_costs.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace lodopt::evaluation {

double exchangeRate(std::span<const double> deltaFitness, std::span<const double> deltaMs) {
    if (deltaFitness.size() != deltaMs.size()) throw std::invalid_argument("exchangeRate: spans of unequal length");
    auto violation = [&](double lambda) {
        double sum = 0.0;
        for (std::size_t m = 0; m < deltaMs.size(); ++m) sum += std::max(0.0, deltaFitness[m] - lambda * deltaMs[m]);
        return sum;
    };
    std::vector<double> candidates{0.0};
    for (std::size_t m = 0; m < deltaMs.size(); ++m) {
        if (deltaMs[m] != 0.0 && deltaFitness[m] / deltaMs[m] > 0.0) candidates.push_back(deltaFitness[m] / deltaMs[m]);
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    std::vector<double> values;
    for (double lambda : candidates) values.push_back(violation(lambda));
    const double least = *std::min_element(values.begin(), values.end());
    const double tolerance = 1e-12 * std::max(1.0, least);
    double low = INFINITY, high = 0.0;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
        if (values[c] <= least + tolerance) {
            low = std::min(low, candidates[c]);
            high = std::max(high, candidates[c]);
        }
    }
    return low > 0.0 ? std::sqrt(low * high) : high / 2.0;
}

ViewLevelCosts measureLevelCosts(const scenes::Scene& scene, const scenes::Camera& camera, const ViewChoices& choices,
                                 renderer::Renderer& renderer, const metrics::MetricParameters& metrics,
                                 const FrameTimeEstimator& estimator, const timemodel::FeatureSet& readFeatures,
                                 const SearchViewSettings& settings) {
    if (choices.levels.size() != scene.objects.size()) {
        throw std::invalid_argument("measureLevelCosts: the answer needs one level per object");
    }
    const SearchView view = prepareSearchView(scene, camera, renderer, metrics, estimator, readFeatures, settings);
    const ViewSetup& setup = *view.setup;
    const optimizer::Combination answer = setup.fromScene(choices.levels);
    const scenes::Combination answerScene = setup.toScene(answer);
    const double answerFitness = view.evaluator->evaluate(answer).fitness;
    const double answerMs = view.cost->predictSceneMs(answerScene);
    std::map<int, std::size_t> variableOf;
    for (std::size_t v = 0; v < setup.variableObjects().size(); ++v) variableOf[setup.variableObjects()[v]] = v;

    // Every single move: per searched object, per scene level, dF and dT.
    struct Move {
        std::size_t entry;
        int level;
        double deltaFitness;
        double deltaMs;
    };
    std::vector<Move> moves;
    ViewLevelCosts costs;
    for (std::size_t entry = 0; entry < choices.searched.size(); ++entry) {
        const int object = choices.searched[entry];
        const int levels = int(scene.objects.at(std::size_t(object)).levels.size());
        costs.levelCost.emplace_back(std::size_t(levels), 0.0);
        const auto variable = variableOf.find(object);
        if (variable == variableOf.end()) continue;
        const std::vector<int>& options = setup.objects()[std::size_t(object)].optionLevels;
        std::map<int, double> fitnessOfOption;
        for (int level = 0; level < levels; ++level) {
            // The option drawing this level's image: the first searched level at or after it.
            const auto option = std::lower_bound(options.begin(), options.end(), level) - options.begin();
            const int optionIndex = int(std::min<std::ptrdiff_t>(option, std::ptrdiff_t(options.size()) - 1));
            if (optionIndex == answer[variable->second] && level == answerScene[std::size_t(object)]) continue;
            auto found = fitnessOfOption.find(optionIndex);
            if (found == fitnessOfOption.end()) {
                optimizer::Combination moved = answer;
                moved[variable->second] = optionIndex;
                found = fitnessOfOption.emplace(optionIndex, view.evaluator->evaluate(moved).fitness).first;
            }
            scenes::Combination movedScene = answerScene;
            movedScene[std::size_t(object)] = level;
            moves.push_back({entry, level, found->second - answerFitness, view.cost->predictSceneMs(movedScene) - answerMs});
        }
    }
    std::vector<double> deltaFitness, deltaMs;
    for (const Move& move : moves) {
        deltaFitness.push_back(move.deltaFitness);
        deltaMs.push_back(move.deltaMs);
    }
    costs.lambda = exchangeRate(deltaFitness, deltaMs);
    for (const Move& move : moves) {
        costs.levelCost[move.entry][std::size_t(move.level)] = costs.lambda * move.deltaMs - move.deltaFitness;
    }
    return costs;
}

}  // namespace lodopt::evaluation
