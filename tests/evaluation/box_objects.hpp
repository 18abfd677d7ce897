// Hand-made test scenes' objects: boxes, one box per level (evaluation_test, occlusion_test).
#pragma once

#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/mesh_builder.hpp"
#include "scenes/scene.hpp"

namespace lodopt::test_scenes {

inline scenes::Level boxLevel(glm::vec3 halfExtents, int material) {
    scenes::MeshBuilder builder(material);
    builder.addBox(glm::vec3(0.0f), halfExtents);
    scenes::Level level;
    level.meshes.push_back(builder.finish());
    return level;
}

// An object at `position` whose level k is a box of half extents levels[k] around it.
inline scenes::Object boxObject(const std::string& name, glm::vec3 position, const std::vector<glm::vec3>& levels,
                                int material) {
    scenes::Object object;
    object.name = name;
    object.transform = glm::translate(glm::mat4(1.0f), position);
    for (glm::vec3 halfExtents : levels) object.levels.push_back(boxLevel(halfExtents, material));
    return object;
}

}  // namespace lodopt::test_scenes
