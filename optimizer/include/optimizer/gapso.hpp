// GA-PSO: particle swarm optimisation with genetic operators over discrete LOD levels.
//
// After Che & Kang 2015 ("GAPSO15", docs/method.md §3). Each particle is a combination (one
// integer level per variable) with a real velocity. One iteration, one batch of evaluations:
//   1. roulette selection (when `ga`) on the fitness just measured: p_i = F_i / sum F keeps
//      round(selectionKeep * N) particles (without replacement); each other slot becomes a copy
//      of a kept particle (position, velocity, personal best) drawn by roulette;
//   2. PSO move (when `pso`), eq. (7)-(8) with inertia:
//      v <- w v + c1 r1 (pbest - x) + c2 r2 (gbest - x), r1, r2 ~ U(0, 1) per dimension,
//      |v_i| clamped to velocityClamp * (levelCounts[i] - 1) (w = 1, c1 = c2 = 2 diverges
//      otherwise), x <- round(x + v) clamped to [0, levelCounts[i] - 1] (velocity zeroed at a
//      wall);
//   3. (when `ga`) arithmetic crossover of consecutive particles in a random order, probability
//      crossoverProbability per pair: children round(a x1 + (1-a) x2) and
//      round((1-a) x1 + a x2), a ~ U(0, 1); then mutation, probability mutationProbability per
//      particle: one random variable takes a different random level;
//   4. stagnation kick (when `stagnationKick`, our addition): a particle that sits exactly on
//      the global best would only hit the cache, so one random variable changes level, and a
//      second with probability 1/2; without it the discrete swarm collapses onto the best in a
//      few iterations and stops exploring (docs/optimizer.md has the measurements);
//   5. repair to the budget (repair.hpp; the repaired levels are written back); then, with
//      probability fillProbability per particle (our addition), fill the budget: refine the
//      levels that gain most surrogate fitness per millisecond while they fit (fillToBudget,
//      written back); evaluate the swarm as one batch, update personal and global bests.
//      Why: a particle moved by the swarm often leaves part of the budget unused, and the
//      rounding of PSO and crossover rarely lands exactly on the budget's edge, where good
//      combinations are; filling every particle, though, makes them all the same greedy
//      completion and the swarm collapses (docs/optimizer.md has both measurements).
// The paper applies PSO, then selection, crossover and mutation, then evaluates. Selection
// needs fitness, and only the positions before the move have one, so we select first; and
// crossover and mutation stay after the move so that the move does not pull their changes
// straight back before they are evaluated.
// Roulette weights: with `windowedRoulette` (default) F - min F + 5% of the range
// (windowedRouletteWeights); the paper's p_i = F_i / sum F (rouletteWeights, `--paper`) is F
// itself when every F >= 0 and sum F > 0, F - min F when some F < 0, uniform when all weights
// are 0. Why the default differs: fused fitness values of one swarm lie within a few percent
// of each other (0.93-0.95 on the forest), so F / sum F is nearly uniform and selection
// replaces 30% of the swarm with random clones (diversity lost, no pressure gained); the window
// restores the pressure the paper's operator intends (docs/optimizer.md has the comparison).
// `pso` alone is plain PSO, `ga` alone a GA with these operators.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "optimizer/algorithm.hpp"
#include "optimizer/random.hpp"

namespace lodopt::optimizer {

struct GapsoParameters {
    int particles = 12;                  // >= 1, swarm size N
    double inertia = 0.7;                // w, finite, >= 0 (paper: 1)
    double cognitive = 1.5;              // c1, finite, >= 0 (paper: 2)
    double social = 1.5;                 // c2, finite, >= 0 (paper: 2)
    double velocityClamp = 0.5;          // > 0, finite: |v_i| <= velocityClamp * (levels_i - 1)
    bool pso = true;                     // apply the PSO move
    bool ga = true;                      // apply the genetic operators (at least one of the two)
    double selectionKeep = 0.7;          // (0, 1], fraction of the swarm kept by roulette
    double crossoverProbability = 0.15;  // [0, 1], per pair
    double mutationProbability = 0.15;   // [0, 1], per particle
    bool stagnationKick = true;          // perturb particles that sit on the global best
    bool windowedRoulette = true;        // selection weights F - min F (+5% of range); paper: F
    double fillProbability = 0.15;       // [0, 1], per particle and evaluation: fill the budget
    std::uint64_t seed = 1;
    // Optional starting particles (e.g. the mckp solution for "--seed-from mckp"), at most
    // `particles`, repaired to the budget; the other particles start uniformly at random.
    // Checked against the problem in run() (ProblemError).
    std::vector<Combination> initialCombinations;

    // GAPSO15's experiment: c1 = c2 = 2, w = 1, 3 particles, no stagnation kick, no fill (use
    // Termination::paper()). The velocity clamp stays: without it w = 1, c = 2 diverges.
    static GapsoParameters paper(std::uint64_t seed = 1);
};

class Gapso final : public Algorithm {
public:
    // Throws std::invalid_argument naming the first bad parameter and its value.
    explicit Gapso(GapsoParameters parameters = {});

    // "gapso", "pso" (ga off) or "ga" (pso off).
    std::string_view name() const override;
    Result run(const Problem& problem, const Termination& termination) const override;

    const GapsoParameters& parameters() const { return mParameters; }

private:
    GapsoParameters mParameters;
};

// Selection weights for fitnesses `fitness` (finite), written to `weights` (same size): the
// rule in the header comment. Every weight is >= 0 and at least one is > 0 (when not empty).
void rouletteWeights(std::span<const double> fitness, std::span<double> weights);
// F_i - min F + 0.05 (max F - min F); uniform when all F are equal (or any is not finite).
void windowedRouletteWeights(std::span<const double> fitness, std::span<double> weights);

// Index drawn with probability weights[k] / sum(weights); uniform when the sum is 0.
// `weights` not empty, every entry >= 0.
std::size_t rouletteSpin(std::span<const double> weights, Random& random);

}  // namespace lodopt::optimizer
