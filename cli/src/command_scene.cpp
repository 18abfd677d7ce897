// lodopt scene info|export: what a scene holds, and writing it back as glTF.
#include <iomanip>
#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "scenes/builtin.hpp"
#include "scenes/geometric_error.hpp"
#include "scenes/gltf_io.hpp"

namespace lodopt::cli {
namespace {

nlohmann::json vec3Json(const glm::vec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

// A deviation in world units, four significant digits.
std::string formatDeviation(float deviation) {
    std::ostringstream text;
    text << std::setprecision(4) << deviation;
    return text.str();
}

nlohmann::json sceneInfoJson(const scenes::Scene& scene) {
    nlohmann::json objects = nlohmann::json::array();
    for (const scenes::Object& object : scene.objects) {
        nlohmann::json levels = nlohmann::json::array();
        for (const scenes::Level& level : object.levels) {
            const scenes::LevelStats& stats = level.stats;
            nlohmann::json entry = {
                {"vertices", stats.vertices},
                {"triangles", stats.triangles},
                {"texture_bytes", stats.textureBytes},
                {"draw_calls", stats.drawCalls},
                {"bounds_min", vec3Json(stats.bounds.min)},
                {"bounds_max", vec3Json(stats.bounds.max)},
                {"sphere_center", vec3Json(stats.bounds.sphereCenter)},
                {"sphere_radius", stats.bounds.sphereRadius},
                {"simplification_error", level.simplificationError},
                {"geometric_error", level.geometricError ? nlohmann::json(*level.geometricError) : nlohmann::json()},
            };
            entry["screen_coverage"] = level.screenCoverage ? nlohmann::json(*level.screenCoverage) : nlohmann::json();
            levels.push_back(entry);
        }
        objects.push_back({{"name", object.name}, {"levels", levels}});
    }
    nlohmann::json views = nlohmann::json::array();
    for (const scenes::Camera& camera : scene.views) {
        views.push_back({{"name", camera.name},
                         {"position", vec3Json(camera.position)},
                         {"target", vec3Json(camera.target)},
                         {"up", vec3Json(camera.up)},
                         {"fov_y_degrees", camera.fovYDegrees},
                         {"near", camera.nearPlane},
                         {"far", camera.farPlane}});
    }
    nlohmann::json paths = nlohmann::json::array();
    for (const scenes::CameraPath& path : scene.paths) {
        paths.push_back({{"name", path.name}, {"frames", path.frames.size()}, {"fps", path.framesPerSecond}});
    }
    return {{"scene", scene.name},
            {"objects", objects},
            {"views", views},
            {"paths", paths},
            {"materials", scene.materials.size()},
            {"textures", scene.textures.size()}};
}

void printSceneInfo(const scenes::Scene& scene) {
    std::cout << "scene '" << scene.name << "': " << scene.objects.size() << " objects, " << scene.materials.size()
              << " materials, " << scene.textures.size() << " textures, " << scene.views.size() << " views, "
              << scene.paths.size() << " camera paths\n";
    const std::size_t maxRows = 40;
    for (std::size_t o = 0; o < scene.objects.size() && o < maxRows; ++o) {
        const scenes::Object& object = scene.objects[o];
        std::cout << "  " << object.name << " (" << object.levels.size() << " levels)\n";
        std::cout << "    level  vertices  triangles  texture_bytes  draw_calls  deviation  coverage\n";
        for (std::size_t l = 0; l < object.levels.size(); ++l) {
            const scenes::Level& level = object.levels[l];
            std::cout << "    " << std::setw(5) << l << std::setw(10) << level.stats.vertices << std::setw(11)
                      << level.stats.triangles << std::setw(15) << level.stats.textureBytes << std::setw(12)
                      << level.stats.drawCalls << std::setw(11)
                      << (level.geometricError ? formatDeviation(*level.geometricError) : std::string("-")) << "  "
                      << (level.screenCoverage ? std::to_string(*level.screenCoverage) : std::string("-")) << "\n";
        }
    }
    if (scene.objects.size() > maxRows) {
        std::cout << "  ... " << scene.objects.size() - maxRows << " more objects (use --json for all)\n";
    }
    std::cout << "views:";
    for (std::size_t v = 0; v < scene.views.size(); ++v) std::cout << " " << v << ":" << scene.views[v].name;
    std::cout << "\n";
}

}  // namespace

nlohmann::json sceneInfo(const scenes::Scene& scene) {
    return sceneInfoJson(scene);
}

void addSceneCommand(CLI::App& app) {
    CLI::App* scene = app.add_subcommand("scene", "Inspect or export a scene (built-in name or .gltf/.glb)");
    scene->require_subcommand(1);

    struct InfoOptions {
        std::string scene;
        std::uint32_t seed = 1;
        OutputOptions output;
    };
    auto info = std::make_shared<InfoOptions>();
    CLI::App* infoCommand = scene->add_subcommand("info", "Objects, levels and per-level statistics");
    addSceneOption(*infoCommand, info->scene, true)->required();
    addSceneSeedOption(*infoCommand, info->seed);
    addOutputOptions(*infoCommand, info->output);
    infoCommand->callback([info] {
        scenes::Scene loaded = scenes::loadScene(info->scene, info->seed);
        scenes::computeGeometricErrors(loaded);
        if (info->output.json)
            printJson(sceneInfoJson(loaded));
        else
            printSceneInfo(loaded);
    });

    struct ExportOptions {
        std::string scene, out;
        std::uint32_t seed = 1;
        OutputOptions output;
    };
    auto exportOptions = std::make_shared<ExportOptions>();
    CLI::App* exportCommand = scene->add_subcommand("export", "Write a scene as glTF 2.0 with MSFT_lod");
    addSceneOption(*exportCommand, exportOptions->scene, true)->required();
    exportCommand->add_option("--out,out", exportOptions->out, "Output .gltf or .glb")->required();
    addSceneSeedOption(*exportCommand, exportOptions->seed);
    addOutputOptions(*exportCommand, exportOptions->output);
    exportCommand->callback([exportOptions] {
        const std::string& out = exportOptions->out;
        auto lower = out;
        for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (!(lower.size() > 5 && lower.ends_with(".gltf")) && !(lower.size() > 4 && lower.ends_with(".glb"))) {
            throw UsageError("scene export: output '" + out + "' must end in .gltf or .glb");
        }
        scenes::Scene loaded = scenes::loadScene(exportOptions->scene, exportOptions->seed);
        scenes::exportGltf(loaded, out);
        if (exportOptions->output.json) {
            printJson({{"scene", loaded.name}, {"out", out}, {"objects", loaded.objects.size()}});
        } else {
            std::cout << "wrote " << out << " (" << loaded.objects.size() << " objects)\n";
        }
    });
}

}  // namespace lodopt::cli
