// lodopt compare: several algorithms × seeds on one view, budget and evaluation budget
// (the published GA-PSO vs PSO vs GA comparison, on our scenes).
//
// Each (algorithm, seed) run is one unit of work: after it, every finished run is saved in
// <out>/compare.checkpoint.json (atomically) and an interrupt (SIGINT/SIGTERM) stops there;
// --resume reuses the saved runs, so the outputs equal an uninterrupted run's (wall times
// aside). The checkpoint is removed once compare.json, compare.csv and curves.csv are written.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "checkpoint.hpp"
#include "cli_common.hpp"
#include "interrupt.hpp"
#include "optimize_run.hpp"
#include "progress.hpp"
#include "scenes/atomic_file.hpp"
#include "statistics.hpp"

namespace lodopt::cli {
namespace {

struct RunRecord {
    std::string algorithm;
    std::uint64_t seed = 0;
    optimizer::Result result;
    double wallSeconds = 0.0;
    std::optional<double> judge;  // butteraugli of the run's best, rendered (never read by a search)
};

// Evaluations spent when the run's best first reached `target` (-1 if never).
std::int64_t evaluationsToReach(const optimizer::Result& result, double target) {
    for (const optimizer::IterationLog& row : result.log) {
        if (row.bestFitness >= target) return row.evaluations;
    }
    return -1;
}

// The checkpoint stores doubles through JSON, which writes NaN as null.
nlohmann::json runToJson(const RunRecord& run) {
    const optimizer::Result& result = run.result;
    nlohmann::json log = nlohmann::json::array();
    for (const optimizer::IterationLog& row : result.log) {
        log.push_back({row.iteration, row.bestFitness, row.meanFitness, row.bestPredictedMs, row.evaluations,
                       row.cacheHits, row.elapsedSeconds});
    }
    const auto& components = result.bestScore.components;
    return {
        {"algorithm", run.algorithm},
        {"seed", run.seed},
        {"wall_seconds", run.wallSeconds},
        {"best", result.best},
        {"fitness", result.bestScore.fitness},
        {"components", std::vector<double>(components.begin(), components.begin() + result.bestScore.componentCount)},
        {"predicted_ms", result.predictedMs},
        {"evaluations", result.evaluations},
        {"cache_hits", result.cacheHits},
        {"iterations", result.iterations},
        {"stop_reason", std::string(optimizer::toString(result.stopReason))},
        {"judge", run.judge ? nlohmann::json(*run.judge) : nlohmann::json(nullptr)},
        {"log", log}};
}

RunRecord runFromJson(const nlohmann::json& saved) {
    RunRecord run;
    run.algorithm = saved.at("algorithm").get<std::string>();
    run.seed = saved.at("seed").get<std::uint64_t>();
    run.wallSeconds = numberOrNaN(saved.at("wall_seconds"));
    if (saved.contains("judge") && !saved["judge"].is_null()) run.judge = saved["judge"].get<double>();
    optimizer::Result& result = run.result;
    result.algorithm = run.algorithm;
    result.best = saved.at("best").get<optimizer::Combination>();
    result.bestScore.fitness = numberOrNaN(saved.at("fitness"));
    const nlohmann::json& components = saved.at("components");
    if (components.size() > optimizer::Score::kMaxComponents) throw std::out_of_range("too many components");
    for (std::size_t c = 0; c < components.size(); ++c) result.bestScore.components[c] = numberOrNaN(components[c]);
    result.bestScore.componentCount = int(components.size());
    result.predictedMs = numberOrNaN(saved.at("predicted_ms"));
    result.evaluations = saved.at("evaluations").get<std::int64_t>();
    result.cacheHits = saved.at("cache_hits").get<std::int64_t>();
    result.iterations = saved.at("iterations").get<int>();
    const std::string stop = saved.at("stop_reason").get<std::string>();
    for (optimizer::StopReason reason :
         {optimizer::StopReason::Completed, optimizer::StopReason::MaxIterations, optimizer::StopReason::Stable,
          optimizer::StopReason::MaxEvaluations, optimizer::StopReason::WallTime}) {
        if (optimizer::toString(reason) == stop) result.stopReason = reason;
    }
    for (const nlohmann::json& row : saved.at("log")) {
        result.log.push_back({row.at(0).get<int>(), numberOrNaN(row.at(1)), numberOrNaN(row.at(2)),
                              numberOrNaN(row.at(3)), row.at(4).get<std::int64_t>(), row.at(5).get<std::int64_t>(),
                              numberOrNaN(row.at(6))});
    }
    return run;
}

std::string runKey(const std::string& algorithm, std::uint64_t seed) {
    return algorithm + "#" + std::to_string(seed);
}

// Everything that changes a run's result, keyed by option name; --threads does not (results are identical for any
// thread count), so a run may be resumed with another one. --algos and --seeds may change
// too: runs are matched by algorithm and seed.
nlohmann::json checkpointIdentity(const OptimizeOptions& options, std::int64_t evaluations) {
    return {{"scene", options.scene},
            {"scene-seed", options.sceneSeed},
            {"view", options.view},
            {"budget-ms", options.budgetMs},
            {"evals", evaluations},
            {"size", options.size},
            {"shading", options.shading},
            {"eval", options.evalPath},
            {"weights", options.weights},
            {"profile", options.profile},
            {"model", options.model},
            {"paper", options.paper},
            {"seed-from", options.seedFrom},
            {"particles", options.particles},
            {"max-seconds", options.maxSeconds},
            {"fill", effectiveFillProbability(options)},
            {"judge", judgeIdentity(options.judge)}};
}

// The saved runs of an earlier, interrupted compare, by runKey.
std::map<std::string, RunRecord> runsFromCheckpoint(const nlohmann::json& saved) {
    std::map<std::string, RunRecord> runs;
    for (const nlohmann::json& item : saved.at("runs")) {
        RunRecord run = runFromJson(item);
        runs[runKey(run.algorithm, run.seed)] = std::move(run);
    }
    return runs;
}

nlohmann::json runsToCheckpoint(const std::map<std::string, RunRecord>& runs) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& [key, run] : runs) list.push_back(runToJson(run));
    return {{"runs", list}};
}

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        if (!item.empty()) items.push_back(item);
    }
    return items;
}

struct CompareOptions {
    OptimizeOptions optimize;
    std::string algorithms = "gapso,pso,ga,random,greedy,screensize,mckp";
    int seeds = 10;
    std::int64_t evaluations = 300;
    std::string outDir = "out/compare";
    bool resume = false;
    OutputOptions output;
};

// Every (algorithm, seed) run, those in `saved` taken from there; each new one is saved and an
// interrupt stops after it.
std::vector<RunRecord> runAll(const CompareOptions& compare, const std::vector<std::string>& names,
                              const OptimizeOptions& runOptions, const evaluation::SearchView& context,
                              renderer::Renderer& renderer, const CheckpointFile& checkpoint,
                              const nlohmann::json& identity, std::map<std::string, RunRecord>& saved) {
    const std::size_t total = names.size() * std::size_t(compare.seeds);
    std::size_t done = 0;
    for (const std::string& name : names) {
        for (int seed = 1; seed <= compare.seeds; ++seed) done += saved.count(runKey(name, std::uint64_t(seed)));
    }
    if (done < total) pollInterrupt("compare", done, total, "run", checkpoint.path());
    std::vector<RunRecord> runs;
    Progress progress("compare", total - done, compare.output.quiet || compare.output.json);
    for (const std::string& name : names) {
        for (int seed = 1; seed <= compare.seeds; ++seed) {
            auto found = saved.find(runKey(name, std::uint64_t(seed)));
            if (found != saved.end()) {
                runs.push_back(found->second);
                continue;
            }
            const auto start = std::chrono::steady_clock::now();
            RunRecord record{name, std::uint64_t(seed), runAlgorithm(context, runOptions, name, std::uint64_t(seed)),
                             0.0, std::nullopt};
            record.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (const std::optional<metrics::JudgeParameters> judge = judgeParameters(runOptions.judge)) {
                const evaluation::ViewSetup& setup = *context.setup;
                const renderer::Frame image = renderer.render(setup.toScene(record.result.best), setup.camera());
                record.judge = evaluation::judgeFrame(image, setup.reference(), *judge).distance;
            }
            saved[runKey(name, std::uint64_t(seed))] = record;
            runs.push_back(std::move(record));
            checkpoint.save(identity, runsToCheckpoint(saved));
            progress.step(name + " seed " + std::to_string(seed));
            // After the last run only the summary is left: finish it rather than stop.
            try {
                if (++done < total) pollInterrupt("compare", done, total, "run", checkpoint.path());
            } catch (const Interrupted&) {
                progress.finish();  // the message starts on a clean line
                throw;
            }
        }
    }
    progress.finish();
    return runs;
}

// The per-algorithm table (compare.json's "algorithms"), with compare.csv and curves.csv.
nlohmann::json summarize(const std::vector<std::string>& names, const std::vector<RunRecord>& runs, double bestKnown,
                         const std::filesystem::path& dir) {
    nlohmann::json table = nlohmann::json::array();
    std::ostringstream csv, curves;
    csv << "algorithm,runs,median_fitness,min_fitness,max_fitness,median_evals_to_99pct,reached_99pct,"
           "median_wall_seconds,median_evaluations,median_judge\n";
    curves << "algorithm,seed,iteration,evaluations,best_fitness,mean_fitness\n";
    csv << std::setprecision(8);
    curves << std::setprecision(8);
    for (const std::string& name : names) {
        std::vector<double> fitness, wall, toReach, evals, judged;
        int reached = 0;
        for (const RunRecord& run : runs) {
            if (run.algorithm != name) continue;
            fitness.push_back(run.result.bestScore.fitness);
            wall.push_back(run.wallSeconds);
            evals.push_back(double(run.result.evaluations));
            if (run.judge) judged.push_back(*run.judge);
            const std::int64_t k = evaluationsToReach(run.result, 0.99 * bestKnown);
            if (k >= 0) {
                ++reached;
                toReach.push_back(double(k));
            }
            for (const optimizer::IterationLog& row : run.result.log) {
                curves << name << ',' << run.seed << ',' << row.iteration << ',' << row.evaluations << ','
                       << row.bestFitness << ',' << row.meanFitness << '\n';
            }
        }
        const double minFitness = *std::min_element(fitness.begin(), fitness.end());
        const double maxFitness = *std::max_element(fitness.begin(), fitness.end());
        table.push_back(
            {{"algorithm", name},
             {"runs", fitness.size()},
             {"median_fitness", median(fitness)},
             {"min_fitness", minFitness},
             {"max_fitness", maxFitness},
             {"median_evals_to_99pct", toReach.empty() ? nlohmann::json() : nlohmann::json(median(toReach))},
             {"reached_99pct", reached},
             {"median_wall_seconds", median(wall)},
             {"median_evaluations", median(evals)},
             {"median_judge", judged.empty() ? nlohmann::json() : nlohmann::json(median(judged))}});
        csv << name << ',' << fitness.size() << ',' << median(fitness) << ',' << minFitness << ',' << maxFitness << ','
            << (toReach.empty() ? std::string("") : std::to_string(median(toReach))) << ',' << reached << ','
            << median(wall) << ',' << median(evals) << ','
            << (judged.empty() ? std::string("") : std::to_string(median(judged))) << '\n';
    }
    scenes::writeTextAtomically((dir / "compare.csv").string(), csv.str());
    scenes::writeTextAtomically((dir / "curves.csv").string(), curves.str());
    return table;
}

// The judge's median distance, three decimals.
std::string formatJudge(double distance) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(3) << distance;
    return text.str();
}

void printCompare(const nlohmann::json& document, const std::filesystem::path& dir) {
    std::cout << document["scene"].get<std::string>() << " / " << document["view"].get<std::string>() << ", budget "
              << document["budget_ms"].get<double>() << " ms, " << document["evaluation_budget"].get<std::int64_t>()
              << " evaluations per run, " << document["seeds"].get<int>() << " seeds, best known "
              << std::setprecision(6) << document["best_known_fitness"].get<double>() << "\n";
    // The name column fits the longest name ("pagmo:simulated_annealing").
    int nameWidth = 12;
    for (const nlohmann::json& row : document["algorithms"]) {
        nameWidth = std::max(nameWidth, int(row["algorithm"].get<std::string>().size()) + 2);
    }
    std::cout << std::left << std::setw(nameWidth) << "algorithm" << std::right << std::setw(10) << "median"
              << std::setw(10) << "min" << std::setw(10) << "max" << std::setw(14) << "evals→99%" << std::setw(10)
              << "wall s" << std::setw(10) << "judge\n";
    for (const nlohmann::json& row : document["algorithms"]) {
        std::cout << std::left << std::setw(nameWidth) << row["algorithm"].get<std::string>() << std::right
                  << std::fixed << std::setprecision(4) << std::setw(10) << row["median_fitness"].get<double>()
                  << std::setw(10) << row["min_fitness"].get<double>() << std::setw(10)
                  << row["max_fitness"].get<double>() << std::setw(14)
                  << (row["median_evals_to_99pct"].is_null()
                          ? std::string("-")
                          : std::to_string(int(row["median_evals_to_99pct"].get<double>())))
                  << std::setw(10) << std::setprecision(3) << row["median_wall_seconds"].get<double>() << std::setw(10)
                  << (row["median_judge"].is_null() ? std::string("-") : formatJudge(row["median_judge"].get<double>()))
                  << "\n";
        std::cout.unsetf(std::ios::floatfield);
    }
    std::cout << "wrote " << (dir / "compare.json").string() << ", compare.csv, curves.csv\n";
}

void runCompare(const CompareOptions& compare) {
    const std::vector<std::string> names = splitList(compare.algorithms);
    if (names.empty()) throw UsageError("--algos: empty list");
    for (const std::string& name : names) checkAlgorithmName(name);
    if (compare.optimize.view == "all") throw UsageError("compare: --view must name one view");
    OptimizeOptions runOptions = compare.optimize;
    runOptions.maxEvaluations = compare.evaluations;
    // The evaluation budget decides; the iteration cap only stops a converged swarm that
    // would otherwise circle through cached candidates forever.
    runOptions.maxIterations = int(std::max<std::int64_t>(compare.evaluations, 1000));
    runOptions.stableIterations = 0;

    const std::filesystem::path dir(compare.outDir);
    const CheckpointFile checkpoint((dir / "compare.checkpoint.json").string(), "compare", "runs");
    const nlohmann::json identity = checkpointIdentity(runOptions, compare.evaluations);
    std::map<std::string, RunRecord> saved;
    checkpoint.restore(compare.resume, compare.output.quiet || compare.output.json, identity,
                       [&](const nlohmann::json& document) { saved = runsFromCheckpoint(document); });
    InterruptGuard interruptGuard;
    const bool geometricErrors = std::any_of(names.begin(), names.end(), needsGeometricErrors);
    PreparedScene prepared = prepareScene(runOptions, geometricErrors);
    evaluation::SearchView context = prepareView(prepared, prepared.views[0], runOptions);
    const std::vector<RunRecord> runs =
        runAll(compare, names, runOptions, context, *prepared.renderer, checkpoint, identity, saved);

    double bestKnown = 0.0;
    for (const RunRecord& run : runs) bestKnown = std::max(bestKnown, run.result.bestScore.fitness);
    nlohmann::json document = {{"scene", prepared.scene.name},
                               {"view", context.setup->camera().name},
                               {"budget_ms", runOptions.budgetMs},
                               {"evaluation_budget", compare.evaluations},
                               {"seeds", compare.seeds},
                               {"best_known_fitness", bestKnown},
                               {"searched_objects", context.setup->skipSummary().searchedObjects},
                               {"algorithms", summarize(names, runs, bestKnown, dir)}};
    writeJsonFile((dir / "compare.json").string(), document);
    checkpoint.remove();  // every run is now in the outputs
    if (compare.output.json) {
        printJson(document);
        return;
    }
    printCompare(document, dir);
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto compare = std::make_shared<CompareOptions>();
    CLI::App* command = app.add_subcommand("compare", "Compare algorithms over seeds at equal evaluation budgets");
    addOptimizeOptions(*command, compare->optimize);
    command->remove_option(command->get_option("--seed"));  // the runs take seeds 1..--seeds
    command->add_option("--algos", compare->algorithms, "Comma-separated algorithms")->capture_default_str();
    command->add_option("--seeds", compare->seeds, "Seeds 1..N per algorithm")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    command->add_option("--evals", compare->evaluations, "Evaluation budget of every run")
        ->check(CLI::Range(std::int64_t(1), std::int64_t(1) << 30))
        ->capture_default_str();
    command->add_option("--out", compare->outDir, "Output folder")->capture_default_str();
    addResumeFlag(*command, compare->resume, "the runs in OUT/compare.checkpoint.json");
    addOutputOptions(*command, compare->output);
    command->callback([compare] { runCompare(*compare); });
}

}  // namespace lodopt::cli
