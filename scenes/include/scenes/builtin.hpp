// Built-in procedural scenes, deterministic for a given seed.
//   harbor: a sea with 6 levels, a ship with 5 and an aircraft with 5 (the default scene).
//   forest: 30-100 trees of several species on terrain, >= 4 levels each.
//   city:   >= 1000 buildings with 3 levels on a street grid.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

inline constexpr const char* kDefaultSceneName = "harbor";

std::vector<std::string> builtinSceneNames();
bool isBuiltinScene(const std::string& name);

// Throws SceneError for an unknown name.
Scene makeBuiltinScene(const std::string& name, std::uint32_t seed = 1);

Scene makeHarborScene(std::uint32_t seed = 1);
Scene makeForestScene(std::uint32_t seed = 1);
Scene makeCityScene(std::uint32_t seed = 1);

// Adds views "front", "side" and "three_quarter" framing the scene's level-0 bounds when
// the scene has no cameras (most glTF models have none).
void addDefaultViews(Scene& scene);

// A built-in name or a .gltf/.glb path (with default views added when it has no cameras).
Scene loadScene(const std::string& nameOrPath, std::uint32_t seed = 1);

// Finds a view by name or decimal index; throws SceneError listing the views otherwise.
int findView(const Scene& scene, const std::string& nameOrIndex);

}  // namespace lodopt::scenes
