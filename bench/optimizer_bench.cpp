// Optimizer benchmarks (issue #6).
//
// Timings (Google Benchmark): the mckp solver at 100 variables x 6 levels, repair, the
// checked evaluator's cache, and a whole gapso run on the synthetic problem, whose evaluator
// costs microseconds, so the figures are the optimizer's own overhead per evaluation.
//
// Quality (--compare): the synthetic non-additive problem of optimizer/synthetic.hpp
// (30 variables, 4-6 levels, pair terms), median best fitness over 10 seeds at equal
// evaluation budgets for every algorithm, printed as markdown tables for docs/optimizer.md.
//
// Tuning (--sweep): GA-PSO with and without the stagnation kick on the harbor-shaped problem,
// and a parameter grid on two synthetic instances; (--fill) the budget fill's probability.
//
// Run: build-opt/bench/optimizer_bench --compare
//      build-opt/bench/optimizer_bench --sweep
//      build-opt/bench/optimizer_bench --fill
//      build-opt/bench/optimizer_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "optimizer/optimizer.hpp"

namespace {

using namespace lodopt::optimizer;

// ---- timings ------------------------------------------------------------------------------

void BM_SolveMckp(benchmark::State& state) {
    const auto variables = static_cast<std::size_t>(state.range(0));
    const auto levels = static_cast<std::size_t>(state.range(1));
    Random random(1);
    std::vector<std::vector<double>> loss(variables);
    std::vector<std::vector<double>> cost(variables);
    double total = 0.0;
    for (std::size_t i = 0; i < variables; ++i) {
        double ms = random.uniform(0.5, 8.0);
        double lost = 0.0;
        for (std::size_t l = 0; l < levels; ++l) {
            loss[i].push_back(lost);
            cost[i].push_back(ms);
            total += l == 0 ? ms : 0.0;
            lost += random.uniform(0.0, 0.01);
            ms *= random.uniform(0.35, 0.7);
        }
    }
    for (auto _ : state) {
        Combination answer = solveMckp(loss, cost, 0.3 * total, 10000);
        benchmark::DoNotOptimize(answer.data());
    }
}
BENCHMARK(BM_SolveMckp)->Args({30, 5})->Args({100, 6})->Args({1000, 6})->Unit(benchmark::kMillisecond);

// Repair and fill benchmarks: range(0) variables, with the surrogate table when range(1) != 0.
struct RepairBench {
    explicit RepairBench(const benchmark::State& state)
        : synthetic([&] {
              SyntheticParameters parameters;
              parameters.variables = static_cast<int>(state.range(0));
              return parameters;
          }()),
          problem(synthetic.problem()) {
        if (state.range(1) != 0) problem.surrogateLoss = synthetic.additiveLoss();
    }
    SyntheticProblem synthetic;
    Problem problem;  // points into synthetic
};

void BM_RepairFinestToBudget(benchmark::State& state) {
    const RepairBench bench(state);
    const Problem& problem = bench.problem;
    for (auto _ : state) {
        Combination combination(problem.levelCounts.size(), 0);
        benchmark::DoNotOptimize(repairToBudget(problem, combination));
    }
}
BENCHMARK(BM_RepairFinestToBudget)->Args({30, 0})->Args({30, 1})->Args({100, 0})->Unit(benchmark::kMicrosecond);

// The budget fill's longest walk: from all coarsest up to the budget.
void BM_FillCoarsestToBudget(benchmark::State& state) {
    const RepairBench bench(state);
    const Problem& problem = bench.problem;
    for (auto _ : state) {
        Combination combination = coarsestCombination(problem);
        benchmark::DoNotOptimize(fillToBudget(problem, combination));
    }
}
BENCHMARK(BM_FillCoarsestToBudget)->Args({30, 0})->Args({30, 1})->Args({100, 0})->Unit(benchmark::kMicrosecond);

void BM_CheckedEvaluatorCacheHits(benchmark::State& state) {
    SyntheticProblem synthetic(SyntheticParameters{});
    const Problem problem = synthetic.problem();
    CheckedEvaluator checked(problem);
    std::vector<Combination> batch(12, coarsestCombination(problem));
    for (std::size_t k = 0; k < batch.size(); ++k) batch[k][k] = 0;
    std::vector<Score> scores(batch.size());
    checked.evaluateBatch(batch, scores);
    for (auto _ : state) benchmark::DoNotOptimize(checked.evaluateBatch(batch, scores));
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(batch.size()));
}
BENCHMARK(BM_CheckedEvaluatorCacheHits);

// range(1): 0 = no budget fill, 1 = the default fill probability.
void BM_GapsoRun(benchmark::State& state) {
    SyntheticProblem synthetic(SyntheticParameters{});
    const Problem problem = synthetic.problem();
    Termination termination = Termination::none();
    termination.maxEvaluations = state.range(0);
    termination.maxIterations = 100000;
    GapsoParameters parameters;
    if (state.range(1) == 0) parameters.fillProbability = 0.0;
    std::int64_t evaluations = 0;
    for (auto _ : state) {
        const Result result = Gapso(parameters).run(problem, termination);
        evaluations += result.evaluations;
    }
    state.counters["us/evaluation"] =
        benchmark::Counter(static_cast<double>(evaluations), benchmark::Counter::kIsRate | benchmark::Counter::kInvert,
                           benchmark::Counter::kIs1000);
}
BENCHMARK(BM_GapsoRun)->Args({1000, 0})->Args({1000, 1})->Unit(benchmark::kMillisecond);

// ---- quality comparison -------------------------------------------------------------------

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

struct Contender {
    std::string label;
    std::function<std::unique_ptr<Algorithm>(std::uint64_t seed)> make;
};

std::vector<Contender> contenders(const Problem& problem) {
    std::vector<Contender> list;
    for (const char* name : {"gapso", "pso", "ga", "random", "greedy", "mckp"}) {
        list.push_back({name, [name](std::uint64_t seed) { return makeAlgorithm(name, seed); }});
    }
    // GA-PSO started from the mckp answer (CLI: --seed-from mckp); the mckp run's
    // evaluations are charged to the same budget by the caller.
    (void)problem;
    list.push_back({"gapso+mckp", nullptr});
    list.push_back(
        {"gapso-paper", [](std::uint64_t seed) { return std::make_unique<Gapso>(GapsoParameters::paper(seed)); }});
    for (const char* name : {"distance", "importance", "screensize"}) {
        list.push_back({name, [name](std::uint64_t seed) { return makeAlgorithm(name, seed); }});
    }
    return list;
}

// Equal evaluation budgets: the iterative searches run until they have spent them, capped
// at this many iterations in case a converged swarm only hits the cache.
constexpr int kIterationCap = 3000;

// Best fitness of one contender with `evaluations` evaluations at most.
double runOnce(const Contender& contender, const Problem& problem, std::int64_t evaluations, std::uint64_t seed) {
    Termination termination = Termination::none();
    termination.maxEvaluations = evaluations;
    termination.maxIterations = kIterationCap;
    if (contender.label == "gapso+mckp") {
        const Result seedResult = Mckp().run(problem, termination);
        GapsoParameters parameters;
        parameters.seed = seed;
        parameters.initialCombinations = {seedResult.best};
        termination.maxEvaluations = evaluations - seedResult.evaluations;
        const Result result = Gapso(parameters).run(problem, termination);
        return std::max(result.bestScore.fitness, seedResult.bestScore.fitness);
    }
    return contender.make(seed)->run(problem, termination).bestScore.fitness;
}

// The best known fitness's contribution of one seed: a 30-particle GA-PSO with 50,000 evaluations.
double longRunFitness(const Problem& problem, std::uint64_t seed) {
    GapsoParameters longRun;
    longRun.seed = seed;
    longRun.particles = 30;
    Termination termination = Termination::none();
    termination.maxEvaluations = 50000;
    termination.maxIterations = kIterationCap;
    return Gapso(longRun).run(problem, termination).bestScore.fitness;
}

int compare() {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // rows appear as they are computed
    const std::vector<std::int64_t> budgets{200, 500, 2000};
    constexpr int kSeeds = 10;

    // Table 1: one problem instance, 10 algorithm seeds.
    SyntheticParameters parameters;  // defaults: 30 variables, 4-6 levels, budget fraction 0.3
    SyntheticProblem synthetic(parameters);
    const Problem problem = synthetic.problem();
    double bestKnown = 0.0;
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
        bestKnown = std::max(bestKnown, longRunFitness(problem, seed));
    }
    std::printf(
        "Synthetic problem (optimizer/synthetic.hpp defaults, seed 1): %zu variables, %.0f combinations, "
        "budget %.3f ms (min %.3f, max %.3f)\n",
        problem.levelCounts.size(), combinationCount(problem.levelCounts), problem.budgetMs,
        synthetic.cost().predictMs(coarsestCombination(problem)),
        synthetic.cost().predictMs(finestCombination(problem)));
    std::printf(
        "reference (all finest, infeasible) fitness 1; all coarsest %.4f; best known %.4f (gapso, 30 "
        "particles, 50000 evaluations, best of 5 seeds)\n\n",
        synthetic.evaluator().fitness(coarsestCombination(problem)), bestKnown);

    const std::vector<Contender> list = contenders(problem);
    std::printf("| algorithm |");
    for (auto budget : budgets) std::printf(" %lld evals: median [min, max] |", static_cast<long long>(budget));
    std::printf("\n|---|");
    for (std::size_t b = 0; b < budgets.size(); ++b) std::printf("---|");
    std::printf("\n");
    for (const Contender& contender : list) {
        std::printf("| %s |", contender.label.c_str());
        for (auto budget : budgets) {
            std::vector<double> best;
            for (std::uint64_t seed = 1; seed <= kSeeds; ++seed)
                best.push_back(runOnce(contender, problem, budget, seed));
            std::printf(" %.4f [%.4f, %.4f] |", median(best), *std::min_element(best.begin(), best.end()),
                        *std::max_element(best.begin(), best.end()));
        }
        std::printf("\n");
    }

    // Table 2: ten problem instances (instance seed = algorithm seed), gap to the best known.
    std::printf(
        "\nTen instances (seeds 1-10), median gap to the instance's best known fitness at 500 evaluations:\n\n");
    std::printf("| algorithm | median gap | worst gap |\n|---|---|---|\n");
    std::map<std::string, std::vector<double>> gaps;
    for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
        SyntheticParameters instanceParameters;
        instanceParameters.seed = seed;
        SyntheticProblem instance(instanceParameters);
        const Problem instanceProblem = instance.problem();
        std::map<std::string, double> fitness;
        double instanceBest = 0.0;
        for (const Contender& contender : list) {
            fitness[contender.label] = runOnce(contender, instanceProblem, 500, seed);
            instanceBest = std::max(instanceBest, fitness[contender.label]);
        }
        instanceBest = std::max(instanceBest, longRunFitness(instanceProblem, seed));
        for (const auto& [label, value] : fitness) gaps[label].push_back(instanceBest - value);
    }
    for (const Contender& contender : list) {
        const auto& values = gaps[contender.label];
        std::printf("| %s | %.4f | %.4f |\n", contender.label.c_str(), median(values),
                    *std::max_element(values.begin(), values.end()));
    }
    return 0;
}

// ---- GA-PSO parameter sweep (--sweep) -----------------------------------------------------

// The harbor-shaped problem of tests/optimizer/fixtures.hpp (aircraft 5 levels, ship 5, sea 6),
// repeated here so that the bench links the optimizer alone.
class HarborEvaluator final : public Evaluator {
public:
    Score evaluate(const Combination& c) override {
        static const double aircraft[] = {1228, 822, 600, 450, 393};
        static const double ship[] = {6578, 6013, 5317, 3341, 3071};
        const double air = (aircraft[0] - aircraft[c[0]]) / (aircraft[0] - aircraft[4]);
        const double hull = (ship[0] - ship[c[1]]) / (ship[0] - ship[4]);
        const double sea = c[2] / 5.0;
        Score score;
        score.fitness = 1.0 - 0.25 * air - 0.35 * hull - 0.2 * sea - 0.2 * hull * sea;
        return score;
    }
};

// Median best fitness of GA-PSO with `parameters` over seeds 1-10 at `evaluations` evaluations.
double medianOverSeeds(GapsoParameters parameters, const Problem& problem, std::int64_t evaluations) {
    std::vector<double> best;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        parameters.seed = seed;
        Termination termination = Termination::none();
        termination.maxEvaluations = evaluations;
        termination.maxIterations = kIterationCap;
        best.push_back(Gapso(parameters).run(problem, termination).bestScore.fitness);
    }
    return median(best);
}

// The harbor-shaped problem with GAPSO15's polygon costs at an 8 ms budget, and its optimum.
struct HarborBench {
    HarborEvaluator evaluator;
    AdditiveCost cost{
        0.5,
        {{1.228, 0.822, 0.600, 0.450, 0.393}, {6.578, 6.013, 5.317, 3.341, 3.071}, {3.0, 2.4, 1.8, 1.2, 0.7, 0.3}}};
    Problem problem;
    Result truth;
    HarborBench() {
        problem.levelCounts = {5, 5, 6};
        problem.evaluator = &evaluator;
        problem.cost = &cost;
        problem.budgetMs = 8.0;
        truth = Exhaustive().run(problem, Termination::none());
    }
    HarborBench(const HarborBench&) = delete;  // problem points into it
    HarborBench& operator=(const HarborBench&) = delete;
};

int sweep() {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    HarborBench bench;
    const Problem& harbor = bench.problem;
    const Result& truth = bench.truth;
    std::printf("Harbor problem, budget 8 ms: optimum %s fitness %.4f; 40 seeds, 30 iterations\n\n",
                formatCombination(truth.best).c_str(), truth.bestScore.fitness);
    std::printf("| parameters | kick | optimum found | mean evaluations |\n|---|---|---|---|\n");
    for (bool paper : {true, false}) {
        for (bool kick : {false, true}) {
            int found = 0;
            double evaluations = 0.0;
            for (std::uint64_t seed = 1; seed <= 40; ++seed) {
                GapsoParameters parameters = paper ? GapsoParameters::paper(seed) : GapsoParameters{};
                parameters.seed = seed;
                parameters.stagnationKick = kick;
                Termination termination = Termination::none();
                termination.maxIterations = 30;
                const Result result = Gapso(parameters).run(harbor, termination);
                found += result.best == truth.best;
                evaluations += static_cast<double>(result.evaluations);
            }
            std::printf("| %s | %s | %d/40 | %.1f |\n",
                        paper ? "paper (N 3, w 1, c 2)" : "defaults (N 12, w 0.7, c 1.5)", kick ? "on" : "off", found,
                        evaluations / 40.0);
        }
    }

    std::printf("\nSynthetic instances 1 and 2 (30 variables), median best fitness of seeds 1-10:\n\n");
    std::printf("| N | w | c1 = c2 | clamp | kick | inst 1, 500 | inst 1, 2000 | inst 2, 500 | inst 2, 2000 |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    std::vector<std::unique_ptr<SyntheticProblem>> instances;
    for (std::uint64_t seed : {1, 2}) {
        SyntheticParameters parameters;
        parameters.seed = seed;
        instances.push_back(std::make_unique<SyntheticProblem>(parameters));
    }
    auto row = [&](GapsoParameters parameters) {
        std::printf("| %d | %.1f | %.1f | %.1f | %s |", parameters.particles, parameters.inertia, parameters.cognitive,
                    parameters.velocityClamp, parameters.stagnationKick ? "on" : "off");
        for (const auto& instance : instances) {
            const Problem problem = instance->problem();
            for (std::int64_t budget : {500, 2000}) {
                std::printf(" %.4f |", medianOverSeeds(parameters, problem, budget));
            }
        }
        std::printf("\n");
    };
    for (bool kick : {false, true}) {
        GapsoParameters parameters;
        parameters.stagnationKick = kick;
        row(parameters);
    }
    for (int particles : {6, 12, 24}) {
        for (double inertia : {0.5, 0.7, 0.9}) {
            for (double acceleration : {1.0, 1.5, 2.0}) {
                for (double clamp : {0.3, 0.5, 1.0}) {
                    GapsoParameters parameters;
                    parameters.particles = particles;
                    parameters.inertia = inertia;
                    parameters.cognitive = parameters.social = acceleration;
                    parameters.velocityClamp = clamp;
                    row(parameters);
                }
            }
        }
    }
    return 0;
}

// ---- GA-PSO budget fill (--fill) ------------------------------------------------------------

// Fill probability 0 (no fill), the default and every particle, on the harbor-shaped
// problem and on synthetic instances 1-4 with and without the additive surrogate table (the CLI
// always measures it; without it the fill takes the cheapest step first).
int fillSweep() {
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    HarborBench bench;
    const Problem& harbor = bench.problem;
    const Result& truth = bench.truth;
    const std::vector<double> probabilities{0.0, 0.05, GapsoParameters{}.fillProbability, 0.3, 1.0};
    std::printf("Harbor problem, budget 8 ms, 40 seeds, 30 iterations: optimum found\n\n| fill |");
    for (double p : probabilities) std::printf(" %.2f |", p);
    std::printf("\n|---|");
    for (std::size_t k = 0; k < probabilities.size(); ++k) std::printf("---|");
    std::printf("\n| found |");
    for (double p : probabilities) {
        int found = 0;
        for (std::uint64_t seed = 1; seed <= 40; ++seed) {
            GapsoParameters parameters;
            parameters.seed = seed;
            parameters.fillProbability = p;
            Termination termination = Termination::none();
            termination.maxIterations = 30;
            found += Gapso(parameters).run(harbor, termination).best == truth.best;
        }
        std::printf(" %d/40 |", found);
    }
    std::printf(
        "\n\nSynthetic instances 1-4 (30 variables), GA-PSO defaults but the fill, median best fitness "
        "of seeds 1-10:\n\n| instance | surrogate | evaluations |");
    for (double p : probabilities) std::printf(" fill %.2f |", p);
    std::printf("\n|---|---|---|");
    for (std::size_t k = 0; k < probabilities.size(); ++k) std::printf("---|");
    std::printf("\n");
    for (std::uint64_t instanceSeed = 1; instanceSeed <= 4; ++instanceSeed) {
        SyntheticParameters instanceParameters;
        instanceParameters.seed = instanceSeed;
        const SyntheticProblem instance(instanceParameters);
        for (bool surrogate : {false, true}) {
            Problem problem = instance.problem();
            if (surrogate) problem.surrogateLoss = instance.additiveLoss();
            for (std::int64_t budget : {500, 2000}) {
                std::printf("| %llu | %s | %lld |", static_cast<unsigned long long>(instanceSeed),
                            surrogate ? "yes" : "no", static_cast<long long>(budget));
                for (double p : probabilities) {
                    GapsoParameters parameters;
                    parameters.fillProbability = p;
                    std::printf(" %.4f |", medianOverSeeds(parameters, problem, budget));
                }
                std::printf("\n");
            }
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    for (int k = 1; k < argc; ++k) {
        if (std::strcmp(argv[k], "--fill") == 0) return fillSweep();
        if (std::strcmp(argv[k], "--compare") == 0) return compare();
        if (std::strcmp(argv[k], "--sweep") == 0) return sweep();
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
