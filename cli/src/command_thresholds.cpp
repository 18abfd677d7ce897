// lodopt thresholds: per-object screen-size switch thresholds fitted to a sweep's per-view
// optimizer answers (evaluation/engine_thresholds.hpp), written for the engines: thresholds.json
// (each engine's convention) and the scene as <scene>.lod.glb with MSFT_lod and
// MSFT_screencoverage in UnityGLTF's convention (docs/thresholds.md).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "evaluation/engine_thresholds.hpp"
#include "report_data.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "sweep_files.hpp"

namespace lodopt::cli {
namespace {

struct ThresholdsOptions {
    std::string from;
    std::string out = "out/thresholds";
    int holdoutEvery = 4;
    double fovYDegrees = 0.0;  // 0: the sweep's cameras' (which must agree)
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

nlohmann::json objectJson(const scenes::Object& object, const evaluation::ObjectThresholds& r) {
    auto numberOrNull = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    return {{"name", object.name},
            {"levels", r.levelCount},
            {"fitted", r.fitted},
            {"fit_samples", r.fitSamples},
            {"held_out_samples", r.heldOutSamples},
            {"fit_agreement", numberOrNull(r.fitAgreement)},
            {"held_out_agreement", numberOrNull(r.heldOutAgreement)},
            {"screen_size", r.screenSize},
            {"unreal_screen_size", r.unrealScreenSize},
            {"unity_relative_height", r.unityRelativeHeight},
            {"threejs_distance", r.switchDistance},
            {"babylon_distance", r.switchDistance},
            {"babylon_coverage", r.babylonCoverage}};
}

const nlohmann::json& conventions() {
    static const nlohmann::json text = {
        {"rule", "level k is drawn for the first k whose threshold the object reaches; below every threshold the "
                 "coarsest level (never culled)"},
        {"screen_size", "bounding-sphere diameter over the view height (lodopt's own)"},
        {"unreal_screen_size", "Unreal Engine static mesh LOD ScreenSize (views at least as wide as high)"},
        {"unity_relative_height", "Unity LOD.screenRelativeTransitionHeight: bounds' largest extent over the view "
                                  "height; also the values of MSFT_screencoverage in the .lod.glb (UnityGLTF)"},
        {"threejs_distance", "THREE.LOD addLevel(object, distance): level k from this camera distance on, the LOD at "
                             "the bounds' centre, for fov_y_degrees"},
        {"babylon_distance", "Babylon.js addLODLevel(distance) to the bounding sphere's centre, for fov_y_degrees"},
        {"babylon_coverage", "Babylon.js addLODLevel(coverage) with useLODScreenCoverage, for the aspect"}};
    return text;
}

void runThresholds(const ThresholdsOptions& o, const OutputOptions& output) {
    const SweepTable table = readSweepTable(o.from);
    const std::string sceneName = table.settings.value("scene", std::string());
    if (sceneName.empty()) throw UsageError(o.from + ": the sweep names no scene");
    scenes::Scene scene = scenes::loadScene(sceneName, table.settings.value("scene-seed", std::uint32_t(1)));
    if (scene.objects.size() != table.objects.size()) {
        throw UsageError(o.from + ": the sweep has " + std::to_string(table.objects.size()) + " objects, scene '" +
                         sceneName + "' now " + std::to_string(scene.objects.size()));
    }
    int width = 0, height = 0;
    parseSize(table.settings.value("size", std::string("512x512")), width, height);
    evaluation::ThresholdSettings settings;
    settings.fovYDegrees = sweepFov(table, o.fovYDegrees);
    settings.aspect = double(width) / double(height);
    settings.holdoutEvery = o.holdoutEvery;
    std::vector<evaluation::ViewChoices> views;
    for (const SweepTableView& view : table.views) {
        if (!view.feasible) continue;  // all coarsest: nothing was chosen
        views.push_back({view.levels, view.screenSizes, view.searched});
    }
    const std::vector<evaluation::ObjectThresholds> results = evaluation::fitEngineThresholds(scene, views, settings);

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
        {"scene", sceneName},
        {"views", views.size()},
        {"holdout_every", o.holdoutEvery},
        {"fov_y_degrees", settings.fovYDegrees},
        {"aspect", settings.aspect},
        {"objects_with_levels", withLevels},
        {"fitted_objects", fitted},
        {"fit_agreement", fitWeight > 0 ? nlohmann::json(fitAgreement / fitWeight) : nlohmann::json()},
        {"held_out_agreement", heldOutWeight > 0 ? nlohmann::json(heldOutAgreement / heldOutWeight) : nlohmann::json()},
        {"files", {(out / "thresholds.json").string(), glb.string()}}};
    nlohmann::json document = summary;
    document["format"] = "lodopt-thresholds";
    document["version"] = 1;
    document["conventions"] = conventions();
    document["objects"] = objects;
    writeJsonFile((out / "thresholds.json").string(), document);
    if (output.json) return printJson(summary);
    std::cout << "thresholds: " << fitted << " of " << withLevels << " objects with levels fitted on " << views.size()
              << " views of " << sceneName << " (every " << o.holdoutEvery << "th held out); level agreement "
              << jsonNumber(summary, "fit_agreement", NAN) << " fitted, " << jsonNumber(summary, "held_out_agreement", NAN)
              << " held out (weighted by screen size squared)\n";
    for (const auto& file : summary["files"]) std::cout << "wrote " << file.get<std::string>() << "\n";
}

}  // namespace

void addThresholdsCommand(CLI::App& app) {
    auto options = std::make_shared<ThresholdsOptions>();
    auto output = std::make_shared<OutputOptions>();
    CLI::App* command = app.add_subcommand(
        "thresholds", "Fit per-object screen-size LOD switch thresholds to a sweep and write them for engines");
    command->add_option("--from", options->from, "A finished sweep (folder or sweep.json)")->required();
    command->add_option("--out", options->out, "Output folder")->capture_default_str();
    command->add_option("--holdout-every", options->holdoutEvery, "Hold every Nth view out of the fit (0: none)")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    command->add_option("--fov", options->fovYDegrees,
                        "Vertical field of view (degrees) for the distance conventions (default: the sweep's)")
        ->check(CLI::Range(0.01, 179.0));
    addOutputOptions(*command, *output);
    command->callback([options, output] { runThresholds(*options, *output); });
}

}  // namespace lodopt::cli
