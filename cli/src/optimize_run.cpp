#include "optimize_run.hpp"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <map>

#include "cli_common.hpp"
#include "optimizer/baselines.hpp"
#include "optimizer/gapso.hpp"
#include "optimizer/search.hpp"
#include "scenes/builtin.hpp"
#include "scenes/geometric_error.hpp"
#include "time_profile.hpp"

namespace lodopt::cli {

std::string algorithmList() {
    std::string list;
    for (const std::string& name : optimizer::algorithmNames()) list += (list.empty() ? "" : ", ") + name;
    return list;
}

void checkAlgorithmName(const std::string& name) {
    for (const std::string& known : optimizer::algorithmNames()) {
        if (known == name) return;
    }
    throw UsageError("unknown algorithm '" + name + "' (expected one of: " + algorithmList() + ")");
}

bool needsGeometricErrors(const std::string& algorithm) {
    return algorithm == "pixelerror" || algorithm == "unreal-auto";
}

PreparedScene prepareScene(const OptimizeOptions& options, bool geometricErrors) {
    PreparedScene prepared;
    parseSize(options.size, prepared.settings.width, prepared.settings.height);
    prepared.settings.shading = renderer::parseShading(options.shading);
    options.backend.applyTo(prepared.settings);
    parseWeights(options.weights, prepared.metrics);
    prepared.scene = scenes::loadScene(options.scene, options.sceneSeed);
    if (options.view == "all") {
        for (std::size_t v = 0; v < prepared.scene.views.size(); ++v) prepared.views.push_back(int(v));
    } else {
        prepared.views.push_back(scenes::findView(prepared.scene, options.view));
    }
    if (prepared.scene.objects.empty()) throw UsageError("scene '" + prepared.scene.name + "' has no objects");
    if (geometricErrors || needsGeometricErrors(options.algorithm)) scenes::computeGeometricErrors(prepared.scene);
    prepared.renderer = std::make_unique<renderer::Renderer>(prepared.scene, prepared.settings);
    TimeEstimator estimator = loadTimeEstimator(options.profile, options.model, prepared.scene.name, prepared.settings,
                                                prepared.renderer.get(), std::cerr);
    prepared.estimator = estimator.estimate;
    prepared.readFeatures = estimator.model->readFeatures();
    prepared.timeModelName = estimator.name;
    return prepared;
}

evaluation::SearchViewSettings searchViewSettings(const OptimizeOptions& options) {
    evaluation::SearchViewSettings settings;
    settings.path = options.evalPath == "full" ? evaluation::EvaluationPath::Full : evaluation::EvaluationPath::Fast;
    settings.threads = options.threads;
    settings.states = options.evalStates;
    settings.budgetMs = options.budgetMs;
    settings.judge = judgeParameters(options.judge);
    return settings;
}

evaluation::SearchView prepareView(PreparedScene& prepared, int view, const OptimizeOptions& options) {
    return evaluation::prepareSearchView(prepared.scene, prepared.scene.views[std::size_t(view)], *prepared.renderer,
                                         prepared.metrics, prepared.estimator, prepared.readFeatures,
                                         searchViewSettings(options));
}

std::vector<std::string> seedAlgorithms(const std::string& seedFrom) {
    std::vector<std::string> names;
    if (seedFrom.empty() || seedFrom == "none") return names;
    std::size_t start = 0;
    while (start <= seedFrom.size()) {
        const std::size_t comma = std::min(seedFrom.find(',', start), seedFrom.size());
        const std::string name = seedFrom.substr(start, comma - start);
        if (!optimizer::isStartAlgorithm(name)) {
            throw UsageError("--seed-from: '" + name + "' is not mckp, greedy or screensize (or none)");
        }
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        start = comma + 1;
    }
    return names;
}

optimizer::SearchOptions searchOptions(const OptimizeOptions& options, const std::string& algorithm,
                                       std::uint64_t seed) {
    optimizer::SearchOptions search;
    search.algorithm = algorithm;
    search.seed = seed;
    search.termination.maxIterations = options.maxIterations;
    search.termination.stableIterations = options.stableIterations;
    search.termination.maxEvaluations = options.maxEvaluations;
    search.termination.maxSeconds = options.maxSeconds;
    search.paper = options.paper;
    search.particles = options.particles;
    search.fillProbability = options.fillProbability;
    search.startFrom = seedAlgorithms(options.seedFrom);
    return search;
}

double effectiveFillProbability(const OptimizeOptions& options) {
    optimizer::SearchOptions search;
    search.paper = options.paper;
    search.fillProbability = options.fillProbability;
    return optimizer::effectiveFillProbability(search);
}

optimizer::Result runAlgorithm(const evaluation::SearchView& context, const OptimizeOptions& options,
                               const std::string& algorithm, std::uint64_t seed) {
    return optimizer::runSearch(context.problem, searchOptions(options, algorithm, seed));
}

namespace {

// The fast path's owned-window cache after the search (null for the full path and when the
// window groups serve): how many SSIM windows one searched object owns (scored once per level)
// and how many read several (scored per candidate), the (object, level) entries filled and
// their memory.
nlohmann::json ownedWindowsJson(const optimizer::Evaluator* evaluator) {
    const auto* layers = dynamic_cast<const evaluation::LayerEvaluator*>(evaluator);
    if (!layers) return nullptr;
    const metrics::PartCacheStats stats = layers->partCacheStats();
    if (stats.parts == 0) return nullptr;
    return {{"owned_ssim_windows", stats.ownedSsimWindows},
            {"live_ssim_windows", stats.liveSsimWindows},
            {"entries_filled", stats.filledEntries},
            {"entries", stats.entries},
            {"bytes", stats.bytes}};
}

// The fast path's window groups after the search (null for the full path and when they are
// not used): groups, the SSIM windows that depend on two or more objects, kept scores and
// their memory. (How many look-ups found a kept score depends on thread timing: two threads
// may both score a combination neither has found yet, so it is left out of the results.)
nlohmann::json windowGroupsJson(const optimizer::Evaluator* evaluator) {
    const auto* layers = dynamic_cast<const evaluation::LayerEvaluator*>(evaluator);
    if (!layers) return nullptr;
    const evaluation::GroupCacheStats stats = layers->groupCacheStats();
    if (stats.groups == 0) return nullptr;
    return {{"groups", stats.groups},
            {"largest_group_objects", stats.largestGroup},
            {"uncacheable_groups", stats.uncacheableGroups},
            {"ssim_windows", stats.ssimWindows},
            {"multi_object_ssim_windows", stats.multiObjectSsimWindows},
            {"kept_scores", stats.entries},
            {"bytes", stats.bytes}};
}

// Level per object by name ("object<i>" when unnamed, "#<i>" appended to a repeated name).
nlohmann::json levelsByName(const scenes::Scene& scene, const scenes::Combination& levels) {
    nlohmann::json levelMap = nlohmann::json::object();
    std::map<std::string, int> seen;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        std::string key = scene.objects[o].name.empty() ? "object" + std::to_string(o) : scene.objects[o].name;
        if (seen[key]++ > 0) key += "#" + std::to_string(o);
        levelMap[key] = levels[o];
    }
    return levelMap;
}

// What the view left out of the search, and why.
nlohmann::json skippedJson(const scenes::Scene& scene, const evaluation::ViewSetup& setup) {
    nlohmann::json skipped = nlohmann::json::object();
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const evaluation::ObjectSetup& object = setup.objects()[o];
        if (object.skip != evaluation::SkipReason::None)
            skipped[scene.objects[o].name] = evaluation::toString(object.skip);
    }
    const evaluation::SkipSummary& skip = setup.skipSummary();
    return {
        {"outside_frustum", skip.outsideFrustum}, {"below_one_pixel", skip.belowOnePixel},    {"hidden", skip.hidden},
        {"merged_levels", skip.mergedLevels},     {"searched_objects", skip.searchedObjects}, {"objects", skipped}};
}

nlohmann::json entropyJson(const metrics::EntropyComponent& c) {
    return {{"computed", c.computed}, {"candidate", c.candidate}, {"reference", c.reference}, {"fidelity", c.fidelity}};
}

}  // namespace

ViewRun runOptimizer(PreparedScene& prepared, int view, const OptimizeOptions& options, const std::string& algorithm,
                     std::uint64_t seed) {
    evaluation::ViewAnswer answer = evaluation::optimizeView(
        prepared.scene, prepared.scene.views[std::size_t(view)], *prepared.renderer, prepared.metrics,
        prepared.estimator, prepared.readFeatures, searchViewSettings(options), searchOptions(options, algorithm, seed));
    const evaluation::ViewSetup& setup = *answer.view.setup;
    const scenes::Scene& scene = prepared.scene;
    const optimizer::Result& result = answer.result;
    const metrics::MetricResult& full = answer.metrics;
    const double searchSeconds = answer.searchSeconds;
    ViewRun run;
    run.json = {
        {"scene", scene.name},
        {"view", setup.camera().name},
        {"algorithm", algorithm},
        {"seeded_from", optimizer::isSwarmAlgorithm(algorithm) ? nlohmann::json(seedAlgorithms(options.seedFrom))
                                                               : nlohmann::json::array()},
        {"seed", seed},
        {"scene_seed", options.sceneSeed},
        {"fill_probability", optimizer::isSwarmAlgorithm(algorithm) ? nlohmann::json(effectiveFillProbability(options))
                                                                    : nlohmann::json(nullptr)},
        {"eval_path", options.evalPath},
        {"levels", levelsByName(scene, answer.levels)},
        {"combination", answer.levels},
        {"fitness", full.fitness},
        {"search_fitness", result.bestScore.fitness},
        {"judge", judgeJson(answer.judge, options.judge.parameters)},
        {"ssim", {{"computed", full.ssimComputed}, {"value", full.ssim}, {"fidelity", full.ssimFidelity}}},
        {"boundary_entropy", entropyJson(full.boundaryEntropy)},
        {"information_entropy", entropyJson(full.informationEntropy)},
        {"precision", full.precision},
        {"recall", full.recall},
        {"predicted_ms", result.predictedMs},
        {"budget_ms", options.budgetMs},
        {"time_model", prepared.timeModelName},
        {"evaluations", result.evaluations},
        {"cache_hits", result.cacheHits},
        {"iterations", result.iterations},
        {"stop_reason", std::string(optimizer::toString(result.stopReason))},
        {"skipped_objects", skippedJson(scene, setup)},
        {"owned_windows", ownedWindowsJson(answer.view.evaluator.get())},
        {"window_groups", windowGroupsJson(answer.view.evaluator.get())},
        {"setup_seconds", answer.setupSeconds},
        {"evals_per_second", searchSeconds > 0.0 ? double(result.evaluations) / searchSeconds : 0.0},
        {"search_seconds", searchSeconds},
        {"wall_seconds", answer.setupSeconds + searchSeconds},
        {"width", setup.width()},
        {"height", setup.height()},
        {"shading", options.shading},
    };
    run.optimizedImage = std::move(answer.image);
    run.setup = std::move(answer.view.setup);
    run.result = std::move(answer.result);
    return run;
}

void printOptimizeSummary(std::ostream& out, const nlohmann::json& result) {
    out << result["scene"].get<std::string>() << " / " << result["view"].get<std::string>() << " — "
        << result["algorithm"].get<std::string>() << ", budget " << result["budget_ms"].get<double>() << " ms\n";
    out << "  levels:";
    for (auto it = result["levels"].begin(); it != result["levels"].end(); ++it) {
        out << " " << it.key() << "=" << it.value().get<int>();
    }
    out << "\n" << std::fixed << std::setprecision(4);
    out << "  fitness " << result["fitness"].get<double>() << " (ssim " << result["ssim"]["fidelity"].get<double>()
        << ", boundary " << result["boundary_entropy"]["fidelity"].get<double>() << ", information "
        << result["information_entropy"]["fidelity"].get<double>() << ")\n";
    if (result.contains("judge") && !result["judge"].is_null()) {
        const nlohmann::json& judge = result["judge"];
        out << "  judge: butteraugli " << judge["pnorm"].get<double>() << "-norm " << judge["butteraugli"].get<double>()
            << ", max " << judge["butteraugli_max"].get<double>() << " (lower is better; not read by the search)\n";
    }
    out << std::setprecision(2) << "  predicted " << result["predicted_ms"].get<double>() << " ms ("
        << result["time_model"].get<std::string>() << "), " << result["evaluations"].get<std::int64_t>()
        << " evaluations, " << result["cache_hits"].get<std::int64_t>() << " cache hits, "
        << result["skipped_objects"]["searched_objects"].get<int>() << " objects searched, "
        << result["wall_seconds"].get<double>() << " s\n";
    if (result.contains("out")) out << "  wrote " << result["out"].get<std::string>() << "/result.json\n";
    out.unsetf(std::ios::floatfield);
}

}  // namespace lodopt::cli
