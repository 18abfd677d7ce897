// lodopt estimate: the predicted render time of one combination from one view, from a device
// profile (or the profile shipped for the built-in scenes), to check against `render --time`.
#include <iostream>
#include <optional>
#include <stdexcept>

#include "cli_common.hpp"
#include "evaluation/device_timing.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/features.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::cli {
namespace {

struct EstimateOptions {
    std::string profile;  // empty = shipped
    std::string scene = scenes::kDefaultSceneName;
    std::string view = "0";
    std::string levels;
    std::string model;  // empty = the profile's default
    std::string size;   // empty = the profile's
    std::string shading;  // empty = the profile's
    BackendOptions backend;  // the context whose GL renderer and frame clock are compared with the profile's
    std::uint32_t seed = 1;
    bool noRendererCheck = false;
    bool speedProbe = false;
    OutputOptions output;
};

// The current OpenGL renderer string and frame clock, from a context on an empty scene (no
// upload); both empty when no context opens.
struct CurrentRenderer {
    std::string glRenderer, frameClock;
};
CurrentRenderer currentRenderer(const BackendOptions& backend, std::vector<std::string>& warnings) {
    try {
        static const scenes::Scene empty;
        renderer::RenderSettings settings;
        settings.width = settings.height = 1;
        backend.applyTo(settings);
        const renderer::Renderer context(empty, settings);
        return {context.glRendererString(), renderer::frameClockName(context.frameClock())};
    } catch (const std::exception& error) {
        warnings.push_back(std::string("could not open a renderer to compare with the profile: ") + error.what());
        return {};
    }
}

void runEstimate(const EstimateOptions& options) {
    timemodel::DeviceProfile profile;
    std::string source;
    std::vector<std::string> warnings;
    const scenes::Scene scene = scenes::loadScene(options.scene, options.seed);
    try {
        if (options.profile.empty()) {
            bool exact = false;
            profile = timemodel::shippedProfile(scene.name, &exact);
            source = "shipped:" + profile.scene;
        } else {
            profile = timemodel::loadProfile(options.profile);
            source = options.profile;
        }
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }
    std::unique_ptr<timemodel::TimeModel> model;
    try {
        model = timemodel::modelFromProfile(profile, options.model);
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }

    int width = profile.width, height = profile.height;
    if (!options.size.empty()) parseSize(options.size, width, height);
    const std::string shading = options.shading.empty() ? profile.shading : options.shading;
    const int view = scenes::findView(scene, options.view);
    scenes::Combination combination = scenes::referenceCombination(scene);
    if (!options.levels.empty()) {
        combination = parseIntList(options.levels, "--levels");
        scenes::validateCombination(scene, combination);
    }

    if (profile.scene != scene.name) {
        warnings.push_back("the profile was calibrated on scene '" + profile.scene + "', not '" + scene.name + "'");
    }
    const CurrentRenderer current = options.noRendererCheck ? CurrentRenderer{} : currentRenderer(options.backend, warnings);
    for (const std::string& w : timemodel::profileWarnings(profile, current.glRenderer, width, height,
                                                           timemodel::describeMachine(), shading, current.frameClock)) {
        warnings.push_back(w);
    }

    const timemodel::FrameFeatures features =
        timemodel::computeFrameFeatures(scene, combination, scene.views[view], width, height);
    const double modelMs = model->estimateMs(features);
    std::optional<evaluation::SpeedProbe> probe;
    if (options.speedProbe) {
        renderer::RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.shading = renderer::parseShading(shading);
        options.backend.applyTo(settings);
        try {
            probe = evaluation::probeSpeed(scene, profile, settings);
        } catch (const std::invalid_argument& error) {
            throw UsageError(std::string("--speed-probe: ") + error.what());
        }
    }
    const double predictedMs = probe ? modelMs * probe->ratio : modelMs;

    for (const std::string& w : warnings) std::cerr << "lodopt: warning: " << source << ": " << w << "\n";
    if (options.output.json) {
        nlohmann::json featureJson = nlohmann::json::object();
        for (timemodel::Feature f : timemodel::allFeatures()) featureJson[timemodel::featureName(f)] = features[f];
        printJson({{"scene", scene.name},
                   {"view", scene.views[view].name},
                   {"levels", combination},
                   {"width", width},
                   {"height", height},
                   {"shading", shading},
                   {"model", model->name()},
                   {"profile", source},
                   {"predicted_ms", predictedMs},
                   {"model_ms", modelMs},
                   {"speed_probe", probe ? nlohmann::json{{"view", probe->view},
                                                          {"anchor_ms", probe->anchorMs},
                                                          {"probe_ms", probe->probeMs},
                                                          {"ratio", probe->ratio}}
                                         : nlohmann::json(nullptr)},
                   {"features", featureJson},
                   {"warnings", warnings}});
        return;
    }
    std::cout << "predicted_ms " << predictedMs << " (" << model->name() << " model, " << source << "; " << scene.name
              << ", view '" << scene.views[view].name << "', " << width << "x" << height << ", " << shading << ")\n";
    if (probe) {
        std::cout << "speed probe: view '" << probe->view << "' at the finest levels took " << probe->probeMs
                  << " ms now, " << probe->anchorMs << " ms in the calibration: the model's " << modelMs << " ms x "
                  << probe->ratio << "\n";
    }
}

}  // namespace

void addEstimateCommand(CLI::App& app) {
    auto options = std::make_shared<EstimateOptions>();
    CLI::App* command = app.add_subcommand("estimate", "Predict the render time of one LOD combination");
    addSceneOption(*command, options->scene);
    addViewOption(*command, options->view, "View name or index");
    command->add_option("--levels", options->levels,
                        "One level per object, comma-separated (-1 = not drawn); default all 0 (the reference)");
    addProfileOptions(*command, options->profile, options->model);
    command->add_option("--size", options->size, "Render size WIDTHxHEIGHT (default: the profile's)");
    command
        ->add_option("--shading", options->shading,
                     "lambert or pbr: how the frame is drawn (default: as the profile was measured)")
        ->check(CLI::IsMember({"lambert", "pbr"}));
    addBackendOptions(*command, options->backend);
    addSceneSeedOption(*command, options->seed);
    command->add_flag("--no-renderer-check", options->noRendererCheck,
                      "Do not open an OpenGL context to compare the renderer with the profile's");
    command->add_flag("--speed-probe", options->speedProbe,
                      "Time the profile's speed anchor now and scale the prediction by how much faster or slower "
                      "the machine draws than during the calibration");
    addOutputOptions(*command, options->output);
    command->callback([options] { runEstimate(*options); });
}

}  // namespace lodopt::cli
