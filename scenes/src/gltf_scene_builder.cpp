// Object discovery and level assembly for the glTF loader (rules in gltf_io.hpp and
// docs/gltf.md; MSFT_lod per the Microsoft vendor extension, ids = coarser levels in order).
#include "gltf_scene_builder.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include <glm/gtc/matrix_inverse.hpp>

#include "scenes/engine_lod.hpp"
#include "scenes/lod_generation.hpp"

namespace lodopt::scenes::gltf_detail {

namespace {

std::optional<std::vector<float>> numberArray(const tinygltf::Value& value) {
    if (!value.IsArray()) return std::nullopt;
    std::vector<float> numbers;
    for (std::size_t i = 0; i < value.ArrayLen(); ++i) {
        const tinygltf::Value& item = value.Get(int(i));
        if (!item.IsNumber() || !std::isfinite(item.GetNumberAsDouble())) return std::nullopt;
        numbers.push_back(static_cast<float>(item.GetNumberAsDouble()));
    }
    return numbers;
}

// extras.MSFT_screencoverage: one threshold per level (extra values are ignored).
void applyScreenCoverage(const tinygltf::Value& extras, std::vector<Level>& levels) {
    if (!extras.IsObject() || !extras.Has("MSFT_screencoverage")) return;
    auto coverage = numberArray(extras.Get("MSFT_screencoverage"));
    if (!coverage) return;
    for (std::size_t k = 0; k < levels.size() && k < coverage->size(); ++k) levels[k].screenCoverage = (*coverage)[k];
}

// "<base>_LOD<k>" (k: 1-6 digits, "_LOD" in any case, base not empty): the base and k. The
// same rule as std::regex "^(.+)_LOD([0-9]{1,6})$" (icase), which libstdc++ matches by
// recursion, one frame per character: a long hostile name overflowed the stack.
bool splitLodName(const std::string& name, std::string& base, int& k) {
    std::size_t digits = 0;
    while (digits < name.size() && std::isdigit(static_cast<unsigned char>(name[name.size() - 1 - digits]))) ++digits;
    if (digits == 0 || digits > 6 || name.size() < digits + 5) return false;
    const std::size_t suffix = name.size() - digits - 4;
    static const char kLod[] = "_lod";
    for (std::size_t i = 0; i < 4; ++i) {
        if (std::tolower(static_cast<unsigned char>(name[suffix + i])) != kLod[i]) return false;
    }
    base = name.substr(0, suffix);
    k = std::stoi(name.substr(name.size() - digits));
    return true;
}

std::uint64_t triangleCount(const Level& level) {
    std::uint64_t triangles = 0;
    for (const Mesh& mesh : level.meshes) triangles += mesh.indices.size() / 3;
    return triangles;
}

}  // namespace

SceneBuilder::SceneBuilder(const tinygltf::Model& model, const ModelGraph& graph, const std::string& file,
                           const GltfLoadOptions& options, std::vector<std::vector<unsigned char>> encodedImages)
    : mModel(model), mGraph(graph), mFile(file), mOptions(options), mEncodedImages(std::move(encodedImages)) {
    mMeshUses.assign(model.meshes.size(), 0);
    for (const tinygltf::Node& node : model.nodes) {
        if (node.mesh >= 0) ++mMeshUses[node.mesh];
    }
}

void SceneBuilder::warn(const std::string& message) const {
    if (mOptions.warnings) mOptions.warnings->push_back(mFile + ": " + message);
}

std::string SceneBuilder::nodeName(int node) const {
    const tinygltf::Node& n = mModel.nodes[node];
    if (!n.name.empty()) return n.name;
    if (n.mesh >= 0 && !mModel.meshes[n.mesh].name.empty()) return mModel.meshes[n.mesh].name;
    return "node" + std::to_string(node);
}

Scene SceneBuilder::build() {
    const int sceneIndex = mModel.defaultScene >= 0 ? mModel.defaultScene : (mModel.scenes.empty() ? -1 : 0);
    mScene.name = sceneIndex >= 0 ? mModel.scenes[sceneIndex].name : std::string();
    if (mScene.name.empty()) mScene.name = std::filesystem::path(mFile).stem().string();
    buildMaterials();

    std::vector<int> roots;
    if (sceneIndex >= 0) {
        roots = mModel.scenes[sceneIndex].nodes;
        for (int root : roots) {
            if (mGraph.parent[root] != -1) {
                // Invalid (SCENE_NON_ROOT_NODE) but common in exported files: draw the
                // node where its own transform puts it, as viewers do.
                warn(element("nodes", root) + " is listed as a scene root but is a child of node " +
                     std::to_string(mGraph.parent[root]) + "; its parent's transform is ignored");
            }
        }
    } else {
        // No scene: every parentless node, as a viewer that shows "all nodes" would.
        for (int n = 0; n < static_cast<int>(mModel.nodes.size()); ++n) {
            if (mGraph.parent[n] == -1) roots.push_back(n);
        }
    }
    visitGroupLevel(roots, glm::mat4(1.0f));
    generateMissingTangents();
    updateStatistics(mScene);
    convertScreenCoverage();
    buildViews();
    if (sceneIndex >= 0) buildPaths(sceneIndex);
    validateScene(mScene);
    return std::move(mScene);
}

// A file that marks its MSFT_screencoverage values as Unity relative heights (gltf_io.hpp):
// back to screen sizes, with each object's level-0 world bounds as the exporter used them.
void SceneBuilder::convertScreenCoverage() {
    const tinygltf::Value& extras = mModel.asset.extras;
    if (!extras.IsObject() || !extras.Has("lodopt_screencoverage")) return;
    const tinygltf::Value& convention = extras.Get("lodopt_screencoverage");
    if (!convention.IsString() || convention.Get<std::string>() != "unity_relative_height") {
        warn("asset.extras.lodopt_screencoverage: unknown convention, MSFT_screencoverage read as screen sizes");
        return;
    }
    for (Object& object : mScene.objects) {
        const Bounds bounds = worldBounds(object, 0);
        for (Level& level : object.levels) {
            if (!level.screenCoverage) continue;
            const float size = float(screenSizeFromUnityRelativeHeight(*level.screenCoverage, bounds));
            if (std::isfinite(size)) {
                level.screenCoverage = size;
            } else {  // degenerate or enormous bounds: no usable threshold
                level.screenCoverage.reset();
                warn("object '" + object.name + "': an MSFT_screencoverage value does not convert to a screen size; "
                     "ignored");
            }
        }
    }
}

// Normal maps need a tangent frame; a primitive without TANGENT gets one from its UVs (spec
// §3.7.2.1: "client implementations SHOULD calculate tangents using default MikkTSpace
// algorithms"). Without the UV set the normal map cannot be read, and the renderer skips it.
void SceneBuilder::generateMissingTangents() {
    for (Object& object : mScene.objects) {
        for (Level& level : object.levels) {
            for (Mesh& mesh : level.meshes) {
                if (mesh.material < 0 || !mesh.tangents.empty()) continue;
                const TextureRef& normalMap = mScene.materials[std::size_t(mesh.material)].normalTexture;
                const std::vector<glm::vec2>& uvs = normalMap.texCoord == 1 ? mesh.uvs1 : mesh.uvs;
                if (normalMap.present() && uvs.size() == mesh.positions.size())
                    computeTangents(mesh, normalMap.texCoord);
            }
        }
    }
}

SceneBuilder::Classified SceneBuilder::classify(const std::vector<int>& siblings) const {
    Classified result;
    result.roles.assign(siblings.size(), Role::kPlain);
    result.group.assign(siblings.size(), -1);
    std::map<std::string, std::vector<std::pair<int, std::size_t>>> byBase;  // base → (k, sibling position)
    for (std::size_t i = 0; i < siblings.size(); ++i) {
        const int n = siblings[i];
        const tinygltf::Node& node = mModel.nodes[n];
        if (mGraph.lodLevelOf[n] != -1) {
            result.roles[i] = Role::kLodLevel;
        } else if (!mGraph.nodeLods[n].empty()) {
            result.roles[i] = Role::kLodRoot;
        } else {
            result.roles[i] = node.mesh >= 0 ? Role::kMeshNode : Role::kPlain;
            std::string base;
            int k = 0;
            if (splitLodName(node.name, base, k)) {
                std::transform(base.begin(), base.end(), base.begin(), [](unsigned char c) { return std::tolower(c); });
                byBase[base].emplace_back(k, i);
            }
        }
    }
    for (auto& [base, members] : byBase) {
        if (members.size() < 2) continue;
        std::sort(members.begin(), members.end());
        bool distinct = true;
        for (std::size_t m = 1; m < members.size(); ++m) distinct = distinct && members[m].first != members[m - 1].first;
        if (!distinct) {
            warn("sibling nodes named " + base + "_LOD<k> repeat a level number; not read as levels");
            continue;
        }
        // The object takes the finest member's spelling of the name.
        const std::string& finestName = mModel.nodes[siblings[members.front().second]].name;
        NameGroup group{finestName.substr(0, base.size()), {}};
        for (const auto& [k, position] : members) {
            group.members.push_back(siblings[position]);
            result.roles[position] = Role::kGroupMember;
            result.group[position] = static_cast<int>(result.groups.size());
        }
        result.roles[members.front().second] = Role::kGroupFinest;
        result.groups.push_back(std::move(group));
    }
    return result;
}

void SceneBuilder::visitGroupLevel(const std::vector<int>& siblings, const glm::mat4& parentWorld) {
    const Classified classified = classify(siblings);
    for (std::size_t i = 0; i < siblings.size(); ++i) {
        const int n = siblings[i];
        switch (classified.roles[i]) {
        case Role::kLodLevel:
        case Role::kGroupMember: break;
        case Role::kGroupFinest: emitNameGroupObject(classified.groups[classified.group[i]], parentWorld); break;
        case Role::kLodRoot:
        case Role::kMeshNode: emitNodeObject(n, parentWorld); break;
        case Role::kPlain: {
            const glm::mat4 world = parentWorld * localTransform(mModel.nodes[n]);
            if (mModel.nodes[n].camera >= 0) mCameraNodes.emplace_back(n, world);
            visitGroupLevel(mModel.nodes[n].children, world);
            break;
        }
        }
    }
}

void SceneBuilder::appendMesh(int meshIndex, const glm::mat4& relative, Level& level) {
    const auto& primitives = mModel.meshes[meshIndex].primitives;
    const glm::mat3 linear(relative);
    const glm::mat3 normalMatrix = glm::inverseTranspose(linear);
    const bool mirrored = glm::determinant(linear) < 0.0f;
    for (int p = 0; p < static_cast<int>(primitives.size()); ++p) {
        std::shared_ptr<const DecodedPrimitive> decoded;
        auto cached = mPrimitiveCache.find({meshIndex, p});
        if (cached != mPrimitiveCache.end()) {
            decoded = cached->second;
        } else {
            decoded = std::make_shared<const DecodedPrimitive>(
                decodePrimitive(mModel, meshIndex, p, mFile, mOptions.skipNonTrianglePrimitives, mOptions.warnings));
            if (mMeshUses[meshIndex] > 1) mPrimitiveCache[{meshIndex, p}] = decoded;
        }
        if (decoded->skipped || decoded->indices.empty()) continue;
        Mesh mesh;
        mesh.material = decoded->material;
        mesh.positions.resize(decoded->positions.size());
        for (std::size_t v = 0; v < decoded->positions.size(); ++v) {
            mesh.positions[v] = glm::vec3(relative * glm::vec4(decoded->positions[v], 1.0f));
        }
        mesh.uvs = decoded->uvs;
        mesh.uvs1 = decoded->uvs1;
        mesh.colors = decoded->colors;
        mesh.indices = decoded->indices;
        // Tangents follow the surface (the linear part); a mirroring transform flips the
        // bitangent's side, which cross(normal', tangent') does not see.
        mesh.tangents.resize(decoded->tangents.size());
        for (std::size_t v = 0; v < decoded->tangents.size(); ++v) {
            const glm::vec4& t = decoded->tangents[v];
            const glm::vec3 direction = linear * glm::vec3(t);
            const float length = glm::length(direction);
            const float sign = (t.w < 0.0f) != mirrored ? -1.0f : 1.0f;
            mesh.tangents[v] = glm::vec4(length > 1e-20f ? direction / length : glm::vec3(1.0f, 0.0f, 0.0f), sign);
        }
        // A mirroring transform turns counter-clockwise front faces clockwise (spec §3.7.4).
        if (mirrored) {
            for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
        }
        if (decoded->normals.empty()) {
            // Flat normals; the file's tangents, if any, are to be ignored (spec §3.7.2.1).
            computeNormals(mesh);
            mesh.flatNormals = true;
            mesh.tangents.clear();
        } else {
            mesh.normals.resize(decoded->normals.size());
            for (std::size_t v = 0; v < decoded->normals.size(); ++v) {
                const glm::vec3 n = normalMatrix * decoded->normals[v];
                const float length = glm::length(n);
                mesh.normals[v] = length > 1e-20f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
            }
        }
        level.meshes.push_back(std::move(mesh));
    }
}

void SceneBuilder::flatten(int node, const glm::mat4& relative, const glm::mat4& world, Level& level, bool split,
                           std::vector<Pending>* pending) {
    const tinygltf::Node& n = mModel.nodes[node];
    if (split && n.camera >= 0) mCameraNodes.emplace_back(node, world);
    if (n.mesh >= 0) appendMesh(n.mesh, relative, level);
    if (n.children.empty()) return;
    const Classified classified = classify(n.children);
    for (std::size_t i = 0; i < n.children.size(); ++i) {
        const int child = n.children[i];
        const glm::mat4 local = localTransform(mModel.nodes[child]);
        const Role role = classified.roles[i];
        if (role == Role::kLodLevel) continue;
        if (split && role == Role::kGroupMember) continue;
        if (split && role == Role::kGroupFinest) {
            pending->push_back({-1, classified.groups[classified.group[i]], world});
            continue;
        }
        if (split && role == Role::kLodRoot) {
            pending->push_back({child, std::nullopt, world});
            continue;
        }
        flatten(child, relative * local, world * local, level, split, pending);
    }
}

void SceneBuilder::emitPending(std::vector<Pending>& pending) {
    for (Pending& item : pending) {
        if (item.group) {
            emitNameGroupObject(*item.group, item.parentWorld);
        } else {
            emitNodeObject(item.node, item.parentWorld);
        }
    }
}

void SceneBuilder::emitNodeObject(int node, const glm::mat4& parentWorld) {
    const tinygltf::Node& n = mModel.nodes[node];
    const glm::mat4 local = localTransform(n);
    Object object;
    object.name = nodeName(node);
    object.transform = parentWorld * local;
    std::vector<Pending> pending;
    object.levels.emplace_back();
    flatten(node, glm::mat4(1.0f), object.transform, object.levels[0], true, &pending);
    const glm::mat4 toObject = glm::inverse(local);
    for (int levelNode : mGraph.nodeLods[node]) {
        // A coarser level sits where level 0 sits: under level 0's parent, with its own
        // local transform (Babylon.js places MSFT_lod levels the same way).
        Level level;
        const glm::mat4 relative = toObject * localTransform(mModel.nodes[levelNode]);
        flatten(levelNode, relative, parentWorld * localTransform(mModel.nodes[levelNode]), level, false, nullptr);
        object.levels.push_back(std::move(level));
    }
    if (object.levels.size() > 1) applyScreenCoverage(n.extras, object.levels);
    applyMaterialLods(object, node);
    finishObject(std::move(object));
    emitPending(pending);
}

void SceneBuilder::emitNameGroupObject(const NameGroup& group, const glm::mat4& parentWorld) {
    const int finest = group.members.front();
    const glm::mat4 local = localTransform(mModel.nodes[finest]);
    Object object;
    object.name = group.base;
    object.transform = parentWorld * local;
    std::vector<Pending> pending;
    const glm::mat4 toObject = glm::inverse(local);
    for (std::size_t k = 0; k < group.members.size(); ++k) {
        const int member = group.members[k];
        const glm::mat4 memberLocal = localTransform(mModel.nodes[member]);
        Level level;
        flatten(member, k == 0 ? glm::mat4(1.0f) : toObject * memberLocal, parentWorld * memberLocal, level, k == 0,
                k == 0 ? &pending : nullptr);
        object.levels.push_back(std::move(level));
    }
    applyScreenCoverage(mModel.nodes[finest].extras, object.levels);
    finishObject(std::move(object));
    emitPending(pending);
}

void SceneBuilder::applyMaterialLods(Object& object, int rootNode) {
    int extraLevels = 0;
    int coverageMaterial = -1;
    for (const Mesh& mesh : object.levels[0].meshes) {
        if (mesh.material < 0 || mGraph.materialLods[mesh.material].empty()) continue;
        extraLevels = std::max(extraLevels, static_cast<int>(mGraph.materialLods[mesh.material].size()));
        if (coverageMaterial < 0) coverageMaterial = mesh.material;
    }
    if (extraLevels == 0) return;
    if (object.levels.size() > 1) {
        warn(element("nodes", rootNode) + ": material MSFT_lod ignored: the node has its own levels");
        return;
    }
    for (int k = 1; k <= extraLevels; ++k) {
        Level level = object.levels[0];
        for (Mesh& mesh : level.meshes) {
            if (mesh.material < 0) continue;
            const std::vector<int>& chain = mGraph.materialLods[mesh.material];
            if (!chain.empty()) mesh.material = chain[std::min<std::size_t>(k, chain.size()) - 1];
        }
        object.levels.push_back(std::move(level));
    }
    applyScreenCoverage(mModel.materials[coverageMaterial].extras, object.levels);
}

void SceneBuilder::finishObject(Object object) {
    std::uint64_t triangles = 0;
    for (const Level& level : object.levels) triangles += triangleCount(level);
    if (triangles == 0) {
        warn("object '" + object.name + "' has no triangles; left out");
        return;
    }
    // Finite vertices under a finite transform can still overflow (1e30 x 1e30): world bounds,
    // default views and the time model would all be infinite.
    for (std::size_t l = 0; l < object.levels.size(); ++l) {
        for (const Mesh& mesh : object.levels[l].meshes) {
            for (const glm::vec3& p : mesh.positions) {
                const glm::vec4 world = object.transform * glm::vec4(p, 1.0f);
                if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z)) {
                    fail(mFile, "object '" + object.name + "'",
                         "level " + std::to_string(l) + " has a world-space position that is not finite (its transform "
                         "overflows)");
                }
            }
        }
    }
    if (mOptions.generateLods && object.levels.size() == 1) generateLodChain(object);
    mScene.objects.push_back(std::move(object));
}

}  // namespace lodopt::scenes::gltf_detail
