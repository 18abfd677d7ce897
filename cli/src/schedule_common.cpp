#include "schedule_common.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_common.hpp"
#include "scheduler/coefficients.hpp"

namespace lodopt::cli {

namespace {

glm::vec3 vec3Of(const nlohmann::json& json, const char* key, const std::string& where, glm::vec3 fallback,
                 bool required) {
    if (!json.contains(key)) {
        if (required) throw UsageError(where + "." + key + ": missing");
        return fallback;
    }
    const nlohmann::json& value = json.at(key);
    if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() ||
        !value[2].is_number()) {
        throw UsageError(where + "." + key + ": expected [x, y, z]");
    }
    const glm::vec3 v(value[0].get<float>(), value[1].get<float>(), value[2].get<float>());
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        throw UsageError(where + "." + key + ": not finite");
    }
    return v;
}

float floatOf(const nlohmann::json& json, const char* key, const std::string& where, float fallback) {
    if (!json.contains(key)) return fallback;
    if (!json.at(key).is_number()) throw UsageError(where + "." + key + ": expected a number");
    const float value = json.at(key).get<float>();
    if (!std::isfinite(value)) throw UsageError(where + "." + key + ": not finite");
    return value;
}

}  // namespace

nlohmann::json cameraToJson(const scenes::Camera& c) {
    return {{"name", c.name},
            {"position", {c.position.x, c.position.y, c.position.z}},
            {"target", {c.target.x, c.target.y, c.target.z}},
            {"up", {c.up.x, c.up.y, c.up.z}},
            {"fov_y_degrees", c.fovYDegrees},
            {"near", c.nearPlane},
            {"far", c.farPlane}};
}

scenes::Camera cameraFromJson(const nlohmann::json& json, const std::string& where) {
    if (!json.is_object()) throw UsageError(where + ": expected an object");
    scenes::Camera c;
    if (json.contains("name") && json.at("name").is_string()) c.name = json.at("name").get<std::string>();
    c.position = vec3Of(json, "position", where, {}, true);
    c.target = vec3Of(json, "target", where, {}, true);
    c.up = vec3Of(json, "up", where, c.up, false);
    c.fovYDegrees = floatOf(json, "fov_y_degrees", where, c.fovYDegrees);
    c.nearPlane = floatOf(json, "near", where, c.nearPlane);
    c.farPlane = floatOf(json, "far", where, c.farPlane);
    if (c.position == c.target) throw UsageError(where + ": position and target coincide");
    if (!(c.fovYDegrees > 0.0f && c.fovYDegrees < 180.0f))
        throw UsageError(where + ".fov_y_degrees: must be in (0, 180)");
    if (!(c.nearPlane > 0.0f && c.farPlane > c.nearPlane)) throw UsageError(where + ": needs 0 < near < far");
    return c;
}

scenes::CameraPath defaultCameraPath(const scenes::Scene& scene) {
    if (scene.paths.empty()) {
        throw UsageError("scene '" + scene.name + "' has no camera path: pass --path FILE (a camera path JSON file)");
    }
    return scene.paths.front();
}

scenes::CameraPath loadCameraPath(const scenes::Scene& scene, const std::string& nameOrFile) {
    for (const scenes::CameraPath& path : scene.paths) {
        if (path.name == nameOrFile) return path;
    }
    if (!std::filesystem::is_regular_file(nameOrFile)) {
        std::string known;
        for (const scenes::CameraPath& path : scene.paths) known += (known.empty() ? "" : ", ") + path.name;
        throw UsageError("--path '" + nameOrFile + "': neither a camera path of scene '" + scene.name + "' (" +
                         (known.empty() ? "it has none" : known) + ") nor a camera path file");
    }
    std::ifstream file(nameOrFile, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    const nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, false);
    if (json.is_discarded() || !json.is_object()) throw UsageError(nameOrFile + ": not a JSON object");
    scenes::CameraPath path;
    path.name = json.contains("name") && json["name"].is_string() ? json["name"].get<std::string>()
                                                                  : std::filesystem::path(nameOrFile).stem().string();
    path.framesPerSecond = floatOf(json, "frames_per_second", nameOrFile, 30.0f);
    if (!(path.framesPerSecond > 0.0f)) throw UsageError(nameOrFile + ".frames_per_second: must be > 0");
    if (!json.contains("frames") || !json["frames"].is_array() || json["frames"].empty()) {
        throw UsageError(nameOrFile + ".frames: expected a non-empty array of cameras");
    }
    const nlohmann::json& frames = json["frames"];
    for (std::size_t f = 0; f < frames.size(); ++f) {
        scenes::Camera camera = cameraFromJson(frames[f], nameOrFile + ": frames[" + std::to_string(f) + "]");
        if (camera.name.empty()) camera.name = path.name + "_" + std::to_string(f);
        path.frames.push_back(camera);
    }
    return path;
}

scheduler::FeatureMode parseFeatureMode(const std::string& text) {
    if (text == "bounds") return scheduler::FeatureMode::Bounds;
    if (text == "exact") return scheduler::FeatureMode::Exact;
    throw UsageError("--features: '" + text + "' (expected bounds or exact)");
}

scheduler::Organisation parseOrganisation(const std::string& text) {
    if (text == "flat") return scheduler::Organisation::Flat;
    if (text == "tiles") return scheduler::Organisation::Tiles;
    throw UsageError("--organisation: '" + text + "' (expected flat or tiles)");
}

void parseSwitchControl(const std::string& text, scheduler::SwitchControlParameters& p) {
    const std::vector<double> values = parseNumberList(text, "--switch-control", "D1,K1,D2,K2,NEAR");
    if (values.size() != 5) throw UsageError("--switch-control: expected five numbers D1,K1,D2,K2,NEAR");
    p.delta1 = values[0];
    p.k1 = values[1];
    p.delta2 = values[2];
    p.k2 = values[3];
    p.nearDistance = values[4];
    try {
        scheduler::validateSwitchControl(p);
    } catch (const std::invalid_argument& error) {
        throw UsageError(std::string("--switch-control: ") + error.what());
    }
}

scheduler::SwitchRule parseSwitchRule(const std::string& text) {
    for (scheduler::SwitchRule rule : {scheduler::SwitchRule::Hysteresis, scheduler::SwitchRule::Vmi20}) {
        if (text == scheduler::toString(rule)) return rule;
    }
    throw UsageError("--switch-rule: '" + text + "' is not hysteresis or vmi20");
}

scheduler::SchedulerCoefficients loadCoefficientsOrThrow(const std::string& path) {
    try {
        return scheduler::loadCoefficients(path);
    } catch (const scheduler::CoefficientsError& error) {
        throw UsageError(error.what());
    }
}

}  // namespace lodopt::cli
