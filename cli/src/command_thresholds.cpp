// lodopt thresholds: per-object screen-size switch thresholds fitted to a sweep's per-view
// optimizer answers (evaluation/engine_thresholds.hpp), written for the engines: thresholds.json
// (each engine's convention) and the scene as <scene>.lod.glb with MSFT_lod and
// MSFT_screencoverage in UnityGLTF's convention (docs/thresholds.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "evaluation/engine_thresholds.hpp"
#include "evaluation/level_costs.hpp"
#include "evaluation/switch_rules.hpp"
#include "optimize_run.hpp"
#include "progress.hpp"
#include "report_data.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "schedule_common.hpp"
#include "sweep_files.hpp"
#include "sweep_run.hpp"

namespace lodopt::cli {
namespace {

struct ThresholdsOptions {
    std::string from;
    SweepOptions sweep;  // without --from: the views to sweep first, into <out>/sweep
    std::string out = "out/thresholds";
    int holdoutEvery = 4;
    double fovYDegrees = 0.0;  // 0: the sweep's cameras' (which must agree)
    double hysteresis = evaluation::ThresholdSettings{}.hysteresis;
    double priorSamples = evaluation::ThresholdSettings{}.priorSamples;
    std::string pricing = "measured";  // or "level-error"
    std::string switchPath;            // camera path to count switches on; empty: the scene's first
};

double sweepFov(const SweepTable& table, double given) {
    if (given > 0.0) return given;
    double fov = 0.0;
    for (const SweepTableView& view : table.views) {
        if (fov == 0.0) fov = view.camera.fovYDegrees;
        if (view.camera.fovYDegrees != fov) {
            throw UsageError("--from: the sweep's cameras have different fields of view; give the engine's with --fov");
        }
    }
    return fov > 0.0 ? fov : 45.0;
}

// A figure, or null where it is undefined (no samples, no held-out views).
nlohmann::json numberOrNull(double value) {
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
}

nlohmann::json objectJson(const scenes::Object& object, const evaluation::ObjectThresholds& r) {
    return {{"name", object.name},
            {"levels", r.levelCount},
            {"fitted", r.fitted},
            {"fit_samples", r.fitSamples},
            {"held_out_samples", r.heldOutSamples},
            {"fit_agreement", numberOrNull(r.fitAgreement)},
            {"held_out_agreement", numberOrNull(r.heldOutAgreement)},
            {"fitted_screen_size", r.fittedScreenSize},
            {"screen_size", r.screenSize},
            {"unreal_screen_size", r.unrealScreenSize},
            {"unity_relative_height", r.unityRelativeHeight},
            {"threejs_distance", r.switchDistance},
            {"babylon_distance", r.switchDistance},
            {"babylon_coverage", r.babylonCoverage},
            {"unreal_lod_hysteresis", r.unrealHysteresis}};
}

const nlohmann::json& conventions() {
    static const nlohmann::json text = {
        {"rule",
         "level k is drawn for the first k whose threshold the object reaches; below every threshold the "
         "coarsest level (never culled)"},
        {"fitted_screen_size",
         "the thresholds as fitted, in screen size (bounding-sphere diameter over the view height)"},
        {"screen_size",
         "fitted_screen_size / lod_bias: the global LOD bias that meets the budget is baked into this and "
         "every engine value below, so engines keep theirs at 1 (Unity QualitySettings.lodBias, Unreal "
         "r.StaticMeshLODDistanceScale)"},
        {"unreal_lod_hysteresis",
         "screen size above the threshold an object must reach to go finer again (Unreal "
         "skeletal mesh LODHysteresis; static meshes have none)"},
        {"hysteresis",
         "three.js LOD.addLevel(object, distance, hysteresis): the level goes finer again only closer "
         "than distance x (1 - hysteresis); Unity and Babylon.js have no band"},
        {"unreal_screen_size", "Unreal Engine static mesh LOD ScreenSize (views at least as wide as high)"},
        {"unity_relative_height",
         "Unity LOD.screenRelativeTransitionHeight: bounds' largest extent over the view "
         "height; also the values of MSFT_screencoverage in the .lod.glb (UnityGLTF)"},
        {"threejs_distance",
         "THREE.LOD addLevel(object, distance): level k from this camera distance on, the LOD at "
         "the bounds' centre, for fov_y_degrees"},
        {"babylon_distance", "Babylon.js addLODLevel(distance) to the bounding sphere's centre, for fov_y_degrees"},
        {"babylon_coverage", "Babylon.js addLODLevel(coverage) with useLODScreenCoverage, for the aspect"}};
    return text;
}

// The options the sweep was made with that decide what a view renders, scores and predicts.
OptimizeOptions sweepOptions(const SweepTable& table, const std::string& from) {
    OptimizeOptions options;
    const nlohmann::json& s = table.settings;
    try {
        options.scene = s.at("scene").get<std::string>();
        options.sceneSeed = s.value("scene-seed", std::uint32_t(1));
        options.size = s.value("size", options.size);
        options.shading = s.value("shading", options.shading);
        options.weights = s.value("weights", options.weights);
        options.profile = s.value("profile", std::string());
        options.model = s.value("model", std::string());
        options.budgetMs = s.at("budget-ms").get<double>();
    } catch (const nlohmann::json::exception& error) {
        throw UsageError(from + ": the sweep's settings lack what a view needs (" + error.what() + ")");
    }
    options.view = "0";
    return options;
}

nlohmann::json biasJson(const evaluation::LodBias& bias) {
    return {{"lod_bias", bias.bias},
            {"fitting_mean_predicted_ms", bias.meanPredictedMs},
            {"meets_budget", bias.meetsBudget}};
}

nlohmann::json comparisonJson(const evaluation::RuleComparison& comparison) {
    nlohmann::json rules = nlohmann::json::array();
    for (const evaluation::RuleOutcome& rule : comparison.rules) {
        nlohmann::json row = {{"rule", rule.rule},
                              {"mean_fitness", numberOrNull(rule.meanFitness)},
                              {"gain_fraction", numberOrNull(rule.gainFraction)},
                              {"over_budget_share", numberOrNull(rule.overBudgetShare)},
                              {"mean_predicted_ms", numberOrNull(rule.meanPredictedMs)}};
        row.update(biasJson(rule.bias));
        rules.push_back(row);
    }
    return rules;
}

void fitThresholds(const ThresholdsOptions& o, const OutputOptions& output) {
    const SweepTable table = readSweepTable(o.from);
    OptimizeOptions sweep = sweepOptions(table, o.from);
    PreparedScene prepared = prepareScene(sweep, true);  // the engines' geometric-error rules read it
    scenes::Scene& scene = prepared.scene;
    if (scene.objects.size() != table.objects.size()) {
        throw UsageError(o.from + ": the sweep has " + std::to_string(table.objects.size()) + " objects, scene '" +
                         sweep.scene + "' now " + std::to_string(scene.objects.size()));
    }
    evaluation::ThresholdSettings settings;
    settings.fovYDegrees = sweepFov(table, o.fovYDegrees);
    settings.aspect = double(prepared.settings.width) / double(prepared.settings.height);
    settings.holdoutEvery = o.holdoutEvery;
    settings.hysteresis = o.hysteresis;
    settings.priorSamples = o.priorSamples;
    std::vector<evaluation::ScoredView> views;
    std::vector<evaluation::ViewChoices> choices;
    for (const SweepTableView& view : table.views) {
        if (!view.feasible) continue;  // all coarsest: nothing was chosen
        choices.push_back({view.levels, view.screenSizes, view.searched});
        views.push_back({choices.back(), view.camera, view.fitness});
    }
    if (views.empty()) throw UsageError(o.from + ": no view of the sweep meets its budget: nothing to fit");
    // Each fitting view's level costs (evaluation/level_costs.hpp), unless the cheaper level error is asked for.
    std::vector<evaluation::ViewLevelCosts> costs;
    if (o.pricing == "measured") {
        evaluation::SearchViewSettings viewSettings = searchViewSettings(sweep);
        Progress progress("level costs", views.size(), output.quiet, Progress::Style::Lines);
        for (std::size_t v = 0; v < views.size(); ++v) {
            costs.push_back(evaluation::isHeldOutView(v, o.holdoutEvery)
                                ? evaluation::ViewLevelCosts{}
                                : evaluation::measureLevelCosts(scene, views[v].camera, choices[v], *prepared.renderer,
                                                                prepared.metrics, prepared.estimator,
                                                                prepared.readFeatures, viewSettings));
            progress.update(v + 1, views[v].camera.name);
        }
        progress.finish();
    }
    std::vector<evaluation::ObjectThresholds> results =
        evaluation::fitEngineThresholds(scene, choices, settings, costs);

    // The tuned rule and the engines' defaults, each with its bias, compared on held-out views.
    std::vector<evaluation::SwitchRuleThresholds> rules{{"tuned", {}}};
    for (const evaluation::ObjectThresholds& r : results) rules.front().thresholds.push_back(r.fittedScreenSize);
    for (evaluation::SwitchRuleThresholds& rule : evaluation::defaultSwitchRules(scene, prepared.settings.height)) {
        rules.push_back(std::move(rule));
    }
    evaluation::RuleComparisonSettings compare;
    compare.budgetMs = sweep.budgetMs;
    compare.holdoutEvery = o.holdoutEvery;
    compare.width = prepared.settings.width;
    compare.height = prepared.settings.height;
    const evaluation::RuleComparison comparison = evaluation::compareSwitchRules(
        scene, views, rules, *prepared.renderer, prepared.metrics, prepared.estimator, prepared.readFeatures, compare);
    const evaluation::LodBias tunedBias = comparison.rules.front().bias;
    evaluation::applyLodBias(scene, results, tunedBias.bias, settings);
    // Level switches of the exported rule along a camera path, without and with the band.
    nlohmann::json pathSwitches;
    if (!o.switchPath.empty() || !scene.paths.empty()) {
        const scenes::CameraPath path =
            o.switchPath.empty() ? scene.paths.front() : loadCameraPath(scene, o.switchPath);
        evaluation::ObjectThresholdList exported;
        for (const evaluation::ObjectThresholds& r : results) exported.push_back(r.screenSize);
        const evaluation::RuleSwitches plain = evaluation::countRuleSwitches(scene, exported, path.frames, 0.0);
        const evaluation::RuleSwitches banded =
            evaluation::countRuleSwitches(scene, exported, path.frames, settings.hysteresis);
        auto per1000 = [](const evaluation::RuleSwitches& s) {
            return s.objectFrames > 0 ? 1000.0 * double(s.switches) / double(s.objectFrames) : 0.0;
        };
        pathSwitches = {{"path", path.name},
                        {"frames", path.frames.size()},
                        {"switches_without_hysteresis", plain.switches},
                        {"switches_with_hysteresis", banded.switches},
                        {"per_1000_object_frames_without", per1000(plain)},
                        {"per_1000_object_frames_with", per1000(banded)}};
    }
    if (!tunedBias.meetsBudget) {
        std::cerr << "lodopt: warning: even the coarsest levels the views need are predicted over the budget on "
                     "average ("
                  << tunedBias.meanPredictedMs << " ms > " << sweep.budgetMs << " ms)\n";
    }

    nlohmann::json objects = nlohmann::json::array();
    int withLevels = 0, fitted = 0;
    double fitAgreement = 0.0, heldOutAgreement = 0.0;
    int fitWeight = 0, heldOutWeight = 0;
    for (const evaluation::ObjectThresholds& r : results) {
        scenes::Object& object = scene.objects[std::size_t(r.object)];
        objects.push_back(objectJson(object, r));
        if (r.levelCount < 2) continue;
        ++withLevels;
        fitted += r.fitted ? 1 : 0;
        if (std::isfinite(r.fitAgreement)) fitAgreement += r.fitAgreement * r.fitSamples, fitWeight += r.fitSamples;
        if (std::isfinite(r.heldOutAgreement)) {
            heldOutAgreement += r.heldOutAgreement * r.heldOutSamples;
            heldOutWeight += r.heldOutSamples;
        }
        for (std::size_t k = 0; k < object.levels.size(); ++k) {
            object.levels[k].screenCoverage = k < r.screenSize.size() ? float(r.screenSize[k]) : 0.0f;
        }
    }
    const std::filesystem::path out(o.out);
    std::filesystem::create_directories(out);
    const std::filesystem::path glb = out / (scene.name + ".lod.glb");
    scenes::GltfExportOptions exportOptions;
    exportOptions.coverage = scenes::CoverageConvention::UnityRelativeHeight;
    scenes::exportGltf(scene, glb.string(), exportOptions);
    nlohmann::json summary = {
        {"from", o.from},
        {"scene", sweep.scene},
        {"budget_ms", sweep.budgetMs},
        {"views", views.size()},
        {"fitting_views", comparison.fittingViews},
        {"held_out_views", comparison.heldOutViews},
        {"holdout_every", o.holdoutEvery},
        {"fov_y_degrees", settings.fovYDegrees},
        {"aspect", settings.aspect},
        {"objects_with_levels", withLevels},
        {"fitted_objects", fitted},
        {"fit_agreement", fitWeight > 0 ? nlohmann::json(fitAgreement / fitWeight) : nlohmann::json()},
        {"held_out_agreement", heldOutWeight > 0 ? nlohmann::json(heldOutAgreement / heldOutWeight) : nlohmann::json()},
        {"lod_bias", biasJson(tunedBias)},
        {"hysteresis", settings.hysteresis},
        {"prior_samples", settings.priorSamples},
        {"pricing", o.pricing},
        {"path_switches", pathSwitches},
        {"held_out", comparisonJson(comparison)},
        {"held_out_reference",
         {{"gain_views", comparison.gainViews},
          {"optimizer_mean_fitness", numberOrNull(comparison.optimizerMeanFitness)},
          {"coarsest_mean_fitness", numberOrNull(comparison.coarsestMeanFitness)}}},
        {"files", {(out / "thresholds.json").string(), glb.string()}}};
    nlohmann::json document = summary;
    document["format"] = "lodopt-thresholds";
    document["version"] = 2;
    document["conventions"] = conventions();
    document["objects"] = objects;
    writeJsonFile((out / "thresholds.json").string(), document);
    if (output.json) return printJson(summary);
    std::cout << "thresholds: " << fitted << " of " << withLevels << " objects with levels fitted on "
              << comparison.fittingViews << " views of " << sweep.scene << " (" << comparison.heldOutViews
              << " held out); level agreement " << jsonNumber(summary, "fit_agreement", NAN) << " fitted, "
              << jsonNumber(summary, "held_out_agreement", NAN) << " held out (weighted by screen size squared)\n";
    std::cout << "LOD bias " << tunedBias.bias << " (mean predicted " << tunedBias.meanPredictedMs
              << " ms on the fitting views, budget " << sweep.budgetMs << " ms), baked into the thresholds; hysteresis "
              << settings.hysteresis << " of the switch distance\n";
    if (comparison.heldOutViews > 0) {
        std::cout << "held out (" << comparison.heldOutViews << " views; optimizer mean fitness "
                  << comparison.optimizerMeanFitness << ", all coarsest " << comparison.coarsestMeanFitness << "):\n";
        std::printf("%-18s %9s %12s %13s %12s %11s\n", "rule", "lod bias", "mean fitness", "gain fraction",
                    "over budget", "mean ms");
        for (const evaluation::RuleOutcome& rule : comparison.rules) {
            std::printf("%-18s %9.4g %12.6f %13.3f %12.3f %11.3f\n", rule.rule.c_str(), rule.bias.bias,
                        rule.meanFitness, rule.gainFraction, rule.overBudgetShare, rule.meanPredictedMs);
        }
    }
    if (!pathSwitches.is_null()) {
        std::cout << "along path " << pathSwitches["path"].get<std::string>() << " ("
                  << pathSwitches["frames"].get<std::size_t>()
                  << " frames): " << pathSwitches["switches_without_hysteresis"].get<long long>()
                  << " level switches without hysteresis, " << pathSwitches["switches_with_hysteresis"].get<long long>()
                  << " with " << settings.hysteresis << "\n";
    }
    for (const auto& file : summary["files"]) std::cout << "wrote " << file.get<std::string>() << "\n";
}

// Without --from: sweep the given views into <out>/sweep first (resumed when it is there already,
// so a second run with other fitting options reuses the views), then fit on it.
void runThresholds(ThresholdsOptions o, const OutputOptions& output) {
    const bool sweeps = !o.sweep.optimize.scene.empty();
    if (sweeps == !o.from.empty()) {
        throw UsageError(
            "thresholds: give --from SWEEP, or --scene S with the views to sweep (--view-count, --path, "
            "--grid or --cameras) and --budget-ms");
    }
    if (sweeps) {
        if (!(o.sweep.optimize.budgetMs > 0.0)) throw UsageError("thresholds --scene: --budget-ms is required");
        o.sweep.out = (std::filesystem::path(o.out) / "sweep").string();
        o.sweep.resume = true;
        o.sweep.printSummary = false;
        runSweepCommand(o.sweep, output);
        o.from = o.sweep.out;
    }
    fitThresholds(o, output);
}

}  // namespace

void addThresholdsCommand(CLI::App& app) {
    auto options = std::make_shared<ThresholdsOptions>();
    auto output = std::make_shared<OutputOptions>();
    CLI::App* command = app.add_subcommand(
        "thresholds", "Fit per-object screen-size LOD switch thresholds to a sweep and write them for engines");
    options->sweep.optimize.scene.clear();                 // no sweep unless --scene is given
    options->sweep.optimize.seedFrom = "screensize,mckp";  // as sweep
    command->add_option("--from", options->from, "A finished sweep (folder or sweep.json)");
    auto* scene =
        command->add_option("--scene", options->sweep.optimize.scene,
                            "Without --from: sweep this scene first (into <out>/sweep), with the views below");
    addSweepSources(*command, options->sweep);
    scene->excludes(command->get_option("--from"));
    command->add_option("--out", options->out, "Output folder")->capture_default_str();
    command->add_option("--holdout-every", options->holdoutEvery, "Hold every Nth view out of the fit (0: none)")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    command
        ->add_option("--fov", options->fovYDegrees,
                     "Vertical field of view (degrees) for the distance conventions (default: the sweep's)")
        ->check(CLI::Range(0.01, 179.0));
    command
        ->add_option("--prior-samples", options->priorSamples,
                     "Weight of the rule shared by objects with as many levels in each object's fit, in the object's "
                     "own samples (0: each object alone)")
        ->check(CLI::Range(0.0, 1e6))
        ->capture_default_str();
    command
        ->add_option("--pricing", options->pricing,
                     "What a disagreement with the optimizer costs in the fit: measured (each level's fitness and "
                     "time at each fitting view) or level-error (levels off, weighted by screen size squared)")
        ->check(CLI::IsMember({"measured", "level-error"}))
        ->capture_default_str();
    command->add_option("--switch-path", options->switchPath,
                        "Count the exported rule's level switches along this camera path (name or JSON file; "
                        "default: the scene's first path, if it has one)");
    command
        ->add_option("--hysteresis", options->hysteresis,
                     "Switch band as a fraction of the switch distance, for engines that have one")
        ->check(CLI::Range(0.0, 0.9))
        ->capture_default_str();
    addOutputOptions(*command, *output);
    command->callback([options, output] { runThresholds(*options, *output); });
}

}  // namespace lodopt::cli
