#include "optimizer/synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "optimizer/random.hpp"

namespace lodopt::optimizer {

namespace {

void requireRange(double value, double low, double high, const char* name) {
    if (!(value >= low && value <= high)) {
        throw std::invalid_argument(std::string("synthetic: ") + name + " = " + std::to_string(value) +
                                    ", must be in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
    }
}

double logUniform(Random& random, double low, double high) {
    return low * std::exp(random.uniform() * std::log(high / low));
}

}  // namespace

InteractionEvaluator::InteractionEvaluator(std::vector<std::vector<double>> degradation, std::vector<double> weights,
                                           std::vector<Pair> pairs)
    : mDegradation(std::move(degradation)), mWeights(std::move(weights)), mPairs(std::move(pairs)) {}

double InteractionEvaluator::degradationAt(std::size_t variable, const Combination& combination) const {
    return mDegradation[variable][static_cast<std::size_t>(combination[variable])];
}

double InteractionEvaluator::additiveLoss(const Combination& combination) const {
    double loss = 0.0;
    for (std::size_t i = 0; i < combination.size(); ++i) loss += mWeights[i] * degradationAt(i, combination);
    return loss;
}

double InteractionEvaluator::fitness(const Combination& combination) const {
    double interaction = 0.0;
    for (const Pair& pair : mPairs) {
        interaction += pair.weight * degradationAt(pair.a, combination) * degradationAt(pair.b, combination);
    }
    return std::clamp(1.0 - additiveLoss(combination) - interaction, 0.0, 1.0);
}

Score InteractionEvaluator::evaluate(const Combination& combination) {
    Score score;
    score.fitness = fitness(combination);
    score.components[0] = additiveLoss(combination);
    score.components[1] = 1.0 - score.components[0] - score.fitness;
    score.componentCount = 2;
    return score;
}

SyntheticProblem::SyntheticProblem(const SyntheticParameters& parameters) {
    const SyntheticParameters& p = parameters;
    if (p.variables < 1)
        throw std::invalid_argument("synthetic: variables = " + std::to_string(p.variables) + ", must be >= 1");
    if (p.minLevels < 1 || p.maxLevels < p.minLevels) {
        throw std::invalid_argument("synthetic: levels " + std::to_string(p.minLevels) + ".." +
                                    std::to_string(p.maxLevels) + ", need 1 <= minLevels <= maxLevels");
    }
    requireRange(p.pairDensity, 0.0, 1.0, "pairDensity");
    requireRange(p.interactionWeight, 0.0, 1e3, "interactionWeight");
    requireRange(p.negativeFraction, 0.0, 1.0, "negativeFraction");
    requireRange(p.budgetFraction, 0.0, 1.0, "budgetFraction");

    Random random(p.seed);
    const auto variables = static_cast<std::size_t>(p.variables);
    mLevelCounts.resize(variables);
    std::vector<std::vector<double>> degradation(variables);
    std::vector<double> weights(variables);
    std::vector<std::vector<double>> levelMs(variables);
    double weightSum = 0.0;
    for (std::size_t i = 0; i < variables; ++i) {
        const int levels = p.minLevels + random.belowInt(p.maxLevels - p.minLevels + 1);
        mLevelCounts[i] = levels;
        const double exponent = random.uniform(0.7, 2.0);
        degradation[i].resize(static_cast<std::size_t>(levels));
        for (int l = 0; l < levels; ++l) {
            degradation[i][static_cast<std::size_t>(l)] =
                levels == 1 ? 0.0 : std::pow(double(l) / (levels - 1), exponent);
        }
        // Visibility spans two orders of magnitude, like near and far objects.
        weights[i] = logUniform(random, 0.01, 1.0);
        weightSum += weights[i];
        const double finestMs = logUniform(random, 0.5, 8.0);
        const double ratio = random.uniform(0.35, 0.7);
        levelMs[i].resize(static_cast<std::size_t>(levels));
        for (int l = 0; l < levels; ++l) levelMs[i][static_cast<std::size_t>(l)] = finestMs * std::pow(ratio, l);
    }
    for (double& weight : weights) weight *= 0.6 / weightSum;

    std::vector<InteractionEvaluator::Pair> pairs;
    double pairSum = 0.0;
    for (std::size_t a = 0; a < variables; ++a) {
        for (std::size_t b = a + 1; b < variables; ++b) {
            if (!random.chance(p.pairDensity)) continue;
            const double sign = random.chance(p.negativeFraction) ? -1.0 : 1.0;
            const double magnitude = random.uniform(0.2, 1.0);
            pairs.push_back({a, b, sign * magnitude});
            pairSum += magnitude;
        }
    }
    for (auto& pair : pairs) pair.weight *= pairSum > 0.0 ? p.interactionWeight / pairSum : 0.0;

    // Hints from visibility, with noise so the heuristics are informed but not exact.
    const double heaviest = *std::max_element(weights.begin(), weights.end());
    mHints.resize(variables);
    for (std::size_t i = 0; i < variables; ++i) {
        const double visibility = weights[i] / heaviest;
        VariableHints& hints = mHints[i];
        hints.distance = 10.0 / (0.2 + visibility) * logUniform(random, 0.8, 1.25);
        hints.viewAngleRadians = random.uniform(0.0, 0.8);
        hints.screenCoverage = std::min(1.0, 0.5 * std::sqrt(visibility) * logUniform(random, 0.8, 1.25));
        hints.projectedArea = 100.0 * hints.screenCoverage * hints.screenCoverage + 1e-3;
        hints.levelPixelError.resize(static_cast<std::size_t>(mLevelCounts[i]));
        // The coarsest level is off by 5% of the object's size on a 512-pixel-high viewport.
        for (std::size_t l = 0; l < hints.levelPixelError.size(); ++l) {
            hints.levelPixelError[l] = degradation[i][l] * 0.05 * hints.screenCoverage * 512.0;
        }
        // The same error as a deviation of an object of radius 1 (no random draw: the problem's
        // other numbers stay those of every earlier version).
        hints.boundingRadius = 1.0;
        hints.pixelsPerWorldUnit = std::max(hints.screenCoverage, 1e-3) * 256.0;
        hints.levelDeviation.resize(hints.levelPixelError.size());
        for (std::size_t l = 0; l < hints.levelDeviation.size(); ++l) {
            hints.levelDeviation[l] = hints.levelPixelError[l] / hints.pixelsPerWorldUnit;
        }
    }

    mEvaluator = std::make_unique<InteractionEvaluator>(std::move(degradation), std::move(weights), std::move(pairs));
    mCost = std::make_unique<AdditiveCost>(1.0, std::move(levelMs));
    Combination coarsest(variables);
    for (std::size_t i = 0; i < variables; ++i) coarsest[i] = mLevelCounts[i] - 1;
    const double minimumMs = mCost->predictMs(coarsest);
    const double maximumMs = mCost->predictMs(Combination(variables, 0));
    mBudgetMs = minimumMs + p.budgetFraction * (maximumMs - minimumMs);
}

Problem SyntheticProblem::problem() const {
    Problem problem;
    problem.levelCounts = mLevelCounts;
    problem.evaluator = mEvaluator.get();
    problem.cost = mCost.get();
    problem.budgetMs = mBudgetMs;
    problem.hints = mHints;
    return problem;
}

std::vector<std::vector<double>> SyntheticProblem::additiveLoss() const {
    std::vector<std::vector<double>> loss = mEvaluator->degradation();
    for (std::size_t i = 0; i < loss.size(); ++i) {
        for (double& value : loss[i]) value *= mEvaluator->weights()[i];
    }
    return loss;
}

}  // namespace lodopt::optimizer
