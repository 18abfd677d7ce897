// The measurements behind `lodopt bench` (run time against error), one function per part, each
// on one prepared view (docs/report.md, "lodopt bench"):
//
//  1. algorithms × evaluation budgets (runAlgorithmGrid): every algorithm runs with every budget
//     E (maxEvaluations = E; iterative searches also get maxIterations = max(E, 1000) so a
//     converged swarm ends), over seeds 1..S for the seeded ones (optimizer::isSeededAlgorithm:
//     gapso, pso, ga, random, pagmo's) and once for the others. Each run records its wall time
//     and its gap = bestKnown − fitness (fitness units, >= 0), where bestKnown is the exhaustive
//     optimum when the space has at most `exhaustiveLimit` members, else the best fitness any
//     run found;
//  2. evaluation paths (measureEvaluationPaths): the same candidates through the fast path
//     (layers + incremental metrics, batched over threads and one at a time) and the full path
//     (render + metrics from scratch): evaluations per second, and |fast − full| fitness;
//  3. metrics (measureMetrics): time per call of each metrics function on the view's reference
//     and a candidate, and its deviation from the float64 reference (metrics/reference.hpp);
//  4. time model (measureTimeModels): every fitted model of a device profile, its held-out error
//     from calibration and its error on random frames of this view rendered and timed now
//     (the profile's clock).
// Timings are medians; all of it runs in the calling thread's GL context (the renderer's).
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "evaluation/search_view.hpp"
#include "optimizer/search.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::evaluation {

// 1. Algorithms against evaluation budgets.

struct AlgorithmRun {
    std::string algorithm;
    std::int64_t evaluationBudget = 0;
    std::uint64_t seed = 0;
    double wallSeconds = 0.0;
    double fitness = 0.0;  // the search's fitness of its best (the evaluator's score)
    double predictedMs = 0.0;
    std::int64_t evaluations = 0;
    // (evaluations so far, best fitness) at the first log row and at each row where the best
    // rose: enough to tell when the run came within a tolerance of any best known.
    std::vector<std::pair<std::int64_t, double>> improvements;
    double gap = 0.0;  // filled once bestKnown is known
    // Filled once bestKnown is known: the evaluations after which the run's best was within
    // kNearBestKnown of it; -1 when it never was.
    std::int64_t evaluationsToNearBest = -1;
};

// "Within 10⁻³ of the best known fitness" (fitness units): the tolerance of
// AlgorithmRun::evaluationsToNearBest.
inline constexpr double kNearBestKnown = 1e-3;

struct BestKnown {
    double fitness = 0.0;
    std::string source;  // "exhaustive" or "best found"
    double combinations = 0.0;
    std::int64_t evaluations = 0;  // exhaustive's
    double seconds = 0.0;          // exhaustive's
};

// Runs every (algorithm, budget, seed) of the grid, in that order, each with `base`'s swarm
// options and start (its algorithm, seed and termination are the grid's). A run found in
// `finished` (same algorithm, budget and seed: restored from a checkpoint) is taken from there,
// not run again; `onNewRun` is called after each run made here.
std::vector<AlgorithmRun> runAlgorithmGrid(const SearchView& view, const optimizer::SearchOptions& base,
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
BestKnown searchBestKnown(const SearchView& view, double exhaustiveLimit);

// Raises best.fitness to the best of `runs` (a no-op under an exhaustive optimum) and fills
// every run's gap and evaluationsToNearBest.
void applyBestKnown(BestKnown& best, std::vector<AlgorithmRun>& runs);

// 2. The fast evaluation path against the full one.

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
// `renderer` draws the view's scene; `metrics` are the user's parameters (the search's fitness
// is measured: searchParameters); `threads` >= 1 for the batched fast path.
std::vector<EvalPathRow> measureEvaluationPaths(const SearchView& view, renderer::Renderer& renderer,
                                                const metrics::MetricParameters& metrics, int threads, int candidates,
                                                std::uint64_t seed);

// 3. The metrics functions against the float64 reference.

struct MetricsRow {
    std::string function;  // "ssim", "boundary_entropy", ...
    int width = 0, height = 0;
    std::int64_t calls = 0;
    double microsecondsPerCall = 0.0;
    std::string reference;  // what it was compared with ("" = no reference)
    double referenceMicrosecondsPerCall = NAN;
    double absDeviation = NAN;
};
// The candidate is every searched object at its coarsest level. `minSeconds` > 0: time spent
// per function (split into 5 batches, median taken).
std::vector<MetricsRow> measureMetrics(const SearchView& view, renderer::Renderer& renderer,
                                       const metrics::MetricParameters& metrics, double minSeconds);

// 4. The device profile's time models on this view.

struct TimeModelRow {
    std::string model;
    std::string source;  // "calibration held-out", "calibration, every viewpoint held out" or "this view, timed now"
    std::size_t samples = 0;
    double mean = NAN, median = NAN, p90 = NAN, max = NAN;  // |t_act − t_est| / t_act
};
// `frames` random combinations of the view (every object at a uniformly drawn level), each
// timed with `repeats` draws under the profile's clock, as `lodopt calibrate` fits it.
std::vector<TimeModelRow> measureTimeModels(const SearchView& view, renderer::Renderer& renderer,
                                            const timemodel::DeviceProfile& profile, int frames, int repeats,
                                            std::uint64_t seed);

}  // namespace lodopt::evaluation
