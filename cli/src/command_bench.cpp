// lodopt bench: run time against error in one run (issue #8): algorithms × evaluation budgets
// (wall time and gap to the best fitness known), fast vs full evaluation path, metrics against
// float64 references, and the time models' error. The measurements are evaluation/benchmark.hpp's; this
// file parses options, writes the CSVs, bench.json and the Pareto plot, and prints a summary.
//
// Each grid run and each later section is one unit of work: after it, every finished unit is
// saved in <out>/bench.checkpoint.json (bench_checkpoint.hpp) and an interrupt (SIGINT/SIGTERM)
// stops there; --resume reuses the saved units, so the outputs equal an uninterrupted run's
// (timings aside). The checkpoint is removed once bench.json is written.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>

#include "bench_checkpoint.hpp"
#include "checkpoint.hpp"
#include "cli_common.hpp"
#include "evaluation/benchmark.hpp"
#include "interrupt.hpp"
#include "optimize_run.hpp"
#include "optimizer/checked_evaluator.hpp"
#include "optimizer/mckp.hpp"
#include "progress.hpp"
#include "report_bench.hpp"
#include "scenes/atomic_file.hpp"
#include "scenes/builtin.hpp"
#include "statistics.hpp"

namespace lodopt::cli {
namespace {

struct BenchOptions {
    OptimizeOptions optimize;
    std::string algorithms = "gapso,pso,ga,random,greedy,mckp,screensize";
    std::string budgets = "30,100,300,1000";
    int seeds = 5;
    int candidates = 96;
    double metricsSeconds = 0.25;
    int timingFrames = 12;
    int timingRepeats = 5;
    double exhaustiveLimit = 1e6;
    bool quick = false;
    bool resume = false;
    std::string out = "out/bench";
    OutputOptions output;
};

std::vector<std::string> splitNames(const std::string& text) {
    std::vector<std::string> names;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        if (!item.empty()) names.push_back(item);
    }
    return names;
}

// Every digit a double needs to read back the same: the tables are compared with the JSON's
// values (a fitness cut to 8 digits could read above the best known one).
std::string number(double value) {
    if (!std::isfinite(value)) return "";
    std::ostringstream out;
    out << std::setprecision(std::numeric_limits<double>::max_digits10) << value;
    return out.str();
}

nlohmann::json jsonNumberOrNull(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

// The budget between the all-coarsest and the all-finest prediction: the search has room in
// both directions.
double defaultBudget(const evaluation::SearchView& context) {
    const std::vector<int>& counts = context.problem.levelCounts;
    optimizer::Combination coarsest(counts.size()), finest(counts.size(), 0);
    for (std::size_t i = 0; i < counts.size(); ++i) coarsest[i] = counts[i] - 1;
    const double low = context.cost->predictMs(coarsest), high = context.cost->predictMs(finest);
    return high > low ? low + 0.5 * (high - low) : std::max(low, 1e-3) * 1.01;
}

// Everything that changes a unit's result, keyed by option name. --threads does not (results
// are identical for any thread count); --algos, --evals and --seeds may change too: grid runs
// are matched by algorithm, budget and seed, and the best found is recomputed from the runs.
nlohmann::json checkpointIdentity(const BenchOptions& bench) {
    const OptimizeOptions& o = bench.optimize;
    return {{"scene", o.scene},
            {"scene-seed", o.sceneSeed},
            {"view", o.view},
            {"seed", o.seed},
            {"budget-ms", o.budgetMs > 0.0 ? nlohmann::json(o.budgetMs) : nlohmann::json()},
            {"size", o.size},
            {"shading", o.shading},
            {"weights", o.weights},
            {"profile", o.profile},
            {"model", o.model},
            {"fill", effectiveFillProbability(o)},  // GA-PSO's default; bench has no --fill
            {"seed-from", seedAlgorithms(o.seedFrom)},
            {"exhaustive-limit", bench.exhaustiveLimit},
            {"candidates", bench.candidates},
            {"metrics-seconds", bench.metricsSeconds},
            {"timing-frames", bench.timingFrames},
            {"quick", bench.quick}};  // beyond the options above, it sets the timing repeats
}

// The grid of a bench: its algorithms and evaluation budgets, checked.
struct BenchGrid {
    std::vector<std::string> algorithms;
    std::vector<std::int64_t> budgets;
};

BenchGrid parseGrid(const BenchOptions& bench) {
    BenchGrid grid;
    grid.algorithms = splitNames(bench.algorithms);
    if (grid.algorithms.empty()) throw UsageError("--algos: empty list");
    for (const std::string& name : grid.algorithms) {
        checkAlgorithmName(name);
        if (name == "exhaustive") throw UsageError("--algos: exhaustive is the ground truth, not a contestant");
    }
    for (int value : parseIntList(bench.budgets, "--evals")) {
        if (value < 1) throw UsageError("--evals: " + std::to_string(value) + " must be >= 1");
        grid.budgets.push_back(value);
    }
    if (bench.optimize.view == "all") throw UsageError("bench: --view must name one view");
    seedAlgorithms(bench.optimize.seedFrom);  // throws UsageError for a bad --seed-from
    return grid;
}

// Units in the whole bench, and those `checkpoint` already holds.
std::pair<std::size_t, std::size_t> unitCounts(const BenchOptions& bench, const BenchGrid& grid,
                                               const BenchCheckpoint& checkpoint) {
    std::size_t gridRuns = 0, done = 0;
    for (const std::string& name : grid.algorithms) {
        const int runsHere = optimizer::isSeededAlgorithm(name) ? bench.seeds : 1;
        gridRuns += grid.budgets.size() * std::size_t(runsHere);
        for (std::int64_t budget : grid.budgets) {
            for (int seed = 1; seed <= runsHere; ++seed) {
                done += evaluation::findRun(checkpoint.runs, name, budget, std::uint64_t(seed)) ? 1 : 0;
            }
        }
    }
    done += std::size_t(checkpoint.bestKnown.has_value()) + std::size_t(checkpoint.evalPaths.has_value()) +
            std::size_t(checkpoint.metrics.has_value()) + std::size_t(checkpoint.timeModels.has_value());
    return {gridRuns + 4, done};  // the runs, best known, evaluation paths, metrics, time models
}

// The surrogate table's cost: measured once per view in prepareView, outside every run's wall
// time, and measured again here so the bench can say what it costs.
std::pair<std::int64_t, double> measureSurrogateTable(const evaluation::SearchView& context) {
    if (context.problem.levelCounts.empty()) return {0, 0.0};
    const auto tableStart = std::chrono::steady_clock::now();
    optimizer::CheckedEvaluator checked(context.problem);
    optimizer::measureSurrogateLoss(context.problem, checked);
    return {checked.evaluations(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - tableStart).count()};
}

// The profile the time-model check reads: the named file, else the scene's shipped one.
timemodel::DeviceProfile benchProfile(const PreparedScene& prepared, const std::string& file) {
    try {
        return file.empty() ? timemodel::shippedProfile(prepared.scene.name) : timemodel::loadProfile(file);
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }
}

// Every unit not yet in `checkpoint`, each saved when done; an interrupt stops after a unit.
std::vector<evaluation::AlgorithmRun> runUnits(const BenchOptions& bench, const BenchGrid& grid,
                                               const OptimizeOptions& options, PreparedScene& prepared,
                                               const evaluation::SearchView& context,
                                               const CheckpointFile& checkpointFile, const nlohmann::json& identity,
                                               BenchCheckpoint& checkpoint) {
    auto [total, done] = unitCounts(bench, grid, checkpoint);
    if (done < total) pollInterrupt("bench", done, total, "unit", checkpointFile.path());
    Progress progress("bench", total - done, bench.output.quiet);
    // After each new unit: save every finished one, then stop here if a signal came. After the
    // last unit only the outputs are left: finish them rather than stop.
    auto unitDone = [&](const std::string& label) {
        checkpointFile.save(identity, benchToCheckpoint(checkpoint));
        progress.step(label);
        try {
            if (++done < total) pollInterrupt("bench", done, total, "unit", checkpointFile.path());
        } catch (const Interrupted&) {
            progress.finish();  // the message starts on a clean line
            throw;
        }
    };
    auto onNewRun = [&](const evaluation::AlgorithmRun& run) {
        checkpoint.runs.push_back(run);
        unitDone(run.algorithm + " " + std::to_string(run.evaluationBudget) + " evals seed " +
                 std::to_string(run.seed));
    };
    std::vector<evaluation::AlgorithmRun> runs =
        evaluation::runAlgorithmGrid(context, searchOptions(options, options.algorithm, options.seed), grid.algorithms,
                                     grid.budgets, bench.seeds, checkpoint.runs, onNewRun);
    if (!checkpoint.bestKnown) {
        checkpoint.bestKnown = evaluation::searchBestKnown(context, bench.exhaustiveLimit);
        unitDone("best known (" + checkpoint.bestKnown->source + ")");
    }
    if (!checkpoint.evalPaths) {
        checkpoint.evalPaths = evaluation::measureEvaluationPaths(context, *prepared.renderer, prepared.metrics,
                                                                  options.threads, bench.candidates, options.seed);
        unitDone("evaluation paths");
    }
    if (!checkpoint.metrics) {
        checkpoint.metrics =
            evaluation::measureMetrics(context, *prepared.renderer, prepared.metrics, bench.metricsSeconds);
        unitDone("metrics");
    }
    if (!checkpoint.timeModels) {
        TimeModelSection section;
        const timemodel::DeviceProfile profile = benchProfile(prepared, options.profile);
        section.warnings = timemodel::profileWarnings(
            profile, prepared.renderer->glRendererString(), prepared.settings.width, prepared.settings.height,
            timemodel::describeMachine(), renderer::shadingName(prepared.settings.shading),
            renderer::frameClockName(prepared.renderer->frameClock()));
        section.rows = evaluation::measureTimeModels(context, *prepared.renderer, profile, bench.timingFrames,
                                                     bench.timingRepeats, options.seed);
        checkpoint.timeModels = std::move(section);
        unitDone("time models");
    }
    progress.finish();
    return runs;
}

// bench.json's tables, with the CSV files of the same rows written beside it.
struct BenchTables {
    nlohmann::json runs, algorithms, paths, metrics, timeModels;
};

nlohmann::json algorithmTable(const BenchGrid& grid, const std::vector<evaluation::AlgorithmRun>& runs,
                              const std::filesystem::path& dir) {
    // Per (algorithm, budget): medians over seeds.
    std::ostringstream runsCsv, algorithmsCsv;
    runsCsv << "algorithm,evaluation_budget,seed,wall_seconds,fitness,gap,evaluations,predicted_ms,"
               "evaluations_to_near_best\n";
    for (const evaluation::AlgorithmRun& run : runs) {
        runsCsv << run.algorithm << ',' << run.evaluationBudget << ',' << run.seed << ',' << number(run.wallSeconds)
                << ',' << number(run.fitness) << ',' << number(run.gap) << ',' << run.evaluations << ','
                << number(run.predictedMs) << ',' << run.evaluationsToNearBest << '\n';
    }
    algorithmsCsv << "algorithm,evaluation_budget,runs,median_wall_seconds,median_gap,min_gap,max_gap,median_fitness,"
                     "median_evaluations,reached_near_best,median_evaluations_to_near_best\n";
    nlohmann::json table = nlohmann::json::array();
    for (const std::string& name : grid.algorithms) {
        for (std::int64_t budget : grid.budgets) {
            std::vector<double> wall, gap, fitness, evaluations, toNearBest;
            for (const evaluation::AlgorithmRun& run : runs) {
                if (run.algorithm != name || run.evaluationBudget != budget) continue;
                wall.push_back(run.wallSeconds);
                gap.push_back(run.gap);
                fitness.push_back(run.fitness);
                evaluations.push_back(double(run.evaluations));
                if (run.evaluationsToNearBest >= 0) toNearBest.push_back(double(run.evaluationsToNearBest));
            }
            // Over the runs that came near the best known; null (empty CSV field) when none did.
            const double medianToNearBest = toNearBest.empty() ? NAN : median(toNearBest);
            const double minGap = *std::min_element(gap.begin(), gap.end());
            const double maxGap = *std::max_element(gap.begin(), gap.end());
            algorithmsCsv << name << ',' << budget << ',' << wall.size() << ',' << number(median(wall)) << ','
                          << number(median(gap)) << ',' << number(minGap) << ',' << number(maxGap) << ','
                          << number(median(fitness)) << ',' << number(median(evaluations)) << ',' << toNearBest.size()
                          << ',' << number(medianToNearBest) << '\n';
            table.push_back({{"algorithm", name},
                             {"evaluation_budget", budget},
                             {"runs", wall.size()},
                             {"median_wall_seconds", median(wall)},
                             {"median_gap", median(gap)},
                             {"min_gap", minGap},
                             {"max_gap", maxGap},
                             {"median_fitness", median(fitness)},
                             {"median_evaluations", median(evaluations)},
                             {"reached_near_best", toNearBest.size()},
                             {"median_evaluations_to_near_best", jsonNumberOrNull(medianToNearBest)}});
        }
    }
    scenes::writeTextAtomically((dir / kBenchRunsCsv).string(), runsCsv.str());
    scenes::writeTextAtomically((dir / kBenchAlgorithmsCsv).string(), algorithmsCsv.str());
    return table;
}

BenchTables writeTables(const BenchGrid& grid, const std::vector<evaluation::AlgorithmRun>& runs,
                        const BenchCheckpoint& checkpoint, const std::filesystem::path& dir) {
    BenchTables tables;
    tables.algorithms = algorithmTable(grid, runs, dir);
    // Every run with its improvement curve, so that a reader can measure it against another
    // best known (scripts/peers_table.py joins two benches of one view).
    tables.runs = nlohmann::json::array();
    for (const evaluation::AlgorithmRun& run : runs) tables.runs.push_back(runToJson(run));
    std::ostringstream pathsCsv, metricsCsv, timeCsv;
    pathsCsv << "path,workload,mode,threads,candidates,seconds,evals_per_second,mean_abs_fitness_diff,"
                "max_abs_fitness_diff\n";
    tables.paths = nlohmann::json::array();
    for (const evaluation::EvalPathRow& row : *checkpoint.evalPaths) {
        pathsCsv << row.path << ',' << row.workload << ',' << row.mode << ',' << row.threads << ',' << row.candidates
                 << ',' << number(row.seconds) << ',' << number(row.evaluationsPerSecond) << ','
                 << number(row.meanAbsFitnessDiff) << ',' << number(row.maxAbsFitnessDiff) << '\n';
        tables.paths.push_back({{"path", row.path},
                                {"workload", row.workload},
                                {"mode", row.mode},
                                {"threads", row.threads},
                                {"candidates", row.candidates},
                                {"evals_per_second", row.evaluationsPerSecond},
                                {"mean_abs_fitness_diff", jsonNumberOrNull(row.meanAbsFitnessDiff)},
                                {"max_abs_fitness_diff", jsonNumberOrNull(row.maxAbsFitnessDiff)}});
    }
    metricsCsv << "function,width,height,calls,microseconds_per_call,reference,reference_microseconds_per_call,"
                  "abs_deviation\n";
    tables.metrics = nlohmann::json::array();
    for (const evaluation::MetricsRow& row : *checkpoint.metrics) {
        metricsCsv << '"' << row.function << "\"," << row.width << ',' << row.height << ',' << row.calls << ','
                   << number(row.microsecondsPerCall) << ",\"" << row.reference << "\","
                   << number(row.referenceMicrosecondsPerCall) << ',' << number(row.absDeviation) << '\n';
        tables.metrics.push_back(
            {{"function", row.function},
             {"microseconds_per_call", row.microsecondsPerCall},
             {"reference", row.reference},
             {"reference_microseconds_per_call", jsonNumberOrNull(row.referenceMicrosecondsPerCall)},
             {"abs_deviation", jsonNumberOrNull(row.absDeviation)}});
    }
    timeCsv << "model,source,samples,mean_error,median_error,p90_error,max_error\n";
    tables.timeModels = nlohmann::json::array();
    for (const evaluation::TimeModelRow& row : checkpoint.timeModels->rows) {
        timeCsv << row.model << ",\"" << row.source << "\"," << row.samples << ',' << number(row.mean) << ','
                << number(row.median) << ',' << number(row.p90) << ',' << number(row.max) << '\n';
        tables.timeModels.push_back({{"model", row.model},
                                     {"source", row.source},
                                     {"samples", row.samples},
                                     {"mean_error", jsonNumberOrNull(row.mean)},
                                     {"median_error", jsonNumberOrNull(row.median)},
                                     {"p90_error", jsonNumberOrNull(row.p90)},
                                     {"max_error", jsonNumberOrNull(row.max)}});
    }
    scenes::writeTextAtomically((dir / kBenchEvalPathsCsv).string(), pathsCsv.str());
    scenes::writeTextAtomically((dir / kBenchMetricsCsv).string(), metricsCsv.str());
    scenes::writeTextAtomically((dir / kBenchTimeModelCsv).string(), timeCsv.str());
    return tables;
}

void printBench(const nlohmann::json& document, const BenchCheckpoint& checkpoint, const std::filesystem::path& dir,
                bool paretoMade) {
    const nlohmann::json& best = document["best_known"];
    const std::int64_t lastBudget = document["evaluation_budgets"].back().get<std::int64_t>();
    std::cout << document["scene"].get<std::string>() << " / " << document["view"].get<std::string>() << ", "
              << document["size"].get<std::string>() << ", budget " << std::setprecision(4)
              << document["budget_ms"].get<double>() << " ms, " << best["combinations"].get<double>()
              << " combinations, best known " << std::setprecision(6) << best["fitness"].get<double>() << " ("
              << best["source"].get<std::string>() << ")\n";
    std::cout << "median over seeds at " << lastBudget << " evaluations:\n";
    for (const nlohmann::json& row : document["algorithm_budget"]) {
        if (row["evaluation_budget"] != lastBudget) continue;
        const nlohmann::json& toNear = row["median_evaluations_to_near_best"];
        std::cout << "  " << std::left << std::setw(26) << row["algorithm"].get<std::string>() << std::right << " gap "
                  << std::setw(10) << std::setprecision(3) << row["median_gap"].get<double>() << "  wall "
                  << std::setw(8) << row["median_wall_seconds"].get<double>()
                  << " s  within 1e-3: " << row["reached_near_best"].get<int>() << "/" << row["runs"].get<int>()
                  << " runs"
                  << (toNear.is_null() ? std::string() : ", median " + std::to_string(toNear.get<std::int64_t>()))
                  << "\n";
    }
    const nlohmann::json& table = document["surrogate_table"];
    std::cout << "  (mckp's per-view table, not in its wall time: " << table["evaluations"].get<std::int64_t>()
              << " evaluations, " << std::setprecision(3) << table["seconds"].get<double>() << " s)\n";
    for (const evaluation::EvalPathRow& row : *checkpoint.evalPaths) {
        if (row.workload != "random") continue;
        std::cout << "  " << row.path << " path (" << row.mode << ", " << row.threads << " thread"
                  << (row.threads > 1 ? "s" : "") << "): " << std::setprecision(4) << row.evaluationsPerSecond
                  << " evaluations/s";
        if (std::isfinite(row.maxAbsFitnessDiff))
            std::cout << ", max |fast - full| " << std::setprecision(3) << row.maxAbsFitnessDiff;
        std::cout << "\n";
    }
    for (const evaluation::MetricsRow& row : *checkpoint.metrics) {
        std::cout << "  " << std::left << std::setw(30) << row.function << std::right << std::setw(10)
                  << std::setprecision(4) << row.microsecondsPerCall << " us/call";
        if (std::isfinite(row.absDeviation)) std::cout << ", |deviation| " << std::setprecision(3) << row.absDeviation;
        std::cout << "\n";
    }
    for (const evaluation::TimeModelRow& row : checkpoint.timeModels->rows) {
        std::cout << "  time model " << std::left << std::setw(7) << row.model << std::right << " " << row.source
                  << ": mean error " << std::setprecision(3) << 100.0 * row.mean << "% (" << row.samples
                  << " frames)\n";
    }
    for (const std::string& warning : checkpoint.timeModels->warnings) std::cout << "  note: " << warning << "\n";
    std::cout << "wrote " << (dir / kBenchJson).string() << ", " << kBenchAlgorithmsCsv << ", " << kBenchRunsCsv << ", "
              << kBenchEvalPathsCsv << ", " << kBenchMetricsCsv << ", " << kBenchTimeModelCsv
              << (paretoMade ? ", bench_pareto.png" : "") << "\n";
}

void runBench(const BenchOptions& bench) {
    const auto start = std::chrono::steady_clock::now();
    OptimizeOptions options = bench.optimize;
    const BenchGrid grid = parseGrid(bench);
    const std::filesystem::path dir(bench.out);
    const CheckpointFile checkpointFile((dir / kBenchCheckpoint).string(), "bench", "units");
    const nlohmann::json identity = checkpointIdentity(bench);
    BenchCheckpoint checkpoint;
    checkpointFile.restore(bench.resume, bench.output.quiet || bench.output.json, identity,
                           [&](const nlohmann::json& saved) { checkpoint = benchFromCheckpoint(saved); });

    InterruptGuard interruptGuard;
    const bool budgetGiven = options.budgetMs > 0.0;
    if (!budgetGiven) options.budgetMs = std::numeric_limits<double>::max();  // set below from the view
    const bool geometricErrors = std::any_of(grid.algorithms.begin(), grid.algorithms.end(), needsGeometricErrors);
    PreparedScene prepared = prepareScene(options, geometricErrors);
    evaluation::SearchView context = prepareView(prepared, prepared.views[0], options);
    if (!budgetGiven) {
        options.budgetMs = defaultBudget(context);
        context.problem.budgetMs = options.budgetMs;
    }
    const auto [tableEvaluations, tableSeconds] = measureSurrogateTable(context);
    std::vector<evaluation::AlgorithmRun> runs =
        runUnits(bench, grid, options, prepared, context, checkpointFile, identity, checkpoint);
    evaluation::BestKnown best = *checkpoint.bestKnown;
    evaluation::applyBestKnown(best, runs);

    const BenchTables tables = writeTables(grid, runs, checkpoint, dir);
    const Plotter plotter(dir.string());
    const PlotOutput pareto = plotter.plot(paretoPlot(readCsv((dir / kBenchAlgorithmsCsv).string()), "bench_pareto"));
    if (!pareto.made) std::cerr << "lodopt: bench: " << pareto.note << "\n";
    nlohmann::json document = {
        {"format", "lodopt-bench/1"},
        {"scene", prepared.scene.name},
        {"scene_seed", options.sceneSeed},
        {"view", context.setup->camera().name},
        {"size", options.size},
        {"shading", options.shading},
        {"budget_ms", options.budgetMs},
        {"budget_source", budgetGiven ? "--budget-ms" : "midway between the all-coarsest and all-finest prediction"},
        {"time_model", prepared.timeModelName},
        {"threads", options.threads},
        {"seeds", bench.seeds},
        {"evaluation_budgets", grid.budgets},
        {"algorithms", grid.algorithms},
        {"searched_objects", context.setup->skipSummary().searchedObjects},
        {"best_known",
         {{"fitness", best.fitness},
          {"source", best.source},
          {"combinations", best.combinations},
          {"exhaustive_evaluations", best.evaluations},
          {"exhaustive_seconds", best.seconds}}},
        {"surrogate_table",
         {{"evaluations", tableEvaluations},
          {"seconds", tableSeconds},
          {"note", "measured once per view before any run; mckp's wall time excludes it"}}},
        {"algorithm_budget", tables.algorithms},
        {"runs", tables.runs},
        {"eval_paths", tables.paths},
        {"metrics", tables.metrics},
        {"time_model_errors", tables.timeModels},
        {"time_model_warnings", checkpoint.timeModels->warnings},
        {"pareto_plot", pareto.made ? nlohmann::json("bench_pareto.png") : nlohmann::json()},
        {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
    };
    writeJsonFile((dir / kBenchJson).string(), document);
    checkpointFile.remove();  // every unit is now in the outputs
    if (bench.output.json) {
        document["out"] = bench.out;
        printJson(document);
        return;
    }
    printBench(document, checkpoint, dir, pareto.made);
}

}  // namespace

void addBenchCommand(CLI::App& app) {
    auto bench = std::make_shared<BenchOptions>();
    bench->optimize.view = "0";
    CLI::App* command =
        app.add_subcommand("bench", "Run time against error: algorithms, evaluation paths, metrics, time models");
    OptimizeOptions& o = bench->optimize;
    addSceneOption(*command, o.scene);
    addViewOption(*command, o.view, "View name or index");
    command
        ->add_option("--budget-ms", o.budgetMs,
                     "Predicted render-time budget (default: midway between the "
                     "all-coarsest and the all-finest prediction)")
        ->check(CLI::PositiveNumber);
    addSizeOption(*command, o.size, "Render size WIDTHxHEIGHT");
    addShadingOption(*command, o.shading);
    addBackendOptions(*command, o.backend);
    command->add_option("--threads", o.threads, "Evaluation threads (default: all cores)")->check(CLI::Range(1, 256));
    addWeightsOption(*command, o.weights);
    addProfileOptions(*command, o.profile, o.model);
    command->add_option("--seed", o.seed, "Seed of the sampled candidates and time-model frames")
        ->capture_default_str();
    addSceneSeedOption(*command, o.sceneSeed);
    command->add_option("--algos", bench->algorithms, "Comma-separated algorithms")->capture_default_str();
    command->add_option("--seed-from", o.seedFrom,
                        "Start gapso, pso and ga from these algorithms' answers (mckp, greedy, screensize; as "
                        "optimize's default 'screensize,mckp'); default none: every search from a random start");
    command->add_option("--evals", bench->budgets, "Comma-separated evaluation budgets")->capture_default_str();
    command->add_option("--seeds", bench->seeds, "Seeds 1..N per stochastic algorithm and budget")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    command->add_option("--candidates", bench->candidates, "Candidates per workload for fast vs full path")
        ->check(CLI::Range(1, 100000))
        ->capture_default_str();
    command->add_option("--metrics-seconds", bench->metricsSeconds, "Time spent timing each metrics function")
        ->check(CLI::Range(0.001, 60.0))
        ->capture_default_str();
    command->add_option("--timing-frames", bench->timingFrames, "Frames rendered and timed for the time-model check")
        ->check(CLI::Range(1, 10000))
        ->capture_default_str();
    command
        ->add_option("--exhaustive-limit", bench->exhaustiveLimit,
                     "Largest space searched exhaustively for the best known fitness")
        ->check(CLI::Range(1.0, 1e6))
        ->capture_default_str();
    command->add_flag("--quick", bench->quick,
                      "A smoke run: 2 seeds, budgets 30,100, 12 candidates, 8 timed frames, short metric timing "
                      "(explicit options still win)");
    command->add_option("--out", bench->out, "Output folder")->capture_default_str();
    addResumeFlag(*command, bench->resume, "the units in OUT/bench.checkpoint.json");
    addOutputOptions(*command, bench->output);
    command->callback([bench, command] {
        BenchOptions options = *bench;
        if (options.quick) {
            // Only what the user did not set explicitly.
            if (command->count("--seeds") == 0) options.seeds = 2;
            if (command->count("--evals") == 0) options.budgets = "30,100";
            if (command->count("--candidates") == 0) options.candidates = 12;
            if (command->count("--metrics-seconds") == 0) options.metricsSeconds = 0.02;
            if (command->count("--timing-frames") == 0) options.timingFrames = 8;
            options.timingRepeats = 3;
        }
        runBench(options);
    });
}

}  // namespace lodopt::cli
