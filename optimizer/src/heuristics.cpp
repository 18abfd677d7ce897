// Hint-driven baselines. Distance thresholds and the importance-ordered scheduler after
// Dong, Liu, Xia, Fan & Zhang, "A time-critical adaptive approach for visualizing natural
// scenes on different devices", PLoS ONE 10(2), 2015, eq. (4), (11)-(12) and §2.4; screen-size
// selection as shipped by engines (glTF MSFT_screencoverage, Unreal/Unity screen size).
#include "optimizer/heuristics.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "optimizer/repair.hpp"
#include "optimizer/search_state.hpp"

namespace lodopt::optimizer {

namespace {

constexpr double kHalfPi = 1.5707963267948966;

const VariableHints& hintsOf(const Problem& problem, std::size_t variable, const char* algorithm, const char* field) {
    if (problem.hints.empty()) {
        throw ProblemError(std::string(algorithm) + ": the problem has no hints (hints[i]." + field + " is needed)");
    }
    return problem.hints[variable];
}

double requireHint(const Problem& problem, std::size_t variable, const char* algorithm, const char* field,
                   double VariableHints::*member) {
    const double value = hintsOf(problem, variable, algorithm, field).*member;
    if (!isKnown(value)) {
        throw ProblemError(std::string(algorithm) + ": hints[" + std::to_string(variable) + "]." + field +
                           " is unknown");
    }
    return value;
}

void validateThresholds(const std::vector<double>& thresholds, const char* algorithm) {
    for (std::size_t k = 0; k < thresholds.size(); ++k) {
        if (!std::isfinite(thresholds[k]) || thresholds[k] <= 0.0 || (k > 0 && thresholds[k] <= thresholds[k - 1])) {
            throw std::invalid_argument(std::string(algorithm) + ": distance thresholds[" + std::to_string(k) +
                                        "] = " + std::to_string(thresholds[k]) +
                                        ", thresholds must be finite, > 0 and strictly ascending");
        }
    }
}

void validateView(const ImportanceView& view, const char* what) {
    if (!std::isfinite(view.distance) || view.distance < 0.0 || !std::isfinite(view.viewAngleRadians) ||
        view.viewAngleRadians < 0.0 || view.viewAngleRadians >= kHalfPi || !std::isfinite(view.projectedArea) ||
        view.projectedArea <= 0.0) {
        throw std::invalid_argument(std::string("importance: ") + what + " (distance " + std::to_string(view.distance) +
                                    ", angle " + std::to_string(view.viewAngleRadians) + ", area " +
                                    std::to_string(view.projectedArea) +
                                    ") needs distance >= 0, angle in [0, pi/2), area > 0");
    }
}

// Variables sorted by `key` ascending, ties by index.
std::vector<std::size_t> orderBy(const std::vector<double>& key) {
    std::vector<std::size_t> order(key.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
    return order;
}

// Lowers variables in `order`, each as far as needed, until the combination fits.
void lowerInOrder(const Problem& problem, const std::vector<std::size_t>& order, Combination& combination) {
    double ms = problem.cost->predictMs(combination);
    for (std::size_t i : order) {
        while (ms > problem.budgetMs && combination[i] + 1 < problem.levelCounts[i]) {
            ++combination[i];
            ms = problem.cost->predictMs(combination);
        }
    }
    repairToBudget(problem, combination);  // no-op unless the cost model is non-monotone
}

}  // namespace

Combination distanceLevels(const Problem& problem, const DistanceParameters& parameters) {
    const std::size_t variables = problem.levelCounts.size();
    std::vector<double> distance(variables);
    for (std::size_t i = 0; i < variables; ++i) {
        distance[i] = requireHint(problem, i, "distance", "distance", &VariableHints::distance);
        if (distance[i] < 0.0) {
            throw ProblemError("distance: hints[" + std::to_string(i) + "].distance = " + std::to_string(distance[i]) +
                               ", must be >= 0");
        }
    }
    Combination combination(variables, 0);
    if (variables == 0) return combination;
    const auto [lowest, highest] = std::minmax_element(distance.begin(), distance.end());
    for (std::size_t i = 0; i < variables; ++i) {
        int level = 0;
        if (!parameters.thresholds.empty()) {
            // Eq. (4): level k when d_k <= d < d_{k+1}.
            level = static_cast<int>(
                std::upper_bound(parameters.thresholds.begin(), parameters.thresholds.end(), distance[i]) -
                parameters.thresholds.begin());
        } else if (*highest > *lowest) {
            const double t = (distance[i] - *lowest) / (*highest - *lowest);
            level = static_cast<int>(std::floor(t * problem.levelCounts[i]));
        }
        combination[i] = std::min(level, problem.levelCounts[i] - 1);
    }
    return combination;
}

DistanceHeuristic::DistanceHeuristic(DistanceParameters parameters) : mParameters(std::move(parameters)) {
    validateThresholds(mParameters.thresholds, "distance");
}

Result DistanceHeuristic::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), false);
    Combination combination = distanceLevels(problem, mParameters);
    repairToBudget(problem, combination);
    return evaluateAndFinish(state, combination);
}

double importanceDenominator(const ImportanceView& view, double alpha1, double alpha2) {
    return alpha1 * (1.0 + std::tan(view.viewAngleRadians)) * view.distance + alpha2 * 100.0 / view.projectedArea;
}

double importance(const ImportanceView& view, const ImportanceView& benchmark, double alpha1, double alpha2) {
    return importanceDenominator(benchmark, alpha1, alpha2) / importanceDenominator(view, alpha1, alpha2);
}

ImportanceHeuristic::ImportanceHeuristic(ImportanceParameters parameters) : mParameters(std::move(parameters)) {
    const ImportanceParameters& p = mParameters;
    if (!std::isfinite(p.alpha1) || p.alpha1 < 0.0) {
        throw std::invalid_argument("importance: alpha1 = " + std::to_string(p.alpha1) + ", must be finite and >= 0");
    }
    if (!std::isfinite(p.alpha2) || p.alpha2 < 0.0) {
        throw std::invalid_argument("importance: alpha2 = " + std::to_string(p.alpha2) + ", must be finite and >= 0");
    }
    if (p.alpha1 == 0.0 && p.alpha2 == 0.0) throw std::invalid_argument("importance: alpha1 and alpha2 are both 0");
    if (p.benchmark) {
        validateView(*p.benchmark, "the benchmark view");
        if (importanceDenominator(*p.benchmark, p.alpha1, p.alpha2) <= 0.0) {
            throw std::invalid_argument("importance: the benchmark view has a zero denominator (B = 0)");
        }
    }
    validateThresholds(p.distance.thresholds, "importance");
}

std::vector<double> ImportanceHeuristic::importances(const Problem& problem) const {
    const ImportanceParameters& p = mParameters;
    const std::size_t variables = problem.levelCounts.size();
    std::vector<double> denominator(variables);
    for (std::size_t i = 0; i < variables; ++i) {
        ImportanceView view;
        view.distance = requireHint(problem, i, "importance", "distance", &VariableHints::distance);
        view.projectedArea = requireHint(problem, i, "importance", "projectedArea", &VariableHints::projectedArea);
        view.viewAngleRadians = problem.hints[i].viewAngleRadians;
        denominator[i] = importanceDenominator(view, p.alpha1, p.alpha2);
    }
    double benchmark = 0.0;
    if (p.benchmark) {
        benchmark = importanceDenominator(*p.benchmark, p.alpha1, p.alpha2);
    } else if (variables > 0) {
        std::vector<double> sorted = denominator;
        std::sort(sorted.begin(), sorted.end());
        const std::size_t middle = variables / 2;
        benchmark = variables % 2 == 1 ? sorted[middle] : 0.5 * (sorted[middle - 1] + sorted[middle]);
    }
    std::vector<double> result(variables);
    for (std::size_t i = 0; i < variables; ++i) {
        // A zero denominator (d = 0 with alpha2 = 0) is infinitely important.
        result[i] = denominator[i] > 0.0 ? benchmark / denominator[i] : std::numeric_limits<double>::infinity();
    }
    return result;
}

Result ImportanceHeuristic::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), false);
    const std::vector<double> importanceOf = importances(problem);
    Combination combination = distanceLevels(problem, mParameters.distance);
    // Increasing importance: objects with I <= 1 come first, so those with I > 1 are lowered
    // only when lowering every other object to its coarsest level was not enough.
    const std::vector<std::size_t> increasing = orderBy(importanceOf);
    if (problem.cost->predictMs(combination) <= problem.budgetMs) {
        for (auto it = increasing.rbegin(); it != increasing.rend(); ++it) {
            const std::size_t i = *it;
            while (combination[i] > 0) {
                --combination[i];
                if (problem.cost->predictMs(combination) > problem.budgetMs) {
                    ++combination[i];  // this object's next step does not fit; try the next object
                    break;
                }
            }
        }
    } else {
        lowerInOrder(problem, increasing, combination);
    }
    return evaluateAndFinish(state, combination);
}

Combination screenSizeLevels(const Problem& problem, const ScreenSizeParameters& parameters) {
    const std::size_t variables = problem.levelCounts.size();
    Combination combination(variables, 0);
    for (std::size_t i = 0; i < variables; ++i) {
        const double coverage = requireHint(problem, i, "screensize", "screenCoverage", &VariableHints::screenCoverage);
        const VariableHints& hints = problem.hints[i];
        const int levels = problem.levelCounts[i];
        int level = 0;
        if (!hints.levelScreenCoverage.empty()) {
            level = levels - 1;
            for (int k = 0; k < levels; ++k) {
                if (coverage >= hints.levelScreenCoverage[static_cast<std::size_t>(k)]) {
                    level = k;
                    break;
                }
            }
        } else if (!hints.levelPixelError.empty()) {
            for (int k = 0; k < levels; ++k) {
                if (hints.levelPixelError[static_cast<std::size_t>(k)] <= parameters.pixelErrorTolerance) level = k;
            }
        } else {
            throw ProblemError("screensize: hints[" + std::to_string(i) +
                               "] has neither levelScreenCoverage nor levelPixelError");
        }
        combination[i] = level;
    }
    return combination;
}

ScreenSizeHeuristic::ScreenSizeHeuristic(ScreenSizeParameters parameters) : mParameters(parameters) {
    if (!std::isfinite(mParameters.pixelErrorTolerance) || mParameters.pixelErrorTolerance <= 0.0) {
        throw std::invalid_argument("screensize: pixelErrorTolerance = " +
                                    std::to_string(mParameters.pixelErrorTolerance) + ", must be finite and > 0");
    }
}

Result ScreenSizeHeuristic::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), false);
    Combination combination = screenSizeLevels(problem, mParameters);
    std::vector<double> coverage(problem.levelCounts.size());
    for (std::size_t i = 0; i < coverage.size(); ++i) coverage[i] = problem.hints[i].screenCoverage;
    lowerInOrder(problem, orderBy(coverage), combination);
    return evaluateAndFinish(state, combination);
}

}  // namespace lodopt::optimizer
