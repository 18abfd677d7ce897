#include "optimize_run.hpp"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <map>

#include "cli_common.hpp"
#include "optimizer/baselines.hpp"
#include "optimizer/gapso.hpp"
#include "scenes/builtin.hpp"
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

PreparedScene prepareScene(const OptimizeOptions& options) {
    PreparedScene prepared;
    parseSize(options.size, prepared.settings.width, prepared.settings.height);
    prepared.settings.shading = renderer::parseShading(options.shading);
    parseWeights(options.weights, prepared.metrics);
    prepared.scene = scenes::loadScene(options.scene, options.sceneSeed);
    if (options.view == "all") {
        for (std::size_t v = 0; v < prepared.scene.views.size(); ++v) prepared.views.push_back(int(v));
    } else {
        prepared.views.push_back(scenes::findView(prepared.scene, options.view));
    }
    if (prepared.scene.objects.empty()) throw UsageError("scene '" + prepared.scene.name + "' has no objects");
    prepared.renderer = std::make_unique<renderer::Renderer>(prepared.scene, prepared.settings);
    TimeEstimator estimator = loadTimeEstimator(options.profile, options.model, prepared.scene.name, prepared.settings,
                                                prepared.renderer->glRendererString(), std::cerr);
    prepared.estimator = estimator.estimate;
    prepared.readFeatures = estimator.model->readFeatures();
    prepared.timeModelName = estimator.name;
    return prepared;
}

ViewContext prepareView(PreparedScene& prepared, int view, const OptimizeOptions& options) {
    ViewContext context;
    const scenes::Camera& camera = prepared.scene.views[view];
    context.setup = std::make_unique<evaluation::ViewSetup>(prepared.scene, camera, *prepared.renderer);
    // The search scores fitness only; the answer's precision/recall come from runOptimizer's
    // full render with prepared.metrics.
    const metrics::MetricParameters search = evaluation::searchParameters(prepared.metrics);
    if (options.evalPath == "full") {
        context.evaluator = std::make_unique<evaluation::FullRenderEvaluator>(*context.setup, *prepared.renderer, search);
    } else {
        context.evaluator = std::make_unique<evaluation::LayerEvaluator>(
            *context.setup, search, options.threads, evaluation::DirtyRegions::ChangedPixels, options.evalStates);
    }
    context.cost =
        std::make_unique<evaluation::TimeModelCost>(*context.setup, prepared.estimator, prepared.readFeatures);
    context.problem.levelCounts = context.setup->levelCounts();
    context.problem.evaluator = context.evaluator.get();
    context.problem.cost = context.cost.get();
    context.problem.budgetMs = options.budgetMs;
    if (!context.problem.levelCounts.empty()) {
        context.problem.hints = evaluation::computeHints(*context.setup);
        // Measured once per view and shared by every algorithm: the mckp baseline's objective
        // and the repair rule's "fitness lost per millisecond saved".
        optimizer::CheckedEvaluator checked(context.problem);
        context.problem.surrogateLoss = optimizer::measureSurrogateLoss(context.problem, checked);
    }
    return context;
}

namespace {

optimizer::Termination terminationOf(const OptimizeOptions& options) {
    if (options.paper) return optimizer::Termination::paper();
    optimizer::Termination termination;
    termination.maxIterations = options.maxIterations;
    termination.stableIterations = options.stableIterations;
    termination.maxEvaluations = options.maxEvaluations;
    termination.maxSeconds = options.maxSeconds;
    return termination;
}

}  // namespace

bool isSwarmAlgorithm(const std::string& algorithm) {
    return algorithm == "gapso" || algorithm == "pso" || algorithm == "ga";
}

double effectiveFillProbability(const OptimizeOptions& options) {
    if (options.fillProbability >= 0.0) return options.fillProbability;
    return options.paper ? optimizer::GapsoParameters::paper().fillProbability
                         : optimizer::GapsoParameters{}.fillProbability;
}

std::vector<std::string> seedAlgorithms(const std::string& seedFrom) {
    std::vector<std::string> names;
    if (seedFrom.empty() || seedFrom == "none") return names;
    std::size_t start = 0;
    while (start <= seedFrom.size()) {
        const std::size_t comma = std::min(seedFrom.find(',', start), seedFrom.size());
        const std::string name = seedFrom.substr(start, comma - start);
        if (name != "mckp" && name != "greedy" && name != "screensize") {
            throw UsageError("--seed-from: '" + name + "' is not mckp, greedy or screensize (or none)");
        }
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
        start = comma + 1;
    }
    return names;
}

optimizer::Result runAlgorithm(const ViewContext& context, const OptimizeOptions& options,
                               const std::string& algorithm, std::uint64_t seed) {
    const optimizer::Problem& problem = context.problem;
    if (problem.levelCounts.empty()) {
        // Every object was skipped: the only combination is the fixed one.
        optimizer::Result result;
        result.algorithm = algorithm;
        result.predictedMs = problem.cost->predictMs({});
        if (result.predictedMs > problem.budgetMs) throw optimizer::BudgetError(problem.budgetMs, result.predictedMs);
        result.bestScore = problem.evaluator->evaluate({});
        result.evaluations = 1;
        result.log.push_back({0, result.bestScore.fitness, result.bestScore.fitness, result.predictedMs, 1, 0, 0.0});
        return result;
    }
    const optimizer::Termination termination = terminationOf(options);
    const bool swarm = isSwarmAlgorithm(algorithm);
    const std::vector<std::string> seeds = seedAlgorithms(options.seedFrom);
    if (!swarm || (!options.paper && options.particles == 0 && options.fillProbability < 0.0 && seeds.empty())) {
        return optimizer::makeAlgorithm(algorithm, seed)->run(problem, termination);
    }
    optimizer::GapsoParameters parameters =
        options.paper ? optimizer::GapsoParameters::paper(seed) : optimizer::GapsoParameters{};
    parameters.seed = seed;
    parameters.pso = algorithm != "ga";
    parameters.ga = algorithm != "pso";
    if (options.particles > 0) parameters.particles = options.particles;
    parameters.fillProbability = effectiveFillProbability(options);
    optimizer::Result result;
    std::int64_t seedEvaluations = 0;
    for (const std::string& name : seeds) {
        optimizer::Result start = optimizer::makeAlgorithm(name, seed)->run(problem, optimizer::Termination{});
        seedEvaluations += start.evaluations;
        const auto& starts = parameters.initialCombinations;
        const bool known = std::find(starts.begin(), starts.end(), start.best) != starts.end();
        if (!known && int(starts.size()) < parameters.particles) parameters.initialCombinations.push_back(start.best);
    }
    result = optimizer::Gapso(parameters).run(problem, termination);
    result.evaluations += seedEvaluations;
    return result;
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

}  // namespace

ViewRun runOptimizer(PreparedScene& prepared, int view, const OptimizeOptions& options,
                     const std::string& algorithm, std::uint64_t seed) {
    const auto start = std::chrono::steady_clock::now();
    ViewContext context = prepareView(prepared, view, options);
    const double setupSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto searchStart = std::chrono::steady_clock::now();
    optimizer::Result result = runAlgorithm(context, options, algorithm, seed);
    const double searchSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - searchStart).count();

    const evaluation::ViewSetup& setup = *context.setup;
    const scenes::Scene& scene = prepared.scene;
    const scenes::Combination levels = setup.toScene(result.best);

    // Full metrics (raw entropies too) of the answer, and its image, through a full render so
    // the reported figures never rest on the layer approximation alone.
    evaluation::FullRenderEvaluator full(setup, *prepared.renderer, prepared.metrics);
    const metrics::MetricResult answer = full.metricsOf(result.best);
    ViewRun run;
    run.optimizedImage = prepared.renderer->render(levels, setup.camera());

    nlohmann::json levelMap = nlohmann::json::object();
    std::map<std::string, int> seen;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        std::string key = scene.objects[o].name.empty() ? "object" + std::to_string(o) : scene.objects[o].name;
        if (seen[key]++ > 0) key += "#" + std::to_string(o);
        levelMap[key] = levels[o];
    }
    nlohmann::json skipped = nlohmann::json::object();
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const evaluation::ObjectSetup& object = setup.objects()[o];
        if (object.skip != evaluation::SkipReason::None) skipped[scene.objects[o].name] = evaluation::toString(object.skip);
    }
    const evaluation::SkipSummary& skip = setup.skipSummary();
    auto entropyJson = [](const metrics::EntropyComponent& c) {
        return nlohmann::json{{"computed", c.computed},
                              {"candidate", c.candidate},
                              {"reference", c.reference},
                              {"fidelity", c.fidelity}};
    };
    run.json = {
        {"scene", scene.name},
        {"view", setup.camera().name},
        {"algorithm", algorithm},
        {"seeded_from",
         isSwarmAlgorithm(algorithm) ? nlohmann::json(seedAlgorithms(options.seedFrom)) : nlohmann::json::array()},
        {"seed", seed},
        {"scene_seed", options.sceneSeed},
        {"fill_probability",
         isSwarmAlgorithm(algorithm) ? nlohmann::json(effectiveFillProbability(options)) : nlohmann::json(nullptr)},
        {"eval_path", options.evalPath},
        {"levels", levelMap},
        {"combination", levels},
        {"fitness", answer.fitness},
        {"search_fitness", result.bestScore.fitness},
        {"ssim", {{"computed", answer.ssimComputed}, {"value", answer.ssim}, {"fidelity", answer.ssimFidelity}}},
        {"boundary_entropy", entropyJson(answer.boundaryEntropy)},
        {"information_entropy", entropyJson(answer.informationEntropy)},
        {"precision", answer.precision},
        {"recall", answer.recall},
        {"predicted_ms", result.predictedMs},
        {"budget_ms", options.budgetMs},
        {"time_model", prepared.timeModelName},
        {"evaluations", result.evaluations},
        {"cache_hits", result.cacheHits},
        {"iterations", result.iterations},
        {"stop_reason", std::string(optimizer::toString(result.stopReason))},
        {"skipped_objects",
         {{"outside_frustum", skip.outsideFrustum},
          {"below_one_pixel", skip.belowOnePixel},
          {"hidden", skip.hidden},
          {"merged_levels", skip.mergedLevels},
          {"searched_objects", skip.searchedObjects},
          {"objects", skipped}}},
        {"owned_windows", ownedWindowsJson(context.evaluator.get())},
        {"window_groups", windowGroupsJson(context.evaluator.get())},
        {"setup_seconds", setupSeconds},
        {"evals_per_second", searchSeconds > 0.0 ? double(result.evaluations) / searchSeconds : 0.0},
        {"search_seconds", searchSeconds},
        {"wall_seconds", setupSeconds + searchSeconds},
        {"width", setup.width()},
        {"height", setup.height()},
        {"shading", options.shading},
    };
    run.setup = std::move(context.setup);
    run.result = std::move(result);
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
    out << std::setprecision(2) << "  predicted " << result["predicted_ms"].get<double>() << " ms ("
        << result["time_model"].get<std::string>() << "), " << result["evaluations"].get<std::int64_t>()
        << " evaluations, " << result["cache_hits"].get<std::int64_t>() << " cache hits, "
        << result["skipped_objects"]["searched_objects"].get<int>() << " objects searched, "
        << result["wall_seconds"].get<double>() << " s\n";
    if (result.contains("out")) out << "  wrote " << result["out"].get<std::string>() << "/result.json\n";
    out.unsetf(std::ios::floatfield);
}

}  // namespace lodopt::cli
