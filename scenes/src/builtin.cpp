#include "scenes/builtin.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "scenes/gltf_io.hpp"

namespace lodopt::scenes {
namespace {

using SceneFactory = Scene (*)(std::uint32_t);

const std::vector<std::pair<std::string, SceneFactory>>& registry() {
    static const std::vector<std::pair<std::string, SceneFactory>> scenes = {
        {"harbor", &makeHarborScene},
        {"forest", &makeForestScene},
        {"city", &makeCityScene},
    };
    return scenes;
}

bool endsWith(const std::string& text, const std::string& suffix) {
    if (text.size() < suffix.size()) return false;
    return std::equal(suffix.rbegin(), suffix.rend(), text.rbegin(),
                      [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const auto& entry : registry()) names.push_back(entry.first);
    return names;
}

bool isBuiltinScene(const std::string& name) {
    for (const auto& entry : registry()) {
        if (entry.first == name) return true;
    }
    return false;
}

Scene makeBuiltinScene(const std::string& name, std::uint32_t seed) {
    for (const auto& entry : registry()) {
        if (entry.first == name) return entry.second(seed);
    }
    std::string known;
    for (const auto& entry : registry()) known += (known.empty() ? "" : ", ") + entry.first;
    throw SceneError("unknown scene '" + name + "': expected a built-in scene (" + known + ") or a .gltf/.glb file");
}

void addDefaultViews(Scene& scene) {
    if (!scene.views.empty()) return;
    Bounds all;
    all.min = glm::vec3(std::numeric_limits<float>::max());
    all.max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Object& object : scene.objects) {
        Bounds b = worldBounds(object, 0);
        if (b.empty()) continue;
        all.min = glm::min(all.min, b.min);
        all.max = glm::max(all.max, b.max);
    }
    if (all.empty()) {
        all.min = glm::vec3(-1.0f);
        all.max = glm::vec3(1.0f);
    }
    const glm::vec3 center = 0.5f * (all.min + all.max);
    const float radius = std::max(0.5f * glm::length(all.max - all.min), 1e-3f);
    // Far enough that the bounding sphere fits a 45° field of view, from three sides.
    const float distance = radius / std::sin(glm::radians(22.5f)) * 1.05f;
    const struct {
        const char* name;
        glm::vec3 direction;
    } sides[] = {{"front", {0.0f, 0.35f, 1.0f}}, {"side", {1.0f, 0.35f, 0.0f}}, {"three_quarter", {-0.7f, 0.6f, 0.7f}}};
    for (const auto& side : sides) {
        Camera camera;
        camera.name = side.name;
        camera.target = center;
        camera.position = center + glm::normalize(side.direction) * distance;
        camera.nearPlane = std::max(distance - 2.0f * radius, distance * 1e-3f);
        camera.farPlane = distance + 2.0f * radius;
        scene.views.push_back(camera);
    }
}

Scene loadScene(const std::string& nameOrPath, std::uint32_t seed) {
    if (isBuiltinScene(nameOrPath)) return makeBuiltinScene(nameOrPath, seed);
    if (endsWith(nameOrPath, ".gltf") || endsWith(nameOrPath, ".glb")) {
        Scene scene = loadGltf(nameOrPath);
        addDefaultViews(scene);
        return scene;
    }
    return makeBuiltinScene(nameOrPath, seed);  // throws with the list of names
}

int findView(const Scene& scene, const std::string& nameOrIndex) {
    for (std::size_t i = 0; i < scene.views.size(); ++i) {
        if (scene.views[i].name == nameOrIndex) return static_cast<int>(i);
    }
    if (!nameOrIndex.empty() && std::all_of(nameOrIndex.begin(), nameOrIndex.end(), ::isdigit) &&
        nameOrIndex.size() < 9) {
        int index = std::stoi(nameOrIndex);
        if (index < static_cast<int>(scene.views.size())) return index;
    }
    std::string known;
    for (std::size_t i = 0; i < scene.views.size(); ++i) {
        known += (known.empty() ? "" : ", ") + std::to_string(i) + " '" + scene.views[i].name + "'";
    }
    if (scene.views.empty()) known = "none: the scene has no cameras";
    throw SceneError("scene '" + scene.name + "': no view '" + nameOrIndex + "' (views: " + known + ")");
}

}  // namespace lodopt::scenes
