// lodopt optimize: the best LOD combination for a view under a render-time budget.
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli_common.hpp"
#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "optimize_run.hpp"
#include "optimizer/optimizer.hpp"
#include "renderer/renderer.hpp"
#include "scenes/atomic_file.hpp"
#include "scenes/builtin.hpp"

namespace lodopt::cli {
namespace {

std::string curveCsv(const optimizer::Result& result) {
    std::ostringstream csv;
    csv << "iteration,best_fitness,mean_fitness,best_predicted_ms,evaluations,cache_hits,elapsed_seconds\n";
    csv << std::setprecision(10);
    for (const optimizer::IterationLog& row : result.log) {
        csv << row.iteration << ',' << row.bestFitness << ',' << row.meanFitness << ',' << row.bestPredictedMs << ','
            << row.evaluations << ',' << row.cacheHits << ',' << row.elapsedSeconds << '\n';
    }
    return csv.str();
}

}  // namespace

void addOptimizeOptions(CLI::App& command, OptimizeOptions& options) {
    addSceneOption(command, options.scene);
    addViewOption(command, options.view, "View name, index, or 'all'");
    addSearchOptions(command, options);
}

void addSearchOptions(CLI::App& command, OptimizeOptions& options) {
    command.add_option("--budget-ms", options.budgetMs, "Predicted render-time budget in milliseconds")
        ->required()
        ->check(CLI::PositiveNumber);
    command.add_option("--seed", options.seed, "Seed of the search (results are deterministic for a seed)")
        ->capture_default_str();
    addSceneSeedOption(command, options.sceneSeed);
    addSizeOption(command, options.size, "Render size WIDTHxHEIGHT");
    addShadingOption(command, options.shading);
    command.add_option("--eval", options.evalPath, "Evaluation path: fast (layers) or full (render each)")
        ->check(CLI::IsMember({"fast", "full"}))
        ->capture_default_str();
    command.add_option("--threads", options.threads, "Evaluation threads (default: all cores)")
        ->check(CLI::Range(1, 256));
    addWeightsOption(command, options.weights);
    addProfileOptions(command, options.profile, options.model);
    command.add_option("--max-iterations", options.maxIterations, "Iterations of iterative searches")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    command.add_option("--max-evals", options.maxEvaluations, "Evaluation budget (0 = none)")
        ->check(CLI::Range(std::int64_t(0), std::int64_t(1) << 40));
    command.add_option("--stable", options.stableIterations, "Stop after K iterations without improvement (0 = off)")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    command.add_option("--max-seconds", options.maxSeconds, "Wall-time limit per view (0 = none)")
        ->check(CLI::NonNegativeNumber);
    command.add_flag("--paper", options.paper,
                     "GA-PSO with the published settings (c1=c2=2, w=1, 3 particles, 20 it.)");
    command
        .add_option("--seed-from", options.seedFrom,
                    "Start the swarm from these algorithms' answers: comma-separated mckp, greedy, screensize, or none")
        ->check([](const std::string& value) {
            try {
                seedAlgorithms(value);
            } catch (const UsageError& error) {
                return std::string(error.what());
            }
            return std::string();
        })
        ->capture_default_str();
    command.add_option("--particles", options.particles, "GA-PSO swarm size")->check(CLI::Range(1, 10000));
    addFillOption(command, options);
    addJudgeOptions(command, options.judge);
}

void addFillOption(CLI::App& command, OptimizeOptions& options) {
    std::ostringstream help;
    help << "GA-PSO: probability per particle and evaluation of filling the unused budget (default "
         << optimizer::GapsoParameters{}.fillProbability
         << "; the paper's settings: " << optimizer::GapsoParameters::paper().fillProbability << ")";
    command.add_option("--fill", options.fillProbability, help.str())->check(CLI::Range(0.0, 1.0));
}

void addOptimizeCommand(CLI::App& app) {
    auto options = std::make_shared<OptimizeOptions>();
    // The answer a user gets is never below the engine baseline's: the swarm starts from it.
    options->seedFrom = "screensize,mckp";
    auto outDir = std::make_shared<std::string>("out/optimize");
    auto output = std::make_shared<OutputOptions>();
    CLI::App* command = app.add_subcommand("optimize", "Find the best LOD combination under a time budget");
    addOptimizeOptions(*command, *options);
    command->add_option("--algo", options->algorithm, "Algorithm: " + algorithmList())->capture_default_str();
    command->add_option("--out", *outDir, "Output folder")->capture_default_str();
    addOutputOptions(*command, *output);
    command->callback([options, outDir, output] {
        checkAlgorithmName(options->algorithm);
        PreparedScene prepared = prepareScene(*options);
        nlohmann::json all = nlohmann::json::array();
        for (int view : prepared.views) {
            const scenes::Camera& camera = prepared.scene.views[view];
            const std::string dir =
                prepared.views.size() > 1 ? (std::filesystem::path(*outDir) / camera.name).string() : *outDir;
            ViewRun run = runOptimizer(prepared, view, *options, options->algorithm, options->seed);
            nlohmann::json result = run.json;
            writeJsonFile((std::filesystem::path(dir) / "result.json").string(), result);
            scenes::writeTextAtomically((std::filesystem::path(dir) / "curve.csv").string(), curveCsv(run.result));
            renderer::writeColorImage((std::filesystem::path(dir) / "optimized.png").string(), run.optimizedImage);
            renderer::writeColorImage((std::filesystem::path(dir) / "reference.png").string(), run.setup->reference());
            result["out"] = dir;
            all.push_back(result);
            if (!output->json) printOptimizeSummary(std::cout, result);
        }
        if (output->json) printJson(prepared.views.size() == 1 ? all[0] : nlohmann::json{{"views", all}});
    });
}

}  // namespace lodopt::cli
