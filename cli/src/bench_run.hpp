// The measurements of `lodopt bench` (run time against error), one function per part, each on
// one prepared view (docs/report.md, "lodopt bench"):
//
//  1. algorithms × evaluation budgets: every algorithm runs with every budget E (maxEvaluations
//     = E; iterative searches also get maxIterations = max(E, 1000) so a converged swarm ends),
//     over seeds 1..S for the stochastic ones (gapso, pso, ga, random) and once for the
//     deterministic ones. Each run records its wall time and its gap = bestKnown − fitness
//     (fitness units, >= 0), where bestKnown is the exhaustive optimum when the space has at
//     most `exhaustiveLimit` members, else the best fitness any run found;
//  2. evaluation paths: the same candidates through the fast path (layers + incremental
//     metrics, batched over threads and one at a time) and the full path (render + metrics
//     from scratch): evaluations per second, and |fast − full| fitness;
//  3. metrics: time per call of each metrics function on the view's reference and a candidate,
//     and its deviation from a straightforward float64 OpenCV implementation;
//  4. time model: every model of the device profile, its held-out error from calibration and
//     its error on random frames of this view rendered and timed now (the profile's clock).
// Timings are medians; all of it runs in this process on one GL context.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "optimize_run.hpp"

namespace lodopt::cli {

struct AlgorithmRun {
    std::string algorithm;
    std::int64_t evaluationBudget = 0;
    std::uint64_t seed = 0;
    double wallSeconds = 0.0;
    double fitness = 0.0;  // the search's fitness of its best (the evaluator's score)
    double predictedMs = 0.0;
    std::int64_t evaluations = 0;
    double gap = 0.0;  // filled once bestKnown is known
};

struct BestKnown {
    double fitness = 0.0;
    std::string source;  // "exhaustive" or "best found"
    double combinations = 0.0;
    std::int64_t evaluations = 0;  // exhaustive's
    double seconds = 0.0;          // exhaustive's
};

bool isStochastic(const std::string& algorithm);

// Runs every (algorithm, budget, seed) of the grid, in that order. A run found in `finished`
// (same algorithm, budget and seed: restored from a checkpoint) is taken from there, not run
// again; `onNewRun` is called after each run made here.
std::vector<AlgorithmRun> runAlgorithmGrid(const evaluation::SearchView& context, const OptimizeOptions& options,
                                           const std::vector<std::string>& algorithms,
                                           const std::vector<std::int64_t>& budgets, int seeds,
                                           const std::vector<AlgorithmRun>& finished,
                                           const std::function<void(const AlgorithmRun&)>& onNewRun);

// The run of `runs` with this algorithm, budget and seed, or null.
const AlgorithmRun* findRun(const std::vector<AlgorithmRun>& runs, const std::string& algorithm,
                            std::int64_t evaluationBudget, std::uint64_t seed);

// The exhaustive optimum when the space has at most `exhaustiveLimit` combinations (>= 1);
// otherwise source "best found" and fitness 0, for applyBestKnown to fill. Independent of the
// runs, so a checkpoint can keep it while the set of runs changes.
BestKnown searchBestKnown(const evaluation::SearchView& context, const OptimizeOptions& options, double exhaustiveLimit);

// Raises best.fitness to the best of `runs` (a no-op under an exhaustive optimum) and fills
// every run's gap.
void applyBestKnown(BestKnown& best, std::vector<AlgorithmRun>& runs);

struct EvalPathRow {
    std::string path;      // "fast" or "full"
    std::string workload;  // "random" (independent candidates) or "walk" (one variable per step)
    std::string mode;      // "batch" (evaluateBatch over threads) or "single" (evaluate, one thread)
    int threads = 1;
    int candidates = 0;
    double seconds = 0.0;
    double evaluationsPerSecond = 0.0;
    double meanAbsFitnessDiff = NAN;  // vs the full path on the same candidates (fast rows)
    double maxAbsFitnessDiff = NAN;
};
std::vector<EvalPathRow> measureEvalPaths(PreparedScene& prepared, const evaluation::SearchView& context,
                                          const OptimizeOptions& options, int candidates, std::uint64_t seed);

struct MetricsRow {
    std::string function;  // "ssim", "boundary_entropy", ...
    int width = 0, height = 0;
    std::int64_t calls = 0;
    double microsecondsPerCall = 0.0;
    std::string reference;  // what it was compared with ("" = no reference)
    double referenceMicrosecondsPerCall = NAN;
    double absDeviation = NAN;
};
// `minSeconds` > 0: time spent per function (split into 5 batches, median taken).
std::vector<MetricsRow> measureMetrics(PreparedScene& prepared, const evaluation::SearchView& context, double minSeconds);

struct TimeModelRow {
    std::string model;
    std::string source;  // "calibration held-out", "calibration, every viewpoint held out" or "this view, timed now"
    std::size_t samples = 0;
    double mean = NAN, median = NAN, p90 = NAN, max = NAN;  // |t_act − t_est| / t_act
};
// `frames` random combinations of the view, each timed with `repeats` draws under the
// profile's clock (least wall time by default, as `lodopt calibrate` fits it).
// `warnings` gets the profile's mismatch sentences (render size, renderer, machine).
std::vector<TimeModelRow> measureTimeModels(PreparedScene& prepared, const evaluation::SearchView& context,
                                            const OptimizeOptions& options, int frames, int repeats, std::uint64_t seed,
                                            std::vector<std::string>& warnings);

}  // namespace lodopt::cli
