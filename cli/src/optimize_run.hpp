// Shared by optimize, compare and bench: preparing a scene and view, running one algorithm.
#pragma once

#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_common.hpp"

#include "evaluation/evaluation.hpp"
#include "evaluation/search_view.hpp"
#include "evaluation/time_cost.hpp"
#include "optimizer/optimizer.hpp"
#include "renderer/renderer.hpp"
#include "scenes/scene.hpp"

namespace CLI {
class App;
}

namespace lodopt::cli {

struct OptimizeOptions {
    std::string scene = "harbor";
    std::string view = "overview";
    std::string algorithm = "gapso";
    double budgetMs = 0.0;
    std::uint64_t seed = 1;       // the search's (and a command's sampling); never the scene's
    std::uint32_t sceneSeed = 1;  // a built-in scene's variant (--scene-seed)
    std::string size = "512x512";
    std::string shading = renderer::shadingName(renderer::kDefaultShading);  // renderer::Shading by name
    BackendOptions backend;  // the platform and frame clock bench times on
    std::string evalPath = "fast";
    int threads = std::max(1, int(std::thread::hardware_concurrency()));
    // Fast-path evaluation states (LayerEvaluator); tune keeps one evaluator per view and
    // lowers this to save memory.
    int evalStates = evaluation::LayerEvaluator::kDefaultStates;
    std::string weights = "1,1,1";
    std::string profile;
    std::string model;
    int maxIterations = 50;
    std::int64_t maxEvaluations = 0;
    int stableIterations = 15;
    double maxSeconds = 0.0;
    bool paper = false;
    // Comma-separated algorithms whose answers start the swarm (mckp, greedy, screensize), or
    // "none" / empty. `optimize` defaults to "screensize,mckp" (the swarm then never returns
    // less than the engine baseline); compare and bench default to none, so that algorithms
    // are compared from the same random start.
    std::string seedFrom;
    int particles = 0;  // 0 = the algorithm's default
    // GA-PSO's fill probability (GapsoParameters::fillProbability); < 0 = the default (0 with --paper).
    double fillProbability = -1.0;
    JudgeOptions judge;  // scores the answers kept (result.json "judge"); never the search
};
// The fill probability a swarm run with these options uses (optimizer::effectiveFillProbability).
double effectiveFillProbability(const OptimizeOptions& options);
void addOptimizeOptions(CLI::App& command, OptimizeOptions& options);
// addOptimizeOptions without --view, for commands that choose their own viewpoints (sweep).
void addSearchOptions(CLI::App& command, OptimizeOptions& options);
// --fill alone (tune takes it without the other optimize options); its help names the defaults.
void addFillOption(CLI::App& command, OptimizeOptions& options);

// The algorithms named by OptimizeOptions::seedFrom, in order, without repeats; throws
// UsageError for a name that is not mckp, greedy or screensize.
std::vector<std::string> seedAlgorithms(const std::string& seedFrom);

// "gapso, pso, ..." for help texts; throws UsageError for an unknown name.
std::string algorithmList();
void checkAlgorithmName(const std::string& name);

struct PreparedScene {
    scenes::Scene scene;
    std::vector<int> views;
    renderer::RenderSettings settings;
    metrics::MetricParameters metrics;
    evaluation::FrameTimeEstimator estimator;
    timemodel::FeatureSet readFeatures = timemodel::everyFeature();  // what `estimator` reads (tables skip the rest)
    std::string timeModelName;
    std::unique_ptr<renderer::Renderer> renderer;
};
// The engines' rules (pixelerror, unreal-auto) read each level's measured geometric error.
bool needsGeometricErrors(const std::string& algorithm);
// Loads the scene, its renderer and time model; measures the levels' geometric errors
// (scenes::computeGeometricErrors) when `geometricErrors` or options.algorithm needs them.
PreparedScene prepareScene(const OptimizeOptions& options, bool geometricErrors = false);

// The view preparation these options ask for (evaluation path, threads, states, budget).
evaluation::SearchViewSettings searchViewSettings(const OptimizeOptions& options);

// Everything about one view that does not depend on the algorithm (evaluation::prepareSearchView
// with these options): reusable across runs.
evaluation::SearchView prepareView(PreparedScene& prepared, int view, const OptimizeOptions& options);

// optimizer::runSearch's options for `algorithm` and `seed` from the command's options.
optimizer::SearchOptions searchOptions(const OptimizeOptions& options, const std::string& algorithm,
                                       std::uint64_t seed);
// Runs `algorithm` with `seed` on a prepared view (optimizer::runSearch).
optimizer::Result runAlgorithm(const evaluation::SearchView& context, const OptimizeOptions& options,
                               const std::string& algorithm, std::uint64_t seed);

struct ViewRun {
    std::unique_ptr<evaluation::ViewSetup> setup;
    optimizer::Result result;
    nlohmann::json json;  // the result.json document
    renderer::Frame optimizedImage;
};
ViewRun runOptimizer(PreparedScene& prepared, int view, const OptimizeOptions& options,
                     const std::string& algorithm, std::uint64_t seed);

void printOptimizeSummary(std::ostream& out, const nlohmann::json& result);

}  // namespace lodopt::cli
