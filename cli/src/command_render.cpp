// lodopt render: one combination from one view, to PNG, JPEG or PPM (and optionally depth EXR
// or PFM), timed.
#include <iostream>

#include "cli_common.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/timing.hpp"

namespace lodopt::cli {

void addRenderCommand(CLI::App& app) {
    struct Options {
        std::string scene = scenes::kDefaultSceneName;
        std::string view = "0";
        std::string levels;
        std::string size = "512x512";
        std::string shading = renderer::shadingName(renderer::kDefaultShading);
        std::string out = "render.png";
        std::string depthOut;
        std::uint32_t seed = 1;
        bool time = false;
        int repeats = 7;
        BackendOptions backend;
        OutputOptions output;
    };
    auto options = std::make_shared<Options>();
    CLI::App* command = app.add_subcommand("render", "Render one LOD combination headless (OSMesa or EGL)");
    addSceneOption(*command, options->scene);
    addViewOption(*command, options->view, "View name or index");
    command->add_option("--levels", options->levels,
                        "One level per object, comma-separated (-1 = not drawn); default all 0 (the reference)");
    addSizeOption(*command, options->size, "WIDTHxHEIGHT");
    addShadingOption(*command, options->shading);
    addBackendOptions(*command, options->backend);
    command->add_option("--out", options->out, "Color image: .png, .jpg or .ppm")->capture_default_str();
    command->add_option("--depth-out", options->depthOut, "Also write depth as floats: .exr or .pfm");
    addSceneSeedOption(*command, options->seed);
    command->add_flag("--time", options->time, "Also time the frame: the median of --repeats draws after 2 untimed ones, on the frame clock (what every device profile predicts)");
    command->add_option("--repeats", options->repeats, "Timed repeats for --time")->check(CLI::Range(1, 1000));
    addOutputOptions(*command, options->output);
    command->callback([options] {
        // Output types first: nothing is rendered or written for an unsupported one.
        if (std::string error = renderer::colorImageTypeError(options->out); !error.empty()) throw UsageError(error);
        if (!options->depthOut.empty()) {
            if (std::string error = renderer::depthImageTypeError(options->depthOut); !error.empty()) {
                throw UsageError(error);
            }
        }
        renderer::RenderSettings settings;
        parseSize(options->size, settings.width, settings.height);
        settings.shading = renderer::parseShading(options->shading);
        options->backend.applyTo(settings);
        scenes::Scene scene = scenes::loadScene(options->scene, options->seed);
        const int view = scenes::findView(scene, options->view);
        scenes::Combination combination = scenes::referenceCombination(scene);
        if (!options->levels.empty()) {
            combination = parseIntList(options->levels, "--levels");
            scenes::validateCombination(scene, combination);
        }
        renderer::Renderer renderer(scene, settings);
        renderer::Frame frame = renderer.render(combination, scene.views[view]);
        renderer::writeColorImage(options->out, frame);
        if (!options->depthOut.empty()) renderer::writeDepthImage(options->depthOut, frame);
        renderer::FrameTimes times;
        if (options->time) times = renderer.timeFrames(combination, scene.views[view], options->repeats, 2);
        if (options->output.json) {
            nlohmann::json result = {{"scene", scene.name},
                                     {"view", scene.views[view].name},
                                     {"levels", combination},
                                     {"width", settings.width},
                                     {"height", settings.height},
                                     {"shading", options->shading},
                                     {"out", options->out},
                                     {"renderer", renderer.glRendererString()},
                                     {"gl_version", renderer.glVersionString()},
                                     {"backend", options->backend.backend},
                                     {"platform", renderer.platformDescription()}};
            if (!options->depthOut.empty()) result["depth_out"] = options->depthOut;
            if (options->time) {
                const auto medianOf = [](const std::vector<double>& draws) -> nlohmann::json {
                    if (draws.empty()) return nullptr;  // no timer queries
                    return timemodel::median(draws);
                };
                result["render_ms"] = times.median();
                result["timing"] = {{"frame_clock", renderer::frameClockName(times.clock)},
                                    {"draws", options->repeats},
                                    {"warmup", 2},
                                    {"wall_ms", medianOf(times.wallMs)},
                                    {"gpu_ms", medianOf(times.gpuMs)},
                                    {"cpu_ms", medianOf(times.cpuMs)}};
            }
            printJson(result);
        } else {
            std::cout << "wrote " << options->out;
            if (!options->depthOut.empty()) std::cout << " and " << options->depthOut;
            std::cout << " (" << scene.name << ", view '" << scene.views[view].name << "', " << settings.width << "x"
                      << settings.height << ")\n";
            if (options->time) {
                std::cout << "render_ms " << times.median() << " (median of " << options->repeats << " draws, "
                          << renderer::frameClockName(times.clock) << " clock)\n";
            }
        }
    });
}

}  // namespace lodopt::cli
