#include "scenes/builtin.hpp"

#include <algorithm>
#include <functional>
#include <utility>

#include "scenes/gltf_io.hpp"

namespace lodopt::scenes {
namespace {

using SceneFactory = Scene (*)(std::uint32_t);

const std::vector<std::pair<std::string, SceneFactory>>& registry() {
    static const std::vector<std::pair<std::string, SceneFactory>> scenes = {
        {"harbor", &makeHarborScene},
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

Scene loadScene(const std::string& nameOrPath, std::uint32_t seed) {
    if (isBuiltinScene(nameOrPath)) return makeBuiltinScene(nameOrPath, seed);
    if (endsWith(nameOrPath, ".gltf") || endsWith(nameOrPath, ".glb")) return loadGltf(nameOrPath);
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
