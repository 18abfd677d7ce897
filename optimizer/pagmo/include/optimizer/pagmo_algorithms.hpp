// pagmo2's optimizers run on lodopt's problem, as peers of lodopt's own searches
// (docs/optimizer.md, "Peers: pagmo2"). Library lodopt::optimizer_pagmo, built when Debian's
// libpagmo-dev is found.
//
// The problem as pagmo sees it: one decision variable per searched object, single objective
// −fitness (pagmo minimises), no constraint. A decision vector is decoded to a combination
// (integer variables in [0, levels − 1] for the algorithms that take integers, sga; otherwise
// continuous in [0, levels], level = floor, the top edge mapped to the coarsest level), then
// brought within the budget by lodopt's repair (repairToBudget, the rule GA-PSO uses) and
// evaluated: the budget is met by repair, not by a constraint, because most of pagmo's
// population algorithms take no constraints. pagmo keeps the unrepaired vector (its search moves
// freely; what it is told is the repaired combination's fitness).
//
// Counting, log and stop are lodopt's (SearchState): every evaluation goes through one
// CheckedEvaluator, so a combination met again is a cache hit and only new combinations count
// against maxEvaluations, as for gapso. Iteration 0 is the initial population, each later
// iteration one generation (evolve with gen = 1 on one algorithm object, with pagmo's `memory`
// on where it has it, so the generations are one continuous run). When the evaluation budget
// runs out inside a generation the run stops there, with the best evaluated so far.
//
// Parameters: pagmo's published defaults for each algorithm; the population is `population`
// individuals (default 12, GA-PSO's swarm size). The population's and the algorithm's seeds
// both come from the run's seed, so a run repeats exactly.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "optimizer/algorithm.hpp"

namespace lodopt::optimizer {

// "pagmo:pso", "pagmo:pso_gen", "pagmo:sga", "pagmo:de", "pagmo:sade", "pagmo:de1220",
// "pagmo:cmaes", "pagmo:simulated_annealing".
const std::vector<std::string>& pagmoAlgorithmNames();

struct PagmoParameters {
    std::string algorithm = "pagmo:pso";  // one of pagmoAlgorithmNames()
    std::uint64_t seed = 1;
    int population = 12;  // >= the algorithm's least (7 for the DE family, 5 for cmaes)
};

class PagmoAlgorithm : public Algorithm {
public:
    // Throws std::invalid_argument for an unknown algorithm or a population below its least.
    explicit PagmoAlgorithm(PagmoParameters parameters);
    std::string_view name() const override { return mParameters.algorithm; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    PagmoParameters mParameters;
};

// Registers every pagmoAlgorithmNames() entry with registerAlgorithm (seeded, default
// parameters). Call once at start-up; a second call does nothing.
void registerPagmoAlgorithms();

}  // namespace lodopt::optimizer
