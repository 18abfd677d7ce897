#include "optimizer/search.hpp"

#include <algorithm>
#include <stdexcept>

namespace lodopt::optimizer {

bool isSwarmAlgorithm(const std::string& algorithm) {
    return algorithm == "gapso" || algorithm == "pso" || algorithm == "ga";
}

bool isStartAlgorithm(const std::string& algorithm) {
    return algorithm == "mckp" || algorithm == "greedy" || algorithm == "screensize";
}

double effectiveFillProbability(const SearchOptions& options) {
    if (options.fillProbability >= 0.0) return options.fillProbability;
    return options.paper ? GapsoParameters::paper().fillProbability : GapsoParameters{}.fillProbability;
}

Result runSearch(const Problem& problem, const SearchOptions& options) {
    const std::string& algorithm = options.algorithm;
    if (problem.levelCounts.empty()) {
        // Every object was skipped: the only combination is the fixed one.
        Result result;
        result.algorithm = algorithm;
        result.predictedMs = problem.cost->predictMs({});
        if (result.predictedMs > problem.budgetMs) throw BudgetError(problem.budgetMs, result.predictedMs);
        result.bestScore = problem.evaluator->evaluate({});
        result.evaluations = 1;
        result.log.push_back({0, result.bestScore.fitness, result.bestScore.fitness, result.predictedMs, 1, 0, 0.0});
        return result;
    }
    for (const std::string& name : options.startFrom) {
        if (!isStartAlgorithm(name)) throw std::invalid_argument("'" + name + "' cannot start a swarm");
    }
    const Termination termination = options.paper ? Termination::paper() : options.termination;
    const bool swarm = isSwarmAlgorithm(algorithm);
    if (!swarm || (!options.paper && options.particles == 0 && options.fillProbability < 0.0 &&
                   options.startFrom.empty())) {
        return makeAlgorithm(algorithm, options.seed)->run(problem, termination);
    }
    GapsoParameters parameters = options.paper ? GapsoParameters::paper(options.seed) : GapsoParameters{};
    parameters.seed = options.seed;
    parameters.pso = algorithm != "ga";
    parameters.ga = algorithm != "pso";
    if (options.particles > 0) parameters.particles = options.particles;
    parameters.fillProbability = effectiveFillProbability(options);
    std::int64_t startEvaluations = 0;
    for (const std::string& name : options.startFrom) {
        const Result start = makeAlgorithm(name, options.seed)->run(problem, Termination{});
        startEvaluations += start.evaluations;
        const auto& starts = parameters.initialCombinations;
        const bool known = std::find(starts.begin(), starts.end(), start.best) != starts.end();
        if (!known && int(starts.size()) < parameters.particles) parameters.initialCombinations.push_back(start.best);
    }
    Result result = Gapso(parameters).run(problem, termination);
    result.evaluations += startEvaluations;
    return result;
}

}  // namespace lodopt::optimizer
