// One search as lodopt runs it: an algorithm by name, and for the swarms (gapso, pso, ga) the
// options the tool exposes: the published settings, the swarm size, the budget fill, and a
// start from other algorithms' answers (mckp, greedy, screensize: each run once, unseeded and
// without a limit, its answer added to the initial particles unless already there; their
// evaluations count toward the result's). A problem without variables (every object fixed)
// has one combination, evaluated once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "optimizer/algorithm.hpp"
#include "optimizer/gapso.hpp"

namespace lodopt::optimizer {

struct SearchOptions {
    std::string algorithm = "gapso";  // one of algorithmNames()
    std::uint64_t seed = 1;
    Termination termination;
    bool paper = false;                  // GapsoParameters::paper() and Termination::paper()
    int particles = 0;                   // 0: the algorithm's default
    double fillProbability = -1.0;       // < 0: the default (GapsoParameters, 0 with `paper`)
    std::vector<std::string> startFrom;  // algorithms whose answers start the swarm
};

// gapso, pso or ga: the algorithms the swarm options apply to.
bool isSwarmAlgorithm(const std::string& algorithm);
// The fill probability a swarm searches with under `options`.
double effectiveFillProbability(const SearchOptions& options);
// The names startFrom accepts.
bool isStartAlgorithm(const std::string& algorithm);

// Runs the search on a validated problem. Throws std::invalid_argument for an unknown algorithm
// or start algorithm, BudgetError when even the fixed combination exceeds the budget.
Result runSearch(const Problem& problem, const SearchOptions& options);

}  // namespace lodopt::optimizer
