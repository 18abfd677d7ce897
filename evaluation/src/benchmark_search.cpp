#include <algorithm>
#include <chrono>

#include "evaluation/benchmark.hpp"

namespace lodopt::evaluation {

std::vector<AlgorithmRun> runAlgorithmGrid(const SearchView& view, const optimizer::SearchOptions& base,
                                           const std::vector<std::string>& algorithms,
                                           const std::vector<std::int64_t>& budgets, int seeds,
                                           const std::vector<AlgorithmRun>& finished,
                                           const std::function<void(const AlgorithmRun&)>& onNewRun) {
    std::vector<AlgorithmRun> runs;
    for (const std::string& algorithm : algorithms) {
        for (std::int64_t budget : budgets) {
            optimizer::SearchOptions options = base;
            options.algorithm = algorithm;
            options.termination.maxEvaluations = budget;
            // As in compare: the evaluation budget decides; the iteration cap only ends a
            // converged swarm circling through cached candidates.
            options.termination.maxIterations = int(std::max<std::int64_t>(budget, 1000));
            options.termination.stableIterations = 0;
            options.termination.maxSeconds = 0.0;
            const int runsHere = optimizer::isSeededAlgorithm(algorithm) ? seeds : 1;
            for (int seed = 1; seed <= runsHere; ++seed) {
                if (const AlgorithmRun* saved = findRun(finished, algorithm, budget, std::uint64_t(seed))) {
                    runs.push_back(*saved);
                    continue;
                }
                options.seed = std::uint64_t(seed);
                const auto start = std::chrono::steady_clock::now();
                const optimizer::Result result = optimizer::runSearch(view.problem, options);
                AlgorithmRun run;
                run.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                run.algorithm = algorithm;
                run.evaluationBudget = budget;
                run.seed = options.seed;
                run.fitness = result.bestScore.fitness;
                run.predictedMs = result.predictedMs;
                run.evaluations = result.evaluations;
                for (const optimizer::IterationLog& row : result.log) {
                    if (run.improvements.empty() || row.bestFitness > run.improvements.back().second) {
                        run.improvements.emplace_back(row.evaluations, row.bestFitness);
                    }
                }
                runs.push_back(run);
                onNewRun(run);
            }
        }
    }
    return runs;
}

const AlgorithmRun* findRun(const std::vector<AlgorithmRun>& runs, const std::string& algorithm,
                            std::int64_t evaluationBudget, std::uint64_t seed) {
    for (const AlgorithmRun& run : runs) {
        if (run.algorithm == algorithm && run.evaluationBudget == evaluationBudget && run.seed == seed) return &run;
    }
    return nullptr;
}

BestKnown searchBestKnown(const SearchView& view, double exhaustiveLimit) {
    BestKnown best;
    best.combinations = optimizer::combinationCount(view.problem.levelCounts);
    if (best.combinations > exhaustiveLimit) {
        best.source = "best found";
        return best;
    }
    optimizer::SearchOptions exhaustive;
    exhaustive.algorithm = "exhaustive";
    exhaustive.termination = optimizer::Termination::none();
    const auto start = std::chrono::steady_clock::now();
    const optimizer::Result result = optimizer::runSearch(view.problem, exhaustive);
    best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best.fitness = result.bestScore.fitness;
    best.evaluations = result.evaluations;
    best.source = "exhaustive";
    return best;
}

void applyBestKnown(BestKnown& best, std::vector<AlgorithmRun>& runs) {
    // The exhaustive optimum is the ceiling; "best found" is the best any run reached.
    for (const AlgorithmRun& run : runs) best.fitness = std::max(best.fitness, run.fitness);
    for (AlgorithmRun& run : runs) {
        run.gap = std::max(0.0, best.fitness - run.fitness);
        run.evaluationsToNearBest = -1;
        for (const auto& [evaluations, fitness] : run.improvements) {
            if (fitness >= best.fitness - kNearBestKnown) {
                run.evaluationsToNearBest = evaluations;
                break;
            }
        }
    }
}

}  // namespace lodopt::evaluation
