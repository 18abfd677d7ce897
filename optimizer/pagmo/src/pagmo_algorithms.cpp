#include "optimizer/pagmo_algorithms.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/de1220.hpp>
#include <pagmo/algorithms/pso.hpp>
#include <pagmo/algorithms/pso_gen.hpp>
#include <pagmo/algorithms/sade.hpp>
#include <pagmo/algorithms/sga.hpp>
#include <pagmo/algorithms/simulated_annealing.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>
#include <pagmo/types.hpp>
#include <span>
#include <stdexcept>
#include <utility>

#include "optimizer/repair.hpp"
#include "optimizer/search_state.hpp"

namespace lodopt::optimizer {
namespace {

// Thrown by the problem when the evaluation budget is spent; ends the run (caught in run()).
struct EvaluationsSpent {};

// What the copies of the problem that pagmo makes share: the run's state and the fitness sum
// of the iteration in progress (for the log's mean).
struct RunShared {
    SearchState* state = nullptr;
    bool integer = false;
    double fitnessSum = 0.0;
    std::size_t evaluated = 0;
};

// The pagmo user-defined problem (default-constructible and copyable, as pagmo requires).
class LevelProblem {
public:
    LevelProblem() = default;
    explicit LevelProblem(RunShared* shared) : mShared(shared) {}

    pagmo::vector_double fitness(const pagmo::vector_double& x) const {
        SearchState& state = *mShared->state;
        const std::vector<int>& counts = state.problem().levelCounts;
        Combination combination(counts.size());
        for (std::size_t i = 0; i < counts.size(); ++i) {
            // Non-finite or out of bounds (cmaes does not force its bounds): clamped.
            const double value = std::isfinite(x[i]) ? std::floor(x[i]) : 0.0;
            combination[i] = int(std::clamp(value, 0.0, double(counts[i] - 1)));
        }
        repairToBudget(state.problem(), combination);
        Score score;
        double predictedMs = 0.0;
        if (state.evaluate(std::span<const Combination>(&combination, 1), std::span<Score>(&score, 1),
                           std::span<double>(&predictedMs, 1)) == 0) {
            throw EvaluationsSpent{};
        }
        mShared->fitnessSum += score.fitness;
        ++mShared->evaluated;
        return {-score.fitness};
    }

    std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
        const std::vector<int>& counts = mShared->state->problem().levelCounts;
        pagmo::vector_double lower(counts.size(), 0.0), upper(counts.size());
        for (std::size_t i = 0; i < counts.size(); ++i) {
            // Integer: the levels themselves. Continuous: [0, levels], one unit per level.
            upper[i] = mShared->integer ? double(counts[i] - 1) : double(counts[i]);
        }
        return {lower, upper};
    }

    pagmo::vector_double::size_type get_nix() const {
        return mShared->integer ? mShared->state->problem().levelCounts.size() : 0;
    }

    std::string get_name() const { return "lodopt LOD combination"; }

private:
    RunShared* mShared = nullptr;
};

// One generation per evolve call, pagmo's defaults otherwise; `memory` on where the algorithm
// has it, so that successive calls continue one run.
struct Entry {
    std::string name;
    bool integer;         // takes the integer encoding
    int leastPopulation;  // refused below this
    pagmo::algorithm (*make)(unsigned seed);
};

const std::vector<Entry>& entries() {
    static const std::vector<Entry> list = {
        {"pagmo:pso", false, 2,
         [](unsigned seed) {
             return pagmo::algorithm(pagmo::pso(1u, 0.7298, 2.05, 2.05, 0.5, 5u, 2u, 4u, true, seed));
         }},
        {"pagmo:pso_gen", false, 2,
         [](unsigned seed) {
             return pagmo::algorithm(pagmo::pso_gen(1u, 0.7298, 2.05, 2.05, 0.5, 5u, 2u, 4u, true, seed));
         }},
        {"pagmo:sga", true, 2,
         [](unsigned seed) {
             return pagmo::algorithm(
                 pagmo::sga(1u, .90, 1., 0.02, 1., 2u, "exponential", "polynomial", "tournament", seed));
         }},
        {"pagmo:de", false, 7,
         [](unsigned seed) { return pagmo::algorithm(pagmo::de(1u, 0.8, 0.9, 2u, 1e-6, 1e-6, seed)); }},
        {"pagmo:sade", false, 7,
         [](unsigned seed) { return pagmo::algorithm(pagmo::sade(1u, 2u, 1u, 1e-6, 1e-6, true, seed)); }},
        {"pagmo:de1220", false, 7,
         [](unsigned seed) {
             return pagmo::algorithm(
                 pagmo::de1220(1u, pagmo::de1220_statics<void>::allowed_variants, 1u, 1e-6, 1e-6, true, seed));
         }},
        {"pagmo:cmaes", false, 5,
         [](unsigned seed) {
             return pagmo::algorithm(pagmo::cmaes(1u, -1, -1, -1, -1, 0.5, 1e-6, 1e-6, true, false, seed));
         }},
        {"pagmo:simulated_annealing", false, 1,
         [](unsigned seed) { return pagmo::algorithm(pagmo::simulated_annealing(10., .1, 10u, 1u, 20u, 1., seed)); }},
    };
    return list;
}

const Entry& entry(std::string_view name) {
    for (const Entry& known : entries()) {
        if (known.name == name) return known;
    }
    std::string valid;
    for (const Entry& known : entries()) valid += (valid.empty() ? "" : ", ") + known.name;
    throw std::invalid_argument("unknown pagmo algorithm '" + std::string(name) + "' (valid: " + valid + ")");
}

// Two 32-bit seeds from the run's (pagmo's seeds are unsigned int): population, algorithm.
std::pair<unsigned, unsigned> pagmoSeeds(std::uint64_t seed) {
    std::uint64_t z = seed + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return {unsigned(z), unsigned(z >> 32)};
}

}  // namespace

const std::vector<std::string>& pagmoAlgorithmNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list;
        for (const Entry& known : entries()) list.push_back(known.name);
        return list;
    }();
    return names;
}

PagmoAlgorithm::PagmoAlgorithm(PagmoParameters parameters) : mParameters(std::move(parameters)) {
    const Entry& known = entry(mParameters.algorithm);
    if (mParameters.population < known.leastPopulation) {
        throw std::invalid_argument(mParameters.algorithm + ": population = " + std::to_string(mParameters.population) +
                                    ", must be >= " + std::to_string(known.leastPopulation));
    }
}

Result PagmoAlgorithm::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, mParameters.algorithm, true);
    const Entry& known = entry(mParameters.algorithm);
    RunShared shared;
    shared.state = &state;
    shared.integer = known.integer;
    const auto [populationSeed, algorithmSeed] = pagmoSeeds(mParameters.seed);
    // The mean of this iteration's evaluations, then a fresh sum for the next.
    auto endIteration = [&] {
        const double mean = shared.evaluated ? shared.fitnessSum / double(shared.evaluated) : 0.0;
        shared.fitnessSum = 0.0;
        shared.evaluated = 0;
        return state.endIteration(mean);
    };
    try {
        const pagmo::problem pagmoProblem{LevelProblem(&shared)};
        pagmo::population population(pagmoProblem, std::size_t(mParameters.population), populationSeed);
        if (endIteration()) return state.finish();
        const pagmo::algorithm algorithm = known.make(algorithmSeed);
        while (true) {
            population = algorithm.evolve(population);
            if (endIteration()) return state.finish();
        }
    } catch (const EvaluationsSpent&) {
        // pagmo stopped mid-generation: log what that generation evaluated and end there.
        endIteration();
    }
    return state.finish();
}

void registerPagmoAlgorithms() {
    static const bool registered = [] {
        for (const std::string& name : pagmoAlgorithmNames()) {
            registerAlgorithm(
                name,
                [name](std::uint64_t seed) {
                    PagmoParameters parameters;
                    parameters.algorithm = name;
                    parameters.seed = seed;
                    return std::unique_ptr<Algorithm>(new PagmoAlgorithm(parameters));
                },
                true);
        }
        return true;
    }();
    (void)registered;
}

}  // namespace lodopt::optimizer
