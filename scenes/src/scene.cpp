#include "scenes/scene.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace lodopt::scenes {

Combination referenceCombination(const Scene& scene) {
    return Combination(scene.objects.size(), 0);
}

Combination coarsestCombination(const Scene& scene) {
    Combination combination;
    combination.reserve(scene.objects.size());
    for (const Object& object : scene.objects) {
        combination.push_back(static_cast<int>(object.levels.size()) - 1);
    }
    return combination;
}

void validateCombination(const Scene& scene, const Combination& combination) {
    if (combination.size() != scene.objects.size()) {
        throw SceneError("combination has " + std::to_string(combination.size()) + " levels but scene '" +
                         scene.name + "' has " + std::to_string(scene.objects.size()) + " objects");
    }
    for (std::size_t i = 0; i < combination.size(); ++i) {
        int level = combination[i];
        int count = static_cast<int>(scene.objects[i].levels.size());
        if (level != kNotDrawn && (level < 0 || level >= count)) {
            throw SceneError("combination: object " + std::to_string(i) + " ('" + scene.objects[i].name +
                             "') has levels 0.." + std::to_string(count - 1) + ", got " + std::to_string(level));
        }
    }
}

Bounds computeBounds(const std::vector<Mesh>& meshes) {
    Bounds bounds;
    bounds.min = glm::vec3(std::numeric_limits<float>::max());
    bounds.max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Mesh& mesh : meshes) {
        for (const glm::vec3& p : mesh.positions) {
            bounds.min = glm::min(bounds.min, p);
            bounds.max = glm::max(bounds.max, p);
        }
    }
    if (bounds.empty()) {
        bounds.min = glm::vec3(0.0f);
        bounds.max = glm::vec3(-1.0f);  // stays empty(): max < min
        return bounds;
    }
    // The box's circumscribed sphere: cheap, conservative and independent of vertex order.
    bounds.sphereCenter = 0.5f * (bounds.min + bounds.max);
    bounds.sphereRadius = 0.5f * glm::length(bounds.max - bounds.min);
    return bounds;
}

LevelStats computeLevelStats(const Scene& scene, const Level& level) {
    LevelStats stats;
    std::set<int> textures;
    for (const Mesh& mesh : level.meshes) {
        stats.vertices += mesh.positions.size();
        stats.triangles += mesh.indices.size() / 3;
        if (!mesh.indices.empty()) ++stats.drawCalls;
        if (mesh.material >= 0 && mesh.material < static_cast<int>(scene.materials.size())) {
            const Material& material = scene.materials[mesh.material];
            for (const TextureRef* reference :
                 {&material.baseColorTexture, &material.metallicRoughnessTexture, &material.normalTexture,
                  &material.occlusionTexture, &material.emissiveTexture}) {
                if (reference->present()) textures.insert(reference->texture);
            }
        }
    }
    for (int texture : textures) {
        if (texture < static_cast<int>(scene.textures.size())) {
            const Texture& t = scene.textures[texture];
            stats.textureBytes += std::uint64_t(t.width) * std::uint64_t(t.height) * 4u;
        }
    }
    stats.bounds = computeBounds(level.meshes);
    return stats;
}

void updateStatistics(Scene& scene) {
    for (Object& object : scene.objects) {
        for (Level& level : object.levels) level.stats = computeLevelStats(scene, level);
    }
}

Bounds worldBounds(const Object& object, int level) {
    const Bounds& local = object.levels.at(level).stats.bounds;
    Bounds world;
    if (local.empty()) return local;
    world.min = glm::vec3(std::numeric_limits<float>::max());
    world.max = glm::vec3(-std::numeric_limits<float>::max());
    for (int corner = 0; corner < 8; ++corner) {
        glm::vec3 p((corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                    (corner & 4) ? local.max.z : local.min.z);
        glm::vec3 w = glm::vec3(object.transform * glm::vec4(p, 1.0f));
        world.min = glm::min(world.min, w);
        world.max = glm::max(world.max, w);
    }
    world.sphereCenter = 0.5f * (world.min + world.max);
    world.sphereRadius = 0.5f * glm::length(world.max - world.min);
    return world;
}

void computeNormals(Mesh& mesh) {
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        std::uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        if (a >= mesh.positions.size() || b >= mesh.positions.size() || c >= mesh.positions.size()) continue;
        // Unnormalised cross product: larger triangles weigh more.
        glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) continue;
        mesh.normals[a] += n;
        mesh.normals[b] += n;
        mesh.normals[c] += n;
    }
    for (glm::vec3& n : mesh.normals) {
        float length = glm::length(n);
        n = length > 1e-20f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void computeTangents(Mesh& mesh, int texCoord) {
    const std::vector<glm::vec2>& uvs = texCoord == 1 ? mesh.uvs1 : mesh.uvs;
    const std::size_t count = mesh.positions.size();
    std::vector<glm::vec3> tangentSum(count, glm::vec3(0.0f)), bitangentSum(count, glm::vec3(0.0f));
    if (uvs.size() == count && mesh.normals.size() == count) {
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const std::uint32_t corner[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
            if (corner[0] >= count || corner[1] >= count || corner[2] >= count) continue;
            const glm::vec3 edge1 = mesh.positions[corner[1]] - mesh.positions[corner[0]];
            const glm::vec3 edge2 = mesh.positions[corner[2]] - mesh.positions[corner[0]];
            const glm::vec2 duv1 = uvs[corner[1]] - uvs[corner[0]], duv2 = uvs[corner[2]] - uvs[corner[0]];
            const float determinant = duv1.x * duv2.y - duv2.x * duv1.y;
            if (!(std::abs(determinant) > 1e-20f)) continue;  // degenerate UVs: no direction
            // Per triangle, unit vectors: MikkTSpace weighs corners by angle, not by area.
            glm::vec3 tangent = (edge1 * duv2.y - edge2 * duv1.y) / determinant;
            glm::vec3 bitangent = (edge2 * duv1.x - edge1 * duv2.x) / determinant;
            const float tangentLength = glm::length(tangent), bitangentLength = glm::length(bitangent);
            if (!(tangentLength > 1e-20f) || !(bitangentLength > 1e-20f) || !std::isfinite(tangentLength) ||
                !std::isfinite(bitangentLength)) {
                continue;
            }
            tangent /= tangentLength;
            bitangent /= bitangentLength;
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 toNext = mesh.positions[corner[(k + 1) % 3]] - mesh.positions[corner[k]];
                const glm::vec3 toPrevious = mesh.positions[corner[(k + 2) % 3]] - mesh.positions[corner[k]];
                const float lengths = glm::length(toNext) * glm::length(toPrevious);
                if (!(lengths > 0.0f)) continue;
                const float angle = std::acos(std::clamp(glm::dot(toNext, toPrevious) / lengths, -1.0f, 1.0f));
                tangentSum[corner[k]] += angle * tangent;
                bitangentSum[corner[k]] += angle * bitangent;
            }
        }
    }
    mesh.tangents.resize(count);
    for (std::size_t v = 0; v < count; ++v) {
        const glm::vec3 normal = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f, 1.0f, 0.0f);
        glm::vec3 tangent = tangentSum[v] - normal * glm::dot(normal, tangentSum[v]);
        float length = glm::length(tangent);
        if (!(length > 1e-12f) || !std::isfinite(length)) {
            // Any direction orthogonal to the normal: the axis least aligned with it, projected.
            const glm::vec3 axis =
                std::abs(normal.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
            tangent = axis - normal * glm::dot(normal, axis);
            length = glm::length(tangent);
        }
        tangent /= length;
        // glTF's v runs down the image while a normal map's green points up it (spec §3.9.3), so
        // the bitangent is -dP/dv, as MikkTSpace gives it for glTF's flipped UVs.
        const float handedness = glm::dot(glm::cross(normal, tangent), bitangentSum[v]) > 0.0f ? -1.0f : 1.0f;
        mesh.tangents[v] = glm::vec4(tangent, handedness);
    }
}

glm::mat3 TextureTransform::matrix() const {
    // KHR_texture_transform: translation * rotation * scale, the rotation matrix as the
    // extension writes it (rows (cos, sin), (-sin, cos)); glm is column-major.
    const float c = std::cos(rotation), s = std::sin(rotation);
    const glm::mat3 translationMatrix(1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f, offset.x, offset.y, 1.0f);
    const glm::mat3 rotationMatrix(c, -s, 0.0f, s, c, 0.0f, 0.0f, 0.0f, 1.0f);
    const glm::mat3 scaleMatrix(scale.x, 0.0f, 0.0f, 0.0f, scale.y, 0.0f, 0.0f, 0.0f, 1.0f);
    return translationMatrix * rotationMatrix * scaleMatrix;
}

Material diffuseMaterial(std::string name, glm::vec3 color, int baseColorTexture) {
    Material material;
    material.name = std::move(name);
    material.baseColorFactor = glm::vec4(color, 1.0f);
    material.baseColorTexture.texture = baseColorTexture;
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.8f;
    material.doubleSided = true;
    return material;
}

void validateScene(const Scene& scene) {
    const std::string prefix = scene.name.empty() ? std::string("scene") : scene.name;
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        const Texture& texture = scene.textures[t];
        if (texture.width <= 0 || texture.height <= 0 ||
            texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4u) {
            throw SceneError(prefix + ": textures[" + std::to_string(t) + "]: pixel data does not match " +
                             std::to_string(texture.width) + "x" + std::to_string(texture.height) + " RGBA8");
        }
    }
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& material = scene.materials[m];
        const std::pair<const char*, const TextureRef*> references[] = {
            {"baseColorTexture", &material.baseColorTexture},
            {"metallicRoughnessTexture", &material.metallicRoughnessTexture},
            {"normalTexture", &material.normalTexture},
            {"occlusionTexture", &material.occlusionTexture},
            {"emissiveTexture", &material.emissiveTexture}};
        for (const auto& [name, reference] : references) {
            const std::string where = prefix + ": materials[" + std::to_string(m) + "]." + name;
            if (reference->texture >= static_cast<int>(scene.textures.size()) || reference->texture < -1) {
                throw SceneError(where + ": " + std::to_string(reference->texture) + " does not exist");
            }
            if (reference->texCoord < 0 || reference->texCoord > 1) {
                throw SceneError(where + ": TEXCOORD_" + std::to_string(reference->texCoord) + " is not 0 or 1");
            }
        }
    }
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const Object& object = scene.objects[o];
        const std::string where = prefix + ": objects[" + std::to_string(o) + "] ('" + object.name + "')";
        if (object.levels.empty()) throw SceneError(where + ": has no levels");
        for (std::size_t l = 0; l < object.levels.size(); ++l) {
            for (std::size_t k = 0; k < object.levels[l].meshes.size(); ++k) {
                const Mesh& mesh = object.levels[l].meshes[k];
                const std::string at = where + ".levels[" + std::to_string(l) + "].meshes[" + std::to_string(k) + "]";
                if (mesh.indices.size() % 3 != 0) throw SceneError(at + ": index count is not a multiple of 3");
                if (mesh.normals.size() != mesh.positions.size()) throw SceneError(at + ": normals do not match positions");
                if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
                    throw SceneError(at + ": uvs do not match positions");
                }
                if (!mesh.uvs1.empty() && mesh.uvs1.size() != mesh.positions.size()) {
                    throw SceneError(at + ": uvs1 do not match positions");
                }
                if (!mesh.tangents.empty() && mesh.tangents.size() != mesh.positions.size()) {
                    throw SceneError(at + ": tangents do not match positions");
                }
                if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) {
                    throw SceneError(at + ": colors do not match positions");
                }
                if (mesh.material < -1 || mesh.material >= static_cast<int>(scene.materials.size())) {
                    throw SceneError(at + ": material " + std::to_string(mesh.material) + " does not exist");
                }
                for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
                    const glm::vec3& p = mesh.positions[v];
                    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
                        throw SceneError(at + ": position " + std::to_string(v) + " is not finite");
                    }
                }
                for (std::uint32_t index : mesh.indices) {
                    if (index >= mesh.positions.size()) {
                        throw SceneError(at + ": index " + std::to_string(index) + " >= vertex count " +
                                         std::to_string(mesh.positions.size()));
                    }
                }
            }
        }
    }
}

glm::mat4 viewMatrix(const Camera& camera) {
    glm::vec3 forward = camera.target - camera.position;
    glm::vec3 up = camera.up;
    // A view straight along `up` has no defined roll: pick another up rather than NaN.
    if (glm::length(glm::cross(forward, up)) < 1e-6f * glm::length(forward)) {
        up = std::abs(forward.y) > std::abs(forward.z) ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return glm::lookAt(camera.position, camera.target, up);
}

glm::mat4 projectionMatrix(const Camera& camera, float aspect) {
    return glm::perspective(glm::radians(camera.fovYDegrees), aspect, camera.nearPlane, camera.farPlane);
}

}  // namespace lodopt::scenes
