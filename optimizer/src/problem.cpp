#include "optimizer/problem.hpp"

#include <cassert>
#include <sstream>

namespace lodopt::optimizer {

namespace {

std::string formatMs(double ms) {
    std::ostringstream out;
    out.precision(6);
    out << ms << " ms";
    return out.str();
}

void validateLevelTable(const std::vector<std::vector<double>>& table, std::span<const int> levelCounts,
                        const char* name) {
    if (table.size() != levelCounts.size()) {
        throw ProblemError(std::string(name) + " has " + std::to_string(table.size()) + " rows, expected " +
                           std::to_string(levelCounts.size()) + " (one per variable)");
    }
    for (std::size_t i = 0; i < table.size(); ++i) {
        if (table[i].size() != static_cast<std::size_t>(levelCounts[i])) {
            throw ProblemError(std::string(name) + "[" + std::to_string(i) + "] has " +
                               std::to_string(table[i].size()) + " entries, variable " + std::to_string(i) + " has " +
                               std::to_string(levelCounts[i]) + " levels");
        }
        for (std::size_t l = 0; l < table[i].size(); ++l) {
            if (!std::isfinite(table[i][l])) {
                throw ProblemError(std::string(name) + "[" + std::to_string(i) + "][" + std::to_string(l) +
                                   "] is not finite");
            }
        }
    }
}

void validateHints(const VariableHints& hints, std::size_t variable, int levelCount) {
    const std::string where = "hints[" + std::to_string(variable) + "]";
    auto checkOptional = [&](double value, const char* field, bool strictlyPositive) {
        if (!isKnown(value)) return;
        if (!std::isfinite(value) || value < 0.0 || (strictlyPositive && value == 0.0)) {
            throw ProblemError(where + "." + field + " = " + std::to_string(value) + ", must be " +
                               (strictlyPositive ? "> 0" : ">= 0") + " and finite");
        }
    };
    checkOptional(hints.distance, "distance", false);
    checkOptional(hints.projectedArea, "projectedArea", true);
    checkOptional(hints.screenCoverage, "screenCoverage", false);
    checkOptional(hints.boundingRadius, "boundingRadius", true);
    checkOptional(hints.pixelsPerWorldUnit, "pixelsPerWorldUnit", true);
    if (!std::isfinite(hints.viewAngleRadians) || hints.viewAngleRadians < 0.0 ||
        hints.viewAngleRadians >= 1.5707963267948966) {
        throw ProblemError(where + ".viewAngleRadians = " + std::to_string(hints.viewAngleRadians) +
                           ", must be in [0, pi/2)");
    }
    auto checkPerLevel = [&](const std::vector<double>& values, const char* field) {
        if (values.empty()) return;
        if (values.size() != static_cast<std::size_t>(levelCount)) {
            throw ProblemError(where + "." + field + " has " + std::to_string(values.size()) +
                               " entries, variable has " + std::to_string(levelCount) + " levels");
        }
        for (std::size_t l = 0; l < values.size(); ++l) {
            if (!std::isfinite(values[l]) || values[l] < 0.0) {
                throw ProblemError(where + "." + field + "[" + std::to_string(l) + "] = " + std::to_string(values[l]) +
                                   ", must be finite and >= 0");
            }
        }
    };
    checkPerLevel(hints.levelScreenCoverage, "levelScreenCoverage");
    checkPerLevel(hints.levelPixelError, "levelPixelError");
    checkPerLevel(hints.levelDeviation, "levelDeviation");
    for (std::size_t l = 1; l < hints.levelScreenCoverage.size(); ++l) {
        if (hints.levelScreenCoverage[l] > hints.levelScreenCoverage[l - 1]) {
            throw ProblemError(where + ".levelScreenCoverage[" + std::to_string(l) +
                               "] = " + std::to_string(hints.levelScreenCoverage[l]) +
                               " is above the previous level's threshold (must be non-increasing)");
        }
    }
}

}  // namespace

BudgetError::BudgetError(double budgetMs, double minimumMs)
    : ProblemError("budget " + formatMs(budgetMs) +
                   " is below the cheapest combination (every object at its "
                   "coarsest level), which is predicted at " +
                   formatMs(minimumMs)),
      mBudgetMs(budgetMs),
      mMinimumMs(minimumMs) {}

void Evaluator::evaluateBatch(std::span<const Combination> combinations, std::span<Score> scores) {
    assert(combinations.size() == scores.size());
    for (std::size_t k = 0; k < combinations.size(); ++k) scores[k] = evaluate(combinations[k]);
}

double Cost::deltaMs(const Combination& combination, int variable, int newLevel) const {
    assert(variable >= 0 && static_cast<std::size_t>(variable) < combination.size());
    Combination changed = combination;
    changed[static_cast<std::size_t>(variable)] = newLevel;
    return predictMs(changed) - predictMs(combination);
}

void Cost::deltasMs(const Combination& combination, std::span<const int> newLevels, std::span<double> deltas) const {
    assert(newLevels.size() == combination.size() && deltas.size() == combination.size());
    for (std::size_t i = 0; i < combination.size(); ++i) {
        deltas[i] = newLevels[i] == combination[i] ? 0.0 : deltaMs(combination, static_cast<int>(i), newLevels[i]);
    }
}

AdditiveCost::AdditiveCost(double baseMs, std::vector<std::vector<double>> levelMs)
    : mBaseMs(baseMs), mLevelMs(std::move(levelMs)) {
    if (!std::isfinite(mBaseMs) || mBaseMs < 0.0) {
        throw ProblemError("AdditiveCost: baseMs = " + std::to_string(mBaseMs) + ", must be finite and >= 0");
    }
    for (std::size_t i = 0; i < mLevelMs.size(); ++i) {
        if (mLevelMs[i].empty()) {
            throw ProblemError("AdditiveCost: levelMs[" + std::to_string(i) + "] is empty");
        }
        for (std::size_t l = 0; l < mLevelMs[i].size(); ++l) {
            const double ms = mLevelMs[i][l];
            if (!std::isfinite(ms) || ms < 0.0) {
                throw ProblemError("AdditiveCost: levelMs[" + std::to_string(i) + "][" + std::to_string(l) +
                                   "] = " + std::to_string(ms) + ", must be finite and >= 0");
            }
        }
    }
}

double AdditiveCost::predictMs(const Combination& combination) const {
    assert(combination.size() == mLevelMs.size());
    double ms = mBaseMs;
    for (std::size_t i = 0; i < combination.size(); ++i) ms += mLevelMs[i][static_cast<std::size_t>(combination[i])];
    return ms;
}

double AdditiveCost::deltaMs(const Combination& combination, int variable, int newLevel) const {
    const auto& row = mLevelMs[static_cast<std::size_t>(variable)];
    return row[static_cast<std::size_t>(newLevel)] -
           row[static_cast<std::size_t>(combination[static_cast<std::size_t>(variable)])];
}

void AdditiveCost::deltasMs(const Combination& combination, std::span<const int> newLevels,
                            std::span<double> deltas) const {
    assert(newLevels.size() == combination.size() && deltas.size() == combination.size());
    for (std::size_t i = 0; i < combination.size(); ++i) {
        const auto& row = mLevelMs[i];
        deltas[i] = row[static_cast<std::size_t>(newLevels[i])] - row[static_cast<std::size_t>(combination[i])];
    }
}

void validateProblem(const Problem& problem) {
    assert(problem.evaluator != nullptr && "Problem::evaluator must be set");
    assert(problem.cost != nullptr && "Problem::cost must be set");
    if (problem.levelCounts.empty()) throw ProblemError("the problem has no variables (levelCounts is empty)");
    for (std::size_t i = 0; i < problem.levelCounts.size(); ++i) {
        if (problem.levelCounts[i] < 1) {
            throw ProblemError("levelCounts[" + std::to_string(i) + "] = " + std::to_string(problem.levelCounts[i]) +
                               ", must be >= 1");
        }
    }
    if (std::isnan(problem.budgetMs) || problem.budgetMs <= 0.0) {
        throw ProblemError("budgetMs = " + std::to_string(problem.budgetMs) + ", must be > 0");
    }
    if (!problem.hints.empty()) {
        if (problem.hints.size() != problem.levelCounts.size()) {
            throw ProblemError("hints has " + std::to_string(problem.hints.size()) + " entries, expected " +
                               std::to_string(problem.levelCounts.size()) + " (one per variable) or none");
        }
        for (std::size_t i = 0; i < problem.hints.size(); ++i) {
            validateHints(problem.hints[i], i, problem.levelCounts[i]);
        }
    }
    if (!problem.surrogateLoss.empty()) validateLevelTable(problem.surrogateLoss, problem.levelCounts, "surrogateLoss");

    const double minimumMs = problem.cost->predictMs(coarsestCombination(problem));
    if (!std::isfinite(minimumMs)) {
        throw ProblemError("the cost model predicted " + formatMs(minimumMs) + " for the all-coarsest combination");
    }
    if (problem.budgetMs < minimumMs) throw BudgetError(problem.budgetMs, minimumMs);
}

void validateCombination(std::span<const int> levelCounts, const Combination& combination) {
    if (combination.size() != levelCounts.size()) {
        throw ProblemError("combination " + formatCombination(combination) + " has " +
                           std::to_string(combination.size()) + " levels, the problem has " +
                           std::to_string(levelCounts.size()) + " variables");
    }
    for (std::size_t i = 0; i < combination.size(); ++i) {
        if (combination[i] < 0 || combination[i] >= levelCounts[i]) {
            throw ProblemError("combination[" + std::to_string(i) + "] = " + std::to_string(combination[i]) +
                               ", variable " + std::to_string(i) + " has " + std::to_string(levelCounts[i]) +
                               " levels");
        }
    }
}

void validateCombination(const Problem& problem, const Combination& combination) {
    validateCombination(problem.levelCounts, combination);
}

Combination finestCombination(const Problem& problem) {
    return Combination(problem.levelCounts.size(), 0);
}

Combination coarsestCombination(const Problem& problem) {
    Combination combination(problem.levelCounts.size());
    for (std::size_t i = 0; i < combination.size(); ++i) combination[i] = problem.levelCounts[i] - 1;
    return combination;
}

double combinationCount(std::span<const int> levelCounts) {
    double count = 1.0;
    for (int levels : levelCounts) count *= static_cast<double>(levels);
    return count;
}

bool isFeasible(const Problem& problem, const Combination& combination) {
    return problem.cost->predictMs(combination) <= problem.budgetMs;
}

std::string formatCombination(const Combination& combination) {
    std::string text = "[";
    for (std::size_t i = 0; i < combination.size(); ++i) {
        if (i > 0) text += ", ";
        text += std::to_string(combination[i]);
    }
    return text + "]";
}

}  // namespace lodopt::optimizer
