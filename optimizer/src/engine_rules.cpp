// The engines' automatic geometric-error rules (optimizer/engine_rules.hpp): Godot 4's mesh LOD
// threshold and meshoptimizer's README rule (pixelerror), Unreal's Auto Compute LOD Screen Size
// (unreal-auto: StaticMesh.cpp CalculateViewDistance, SceneManagement.cpp ComputeBoundsScreenSize,
// ComputeStaticMeshLOD), each with one bias fitted to the budget.
#include "optimizer/engine_rules.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "optimizer/search_state.hpp"

namespace lodopt::optimizer {

namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
// Unreal's fixed import-time view: 1920x1080, 90 degree horizontal field of view.
constexpr double kUnrealHalfWidthPixels = 960.0;
constexpr double kUnrealScreenMultiple = 0.5 * 1920.0 / 1080.0;

const char* ruleName(EngineRule rule) {
    return rule == EngineRule::PixelError ? "pixelerror" : "unreal-auto";
}

double knownHint(std::size_t variable, EngineRule rule, const char* field, double value) {
    if (!isKnown(value)) {
        throw ProblemError(std::string(ruleName(rule)) + ": hints[" + std::to_string(variable) + "]." + field +
                           " is unknown");
    }
    return value;
}

bool fits(const Problem& problem, const Combination& combination) {
    return problem.cost->predictMs(combination) <= problem.budgetMs;
}

}  // namespace

std::vector<std::vector<double>> engineRuleThresholds(const Problem& problem, EngineRule rule) {
    if (problem.hints.size() != problem.levelCounts.size()) {
        throw ProblemError(std::string(ruleName(rule)) +
                           ": the problem has no hints (hints[i].levelDeviation is needed)");
    }
    std::vector<std::vector<double>> thresholds(problem.levelCounts.size());
    for (std::size_t i = 0; i < thresholds.size(); ++i) {
        const VariableHints& hints = problem.hints[i];
        if (hints.levelDeviation.size() != std::size_t(problem.levelCounts[i])) {
            throw ProblemError(std::string(ruleName(rule)) + ": hints[" + std::to_string(i) +
                               "].levelDeviation is missing (the levels' measured geometric error)");
        }
        std::vector<double>& levels = thresholds[i];
        levels.assign(hints.levelDeviation.size(), 0.0);
        if (rule == EngineRule::PixelError) {
            const double pixelsPerUnit = knownHint(i, rule, "pixelsPerWorldUnit", hints.pixelsPerWorldUnit);
            for (std::size_t k = 1; k < levels.size(); ++k) levels[k] = hints.levelDeviation[k] * pixelsPerUnit;
        } else {
            const double radius = knownHint(i, rule, "boundingRadius", hints.boundingRadius);
            const double size = knownHint(i, rule, "screenCoverage", hints.screenCoverage);
            // S_k > size  <=>  deviation_k x 960 / bias < 2 M R / size - R =: reach.
            const double reach = size > 0.0 ? 2.0 * kUnrealScreenMultiple * radius / size - radius : kNever;
            for (std::size_t k = 1; k < levels.size(); ++k) {
                const double deviation = hints.levelDeviation[k];
                if (reach <= 0.0) {
                    levels[k] = kNever;  // the sphere fills more than the screen: level 0 at any bias
                } else {
                    levels[k] = std::isinf(reach) ? 0.0 : kUnrealHalfWidthPixels * deviation / reach;
                }
            }
        }
    }
    return thresholds;
}

Combination engineRuleLevels(const std::vector<std::vector<double>>& thresholds, double pixelError) {
    Combination combination(thresholds.size(), 0);
    for (std::size_t i = 0; i < thresholds.size(); ++i) {
        for (std::size_t k = 1; k < thresholds[i].size(); ++k) {
            if (thresholds[i][k] <= pixelError) combination[i] = int(k);
        }
    }
    return combination;
}

double unrealAutoScreenSize(double deviation, double radius, double pixelError) {
    const double viewDistance = deviation * kUnrealHalfWidthPixels / pixelError;  // UE CalculateViewDistance
    return 2.0 * kUnrealScreenMultiple * radius / (viewDistance + radius);       // UE ComputeBoundsScreenSize
}

double pixelErrorScreenSize(double deviation, double radius, double pixelError, double viewportHeight) {
    if (!(deviation > 0.0)) return kNever;
    return 2.0 * radius * pixelError / (deviation * viewportHeight);
}

EngineRuleHeuristic::EngineRuleHeuristic(EngineRule rule, EngineRuleParameters parameters)
    : mRule(rule), mParameters(parameters) {
    if (!std::isfinite(mParameters.pixelError) || mParameters.pixelError <= 0.0) {
        throw std::invalid_argument(std::string(ruleName(rule)) + ": pixelError = " +
                                    std::to_string(mParameters.pixelError) + ", must be finite and > 0");
    }
}

Result EngineRuleHeuristic::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), false);
    const std::vector<std::vector<double>> thresholds = engineRuleThresholds(problem, mRule);
    Combination combination = engineRuleLevels(thresholds, mParameters.pixelError);
    if (mParameters.fitBudget) {
        // Every bias at which some level switches: the combination is constant between them.
        std::vector<double> biases{0.0};
        for (const std::vector<double>& levels : thresholds) {
            for (double threshold : levels) {
                if (std::isfinite(threshold)) biases.push_back(threshold);
            }
        }
        std::sort(biases.begin(), biases.end());
        biases.erase(std::unique(biases.begin(), biases.end()), biases.end());
        // The smallest bias within the budget, by bisection (cost falls as the bias grows when
        // coarser levels cost less), then upwards one by one if the cost model is not monotone.
        std::size_t low = 0, high = biases.size() - 1;
        if (fits(problem, engineRuleLevels(thresholds, biases[high]))) {
            while (low < high) {
                const std::size_t middle = low + (high - low) / 2;
                if (fits(problem, engineRuleLevels(thresholds, biases[middle]))) {
                    high = middle;
                } else {
                    low = middle + 1;
                }
            }
        }
        std::size_t chosen = high;
        while (chosen + 1 < biases.size() && !fits(problem, engineRuleLevels(thresholds, biases[chosen]))) ++chosen;
        combination = engineRuleLevels(thresholds, biases[chosen]);
    }
    // Over budget at every bias (levels the rule never reaches): the object smallest on screen
    // is lowered first, as the screensize baseline does.
    while (!fits(problem, combination)) {
        std::size_t lowest = combination.size();
        double lowestSize = kNever;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            if (combination[i] + 1 >= problem.levelCounts[i]) continue;
            const double size = isKnown(problem.hints[i].screenCoverage) ? problem.hints[i].screenCoverage : 0.0;
            if (size < lowestSize) {
                lowest = i;
                lowestSize = size;
            }
        }
        if (lowest == combination.size()) break;  // all coarsest: the problem's budget check said it fits
        ++combination[lowest];
    }
    return evaluateAndFinish(state, combination);
}

}  // namespace lodopt::optimizer
