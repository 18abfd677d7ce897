// lodopt compare: several algorithms × seeds on one view, budget and evaluation budget
// (the published GA-PSO vs PSO vs GA comparison, on our scenes).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "optimize_run.hpp"
#include "progress.hpp"
#include "scenes/atomic_file.hpp"

namespace lodopt::cli {
namespace {

struct RunRecord {
    std::string algorithm;
    std::uint64_t seed = 0;
    optimizer::Result result;
    double wallSeconds = 0.0;
};

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t mid = values.size() / 2;
    return values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

// Evaluations spent when the run's best first reached `target` (-1 if never).
std::int64_t evaluationsToReach(const optimizer::Result& result, double target) {
    for (const optimizer::IterationLog& row : result.log) {
        if (row.bestFitness >= target) return row.evaluations;
    }
    return -1;
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

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto options = std::make_shared<OptimizeOptions>();
    auto algorithms = std::make_shared<std::string>("gapso,pso,ga,random,greedy,screensize,mckp");
    auto seeds = std::make_shared<int>(10);
    auto evaluations = std::make_shared<std::int64_t>(300);
    auto outDir = std::make_shared<std::string>("out/compare");
    auto output = std::make_shared<OutputOptions>();
    CLI::App* command = app.add_subcommand("compare", "Compare algorithms over seeds at equal evaluation budgets");
    addOptimizeOptions(*command, *options);
    command->add_option("--algos", *algorithms, "Comma-separated algorithms")->capture_default_str();
    command->add_option("--seeds", *seeds, "Seeds 1..N per algorithm")->check(CLI::Range(1, 1000))->capture_default_str();
    command->add_option("--evals", *evaluations, "Evaluation budget of every run")
        ->check(CLI::Range(std::int64_t(1), std::int64_t(1) << 30))
        ->capture_default_str();
    command->add_option("--out", *outDir, "Output folder")->capture_default_str();
    addOutputOptions(*command, *output);
    command->callback([=] {
        const std::vector<std::string> names = splitList(*algorithms);
        if (names.empty()) throw UsageError("--algos: empty list");
        for (const std::string& name : names) checkAlgorithmName(name);
        if (options->view == "all") throw UsageError("compare: --view must name one view");
        OptimizeOptions runOptions = *options;
        runOptions.maxEvaluations = *evaluations;
        // The evaluation budget decides; the iteration cap only stops a converged swarm that
        // would otherwise circle through cached candidates forever.
        runOptions.maxIterations = int(std::max<std::int64_t>(*evaluations, 1000));
        runOptions.stableIterations = 0;
        PreparedScene prepared = prepareScene(runOptions);
        ViewContext context = prepareView(prepared, prepared.views[0], runOptions);

        std::vector<RunRecord> runs;
        Progress progress("compare", std::size_t(names.size()) * std::size_t(*seeds), output->quiet || output->json);
        for (const std::string& name : names) {
            for (int seed = 1; seed <= *seeds; ++seed) {
                const auto start = std::chrono::steady_clock::now();
                RunRecord record{name, std::uint64_t(seed), runAlgorithm(context, runOptions, name, std::uint64_t(seed)),
                                 0.0};
                record.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
                runs.push_back(std::move(record));
                progress.step(name + " seed " + std::to_string(seed));
            }
        }
        progress.finish();

        double bestKnown = 0.0;
        for (const RunRecord& run : runs) bestKnown = std::max(bestKnown, run.result.bestScore.fitness);
        nlohmann::json table = nlohmann::json::array();
        std::ostringstream csv, curves;
        csv << "algorithm,runs,median_fitness,min_fitness,max_fitness,median_evals_to_99pct,reached_99pct,"
               "median_wall_seconds,median_evaluations\n";
        curves << "algorithm,seed,iteration,evaluations,best_fitness,mean_fitness\n";
        csv << std::setprecision(8);
        curves << std::setprecision(8);
        for (const std::string& name : names) {
            std::vector<double> fitness, wall, toReach, evals;
            int reached = 0;
            for (const RunRecord& run : runs) {
                if (run.algorithm != name) continue;
                fitness.push_back(run.result.bestScore.fitness);
                wall.push_back(run.wallSeconds);
                evals.push_back(double(run.result.evaluations));
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
            table.push_back({{"algorithm", name},
                             {"runs", fitness.size()},
                             {"median_fitness", median(fitness)},
                             {"min_fitness", minFitness},
                             {"max_fitness", maxFitness},
                             {"median_evals_to_99pct", toReach.empty() ? nlohmann::json() : nlohmann::json(median(toReach))},
                             {"reached_99pct", reached},
                             {"median_wall_seconds", median(wall)},
                             {"median_evaluations", median(evals)}});
            csv << name << ',' << fitness.size() << ',' << median(fitness) << ',' << minFitness << ',' << maxFitness
                << ',' << (toReach.empty() ? std::string("") : std::to_string(median(toReach))) << ',' << reached << ','
                << median(wall) << ',' << median(evals) << '\n';
        }
        const std::filesystem::path dir(*outDir);
        nlohmann::json document = {{"scene", prepared.scene.name},
                                   {"view", context.setup->camera().name},
                                   {"budget_ms", runOptions.budgetMs},
                                   {"evaluation_budget", *evaluations},
                                   {"seeds", *seeds},
                                   {"best_known_fitness", bestKnown},
                                   {"searched_objects", context.setup->skipSummary().searchedObjects},
                                   {"algorithms", table}};
        writeJsonFile((dir / "compare.json").string(), document);
        scenes::writeTextAtomically((dir / "compare.csv").string(), csv.str());
        scenes::writeTextAtomically((dir / "curves.csv").string(), curves.str());
        if (output->json) {
            printJson(document);
            return;
        }
        std::cout << prepared.scene.name << " / " << context.setup->camera().name << ", budget " << runOptions.budgetMs
                  << " ms, " << *evaluations << " evaluations per run, " << *seeds << " seeds, best known "
                  << std::setprecision(6) << bestKnown << "\n";
        std::cout << std::left << std::setw(12) << "algorithm" << std::right << std::setw(10) << "median"
                  << std::setw(10) << "min" << std::setw(10) << "max" << std::setw(14) << "evals→99%" << std::setw(10)
                  << "wall s\n";
        for (const nlohmann::json& row : table) {
            std::cout << std::left << std::setw(12) << row["algorithm"].get<std::string>() << std::right << std::fixed
                      << std::setprecision(4) << std::setw(10) << row["median_fitness"].get<double>() << std::setw(10)
                      << row["min_fitness"].get<double>() << std::setw(10) << row["max_fitness"].get<double>()
                      << std::setw(14)
                      << (row["median_evals_to_99pct"].is_null() ? std::string("-")
                                                                 : std::to_string(int(row["median_evals_to_99pct"].get<double>())))
                      << std::setw(10) << std::setprecision(3) << row["median_wall_seconds"].get<double>() << "\n";
            std::cout.unsetf(std::ios::floatfield);
        }
        std::cout << "wrote " << (dir / "compare.json").string() << ", compare.csv, curves.csv\n";
    });
}

}  // namespace lodopt::cli
