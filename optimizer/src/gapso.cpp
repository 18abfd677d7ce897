// GA-PSO after Che Li & Kang Fengju, "Intelligent combination of discrete LOD model for 3D
// visualization based on visual perception and information entropy fusion", Journal of
// System Simulation 27(8), 2015, §3, eq. (7)-(8). The step order and the safety rules
// (velocity clamp, roulette weights) are ours; see gapso.hpp and docs/optimizer.md.
#include "optimizer/gapso.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>

#include "optimizer/repair.hpp"
#include "optimizer/search_state.hpp"

namespace lodopt::optimizer {

namespace {

struct Particle {
    Combination position;
    std::vector<double> velocity;
    double fitness = 0.0;  // of `position` when last evaluated
    Combination personalBest;
    double personalBestFitness = 0.0;
    double personalBestMs = 0.0;
};

void requireFinite(double value, const char* name, double low, const char* rule) {
    if (!std::isfinite(value) || value < low) {
        throw std::invalid_argument(std::string("gapso: ") + name + " = " + std::to_string(value) + ", " + rule);
    }
}

void requireProbability(double value, const char* name) {
    if (!(value >= 0.0 && value <= 1.0)) {
        throw std::invalid_argument(std::string("gapso: ") + name + " = " + std::to_string(value) +
                                    ", must be in [0, 1]");
    }
}

// Roulette selection keeping round(keep * N) particles without replacement; the other slots
// are refilled by clones of kept particles drawn by roulette with replacement.
void select(std::vector<Particle>& swarm, double keep, bool windowed, Random& random) {
    const std::size_t count = swarm.size();
    std::vector<double> fitness(count);
    for (std::size_t k = 0; k < count; ++k) fitness[k] = swarm[k].fitness;
    std::vector<double> weights(count);
    if (windowed) {
        windowedRouletteWeights(fitness, weights);
    } else {
        rouletteWeights(fitness, weights);
    }

    const auto keepCount =
        std::clamp<std::size_t>(static_cast<std::size_t>(std::lround(keep * static_cast<double>(count))), 1, count);
    std::vector<double> work = weights;
    std::vector<bool> taken(count, false);
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < keepCount; ++k) {
        double sum = 0.0;
        for (std::size_t j = 0; j < count; ++j) sum += work[j];
        std::size_t chosen = 0;
        if (sum > 0.0) {
            chosen = rouletteSpin(work, random);
        } else {
            // Only zero weights left: uniform among the particles not yet taken.
            auto skip = random.below(count - k);
            for (chosen = 0; taken[chosen] || skip > 0; ++chosen) {
                if (!taken[chosen]) --skip;
            }
        }
        assert(!taken[chosen]);
        taken[chosen] = true;
        work[chosen] = 0.0;
        kept.push_back(chosen);
    }
    std::sort(kept.begin(), kept.end());

    std::vector<double> keptWeights(kept.size());
    for (std::size_t k = 0; k < kept.size(); ++k) keptWeights[k] = weights[kept[k]];
    std::vector<Particle> next;
    next.reserve(count);
    for (std::size_t index : kept) next.push_back(swarm[index]);
    while (next.size() < count) next.push_back(swarm[kept[rouletteSpin(keptWeights, random)]]);
    swarm = std::move(next);
}

// Arithmetic crossover of consecutive particles in a random order.
void crossover(std::vector<Particle>& swarm, double probability, Random& random) {
    std::vector<std::size_t> order(swarm.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    for (std::size_t k = order.size(); k > 1; --k) std::swap(order[k - 1], order[random.below(k)]);
    for (std::size_t p = 0; p + 1 < order.size(); p += 2) {
        if (!random.chance(probability)) continue;
        Combination& a = swarm[order[p]].position;
        Combination& b = swarm[order[p + 1]].position;
        const double ratio = random.uniform();
        for (std::size_t i = 0; i < a.size(); ++i) {
            const double xa = a[i];
            const double xb = b[i];
            a[i] = static_cast<int>(std::lround(ratio * xa + (1.0 - ratio) * xb));
            b[i] = static_cast<int>(std::lround((1.0 - ratio) * xa + ratio * xb));
        }
    }
}

// One random variable (among those with a choice) of a particle takes a different level.
void mutate(std::vector<Particle>& swarm, std::span<const int> levelCounts, std::span<const int> mutableVariables,
            double probability, Random& random) {
    for (Particle& particle : swarm) {
        if (!random.chance(probability) || mutableVariables.empty()) continue;
        const auto variable = static_cast<std::size_t>(mutableVariables[random.below(mutableVariables.size())]);
        int level = random.belowInt(levelCounts[variable] - 1);
        if (level >= particle.position[variable]) ++level;
        particle.position[variable] = level;
    }
}

// A particle sitting on the global best would only hit the cache: change one random variable,
// and a second with probability 1/2 (our addition, docs/optimizer.md).
void kickStagnant(std::vector<Particle>& swarm, const Combination& globalBest, std::span<const int> levelCounts,
                  std::span<const int> mutableVariables, Random& random) {
    for (Particle& particle : swarm) {
        if (particle.position != globalBest || mutableVariables.empty()) continue;
        const int changes = random.chance(0.5) ? 2 : 1;
        for (int c = 0; c < changes; ++c) {
            const auto variable = static_cast<std::size_t>(mutableVariables[random.below(mutableVariables.size())]);
            int level = random.belowInt(levelCounts[variable] - 1);
            if (level >= particle.position[variable]) ++level;
            particle.position[variable] = level;
        }
    }
}

// Eq. (7)-(8) with inertia, velocity clamp, rounding and absorbing walls.
void move(std::vector<Particle>& swarm, const Combination& globalBest, std::span<const int> levelCounts,
          std::span<const double> maxVelocity, const GapsoParameters& parameters, Random& random) {
    for (Particle& particle : swarm) {
        for (std::size_t i = 0; i < particle.position.size(); ++i) {
            const double x = particle.position[i];
            const double r1 = random.uniform();
            const double r2 = random.uniform();
            double v = parameters.inertia * particle.velocity[i] +
                       parameters.cognitive * r1 * (particle.personalBest[i] - x) +
                       parameters.social * r2 * (globalBest[i] - x);
            v = std::clamp(v, -maxVelocity[i], maxVelocity[i]);
            double next = x + v;
            const double top = levelCounts[i] - 1;
            if (next < 0.0 || next > top) {
                next = std::clamp(next, 0.0, top);
                v = 0.0;
            }
            particle.velocity[i] = v;
            particle.position[i] = static_cast<int>(std::lround(next));
        }
    }
}

}  // namespace

GapsoParameters GapsoParameters::paper(std::uint64_t seed) {
    GapsoParameters parameters;
    parameters.particles = 3;
    parameters.inertia = 1.0;
    parameters.cognitive = 2.0;
    parameters.social = 2.0;
    parameters.stagnationKick = false;
    parameters.windowedRoulette = false;
    parameters.fillProbability = 0.0;
    parameters.seed = seed;
    return parameters;
}

Gapso::Gapso(GapsoParameters parameters) : mParameters(std::move(parameters)) {
    const GapsoParameters& p = mParameters;
    if (p.particles < 1) {
        throw std::invalid_argument("gapso: particles = " + std::to_string(p.particles) + ", must be >= 1");
    }
    requireFinite(p.inertia, "inertia", 0.0, "must be finite and >= 0");
    requireFinite(p.cognitive, "cognitive (c1)", 0.0, "must be finite and >= 0");
    requireFinite(p.social, "social (c2)", 0.0, "must be finite and >= 0");
    if (!std::isfinite(p.velocityClamp) || p.velocityClamp <= 0.0) {
        throw std::invalid_argument("gapso: velocityClamp = " + std::to_string(p.velocityClamp) +
                                    ", must be finite and > 0");
    }
    if (!p.pso && !p.ga) throw std::invalid_argument("gapso: pso and ga are both off, nothing would move");
    if (!(p.selectionKeep > 0.0 && p.selectionKeep <= 1.0)) {
        throw std::invalid_argument("gapso: selectionKeep = " + std::to_string(p.selectionKeep) +
                                    ", must be in (0, 1]");
    }
    requireProbability(p.crossoverProbability, "crossoverProbability");
    requireProbability(p.mutationProbability, "mutationProbability");
    requireProbability(p.fillProbability, "fillProbability");
    if (p.initialCombinations.size() > static_cast<std::size_t>(p.particles)) {
        throw std::invalid_argument("gapso: " + std::to_string(p.initialCombinations.size()) +
                                    " initialCombinations for " + std::to_string(p.particles) +
                                    " particles (at most one per particle)");
    }
}

std::string_view Gapso::name() const {
    if (!mParameters.ga) return "pso";
    if (!mParameters.pso) return "ga";
    return "gapso";
}

Result Gapso::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), true);
    const GapsoParameters& p = mParameters;
    for (std::size_t k = 0; k < p.initialCombinations.size(); ++k) {
        try {
            validateCombination(problem, p.initialCombinations[k]);
        } catch (const ProblemError& error) {
            throw ProblemError(std::string(name()) + ": initialCombinations[" + std::to_string(k) +
                               "]: " + error.what());
        }
    }
    const std::span<const int> levelCounts = problem.levelCounts;
    const std::size_t variables = levelCounts.size();
    const auto count = static_cast<std::size_t>(p.particles);
    std::vector<double> maxVelocity(variables);
    std::vector<int> mutableVariables;
    for (std::size_t i = 0; i < variables; ++i) {
        maxVelocity[i] = p.velocityClamp * (levelCounts[i] - 1);
        if (levelCounts[i] > 1) mutableVariables.push_back(static_cast<int>(i));
    }

    Random random(p.seed);
    std::vector<Particle> swarm(count);
    for (std::size_t k = 0; k < count; ++k) {
        Particle& particle = swarm[k];
        particle.position.resize(variables);
        particle.velocity.resize(variables);
        for (std::size_t i = 0; i < variables; ++i) {
            particle.position[i] =
                k < p.initialCombinations.size() ? p.initialCombinations[k][i] : random.belowInt(levelCounts[i]);
            particle.velocity[i] = random.uniform(-maxVelocity[i], maxVelocity[i]);
        }
    }

    std::vector<Combination> positions(count);
    std::vector<Score> scores(count);
    std::vector<double> predictedMs(count);
    // Repairs (and fills), evaluates and updates the personal bests; returns the mean fitness.
    auto evaluateSwarm = [&](bool first) {
        for (std::size_t k = 0; k < count; ++k) {
            repairToBudget(problem, swarm[k].position);
            if (p.fillProbability > 0.0 && random.chance(p.fillProbability)) fillToBudget(problem, swarm[k].position);
            positions[k] = swarm[k].position;
        }
        const std::size_t scored = state.evaluate(positions, scores, predictedMs);
        for (std::size_t k = 0; k < scored; ++k) {
            Particle& particle = swarm[k];
            particle.fitness = scores[k].fitness;
            if (first || isBetter(particle.fitness, predictedMs[k], particle.position, particle.personalBestFitness,
                                  particle.personalBestMs, particle.personalBest)) {
                particle.personalBest = particle.position;
                particle.personalBestFitness = particle.fitness;
                particle.personalBestMs = predictedMs[k];
            }
        }
        return meanFitness(scores, scored);
    };

    double mean = evaluateSwarm(true);
    while (!state.endIteration(mean)) {
        // Selection needs measured fitness, so it comes first; crossover and mutation come
        // after the move so that their changes are evaluated rather than pulled back.
        if (p.ga) select(swarm, p.selectionKeep, p.windowedRoulette, random);
        if (p.pso) move(swarm, state.best().combination, levelCounts, maxVelocity, p, random);
        if (p.ga) {
            crossover(swarm, p.crossoverProbability, random);
            mutate(swarm, levelCounts, mutableVariables, p.mutationProbability, random);
        }
        if (p.stagnationKick) kickStagnant(swarm, state.best().combination, levelCounts, mutableVariables, random);
        mean = evaluateSwarm(false);
    }
    return state.finish();
}

void rouletteWeights(std::span<const double> fitness, std::span<double> weights) {
    assert(fitness.size() == weights.size());
    if (fitness.empty()) return;
    const double lowest = *std::min_element(fitness.begin(), fitness.end());
    // p_i = F_i / sum F needs F >= 0; shifting by the minimum keeps the order when some F < 0.
    const double shift = lowest < 0.0 ? lowest : 0.0;
    double sum = 0.0;
    for (std::size_t k = 0; k < fitness.size(); ++k) {
        weights[k] = fitness[k] - shift;
        sum += weights[k];
    }
    if (!(sum > 0.0) || !std::isfinite(sum)) std::fill(weights.begin(), weights.end(), 1.0);
}

void windowedRouletteWeights(std::span<const double> fitness, std::span<double> weights) {
    assert(fitness.size() == weights.size());
    if (fitness.empty()) return;
    const bool finite = std::all_of(fitness.begin(), fitness.end(), [](double f) { return std::isfinite(f); });
    const auto [low, high] = std::minmax_element(fitness.begin(), fitness.end());
    const double range = *high - *low;
    if (!finite || !(range > 0.0) || !std::isfinite(range)) {
        std::fill(weights.begin(), weights.end(), 1.0);
        return;
    }
    for (std::size_t k = 0; k < fitness.size(); ++k) weights[k] = fitness[k] - *low + 0.05 * range;
}

std::size_t rouletteSpin(std::span<const double> weights, Random& random) {
    assert(!weights.empty());
    double sum = 0.0;
    for (double weight : weights) sum += weight;
    if (!(sum > 0.0)) return random.below(weights.size());
    const double target = random.uniform() * sum;
    double cumulative = 0.0;
    std::size_t last = 0;
    for (std::size_t k = 0; k < weights.size(); ++k) {
        if (weights[k] <= 0.0) continue;
        cumulative += weights[k];
        last = k;
        if (target < cumulative) return k;
    }
    return last;  // rounding left the target at the very top
}

}  // namespace lodopt::optimizer
