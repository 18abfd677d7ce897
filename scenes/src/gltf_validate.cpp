// Reference, range and cycle checks run after tinygltf has parsed a file.
//
// tinygltf accepts many invalid files (an index past an array, a node that is its own
// ancestor, an accessor that runs past its bufferView); walking such a model naively reads
// out of bounds or recurses forever. Everything the conversion later indexes is checked here
// once, with a message naming the glTF element (docs/gltf.md has the catalogue).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

#include "gltf_detail.hpp"

namespace lodopt::scenes::gltf_detail {

void fail(const std::string& file, const std::string& elementName, const std::string& what) {
    throw SceneError(file + ": " + (elementName.empty() ? std::string() : elementName + ": ") + what);
}

std::string element(const std::string& array, int index) {
    return array + "[" + std::to_string(index) + "]";
}

std::uint64_t componentSize(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

namespace {

// Checks indices into one of the model's arrays.
class RefChecker {
public:
    RefChecker(const tinygltf::Model& model, const std::string& file) : mModel(model), mFile(file) {}

    void check(int index, std::size_t size, const std::string& what, const std::string& arrayName,
               bool optional = true) const {
        if (index < 0 && optional && index == -1) return;
        if (index < 0 || static_cast<std::size_t>(index) >= size) {
            fail(mFile, what, arrayName + " " + std::to_string(index) + " does not exist (the file has " +
                                  std::to_string(size) + ")");
        }
    }
    void accessor(int index, const std::string& what, bool optional = true) const {
        check(index, mModel.accessors.size(), what, "accessor", optional);
    }
    void node(int index, const std::string& what) const { check(index, mModel.nodes.size(), what, "node", false); }
    void texture(const tinygltf::TextureInfo& info, const std::string& what) const {
        check(info.index, mModel.textures.size(), what, "texture");
    }

private:
    const tinygltf::Model& mModel;
    const std::string& mFile;
};

void checkBuffersAndViews(const tinygltf::Model& model, const std::string& file) {
    for (int v = 0; v < static_cast<int>(model.bufferViews.size()); ++v) {
        const tinygltf::BufferView& view = model.bufferViews[v];
        const std::string where = element("bufferViews", v);
        RefChecker(model, file).check(view.buffer, model.buffers.size(), where + ".buffer", "buffer", false);
        const std::uint64_t size = model.buffers[view.buffer].data.size();
        if (view.byteLength == 0) fail(file, where + ".byteLength", "is 0");
        if (view.byteOffset > size || view.byteLength > size - view.byteOffset) {
            fail(file, where, "bytes " + std::to_string(view.byteOffset) + ".." +
                                  std::to_string(std::uint64_t(view.byteOffset) + view.byteLength) +
                                  " run past the end of buffer " + std::to_string(view.buffer) + " (" +
                                  std::to_string(size) + " bytes)");
        }
        if (view.byteStride != 0 && (view.byteStride < 4 || view.byteStride > 252 || view.byteStride % 4 != 0)) {
            fail(file, where + ".byteStride", std::to_string(view.byteStride) + " is not a multiple of 4 in 4..252");
        }
    }
}

void checkAccessor(const tinygltf::Model& model, int a, const std::string& file, std::uint64_t allowance) {
    const tinygltf::Accessor& accessor = model.accessors[a];
    const std::string where = element("accessors", a);
    const std::uint64_t elementSize = accessorElementSize(accessor);
    if (componentSize(accessor.componentType) == 0) {
        fail(file, where + ".componentType", std::to_string(accessor.componentType) + " is not a glTF component type");
    }
    if (elementSize == 0) fail(file, where + ".type", "unknown accessor type");
    if (accessor.count == 0) fail(file, where + ".count", "is 0");
    if (accessor.bufferView >= 0) {
        RefChecker(model, file).check(accessor.bufferView, model.bufferViews.size(), where + ".bufferView",
                                      "bufferView");
        const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
        const std::uint64_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
        if (stride < elementSize) {
            fail(file, where, "bufferView " + std::to_string(accessor.bufferView) + " byteStride " +
                                  std::to_string(stride) + " is smaller than an element (" +
                                  std::to_string(elementSize) + " bytes)");
        }
        // count ≤ byteLength keeps (count - 1) * stride from overflowing.
        const std::uint64_t count = accessor.count;
        if (count > view.byteLength || accessor.byteOffset > view.byteLength ||
            (count - 1) * stride + elementSize > view.byteLength - accessor.byteOffset) {
            fail(file, where, std::to_string(count) + " elements of " + std::to_string(elementSize) +
                                  " bytes (stride " + std::to_string(stride) + ") from byte " +
                                  std::to_string(accessor.byteOffset) + " run past bufferView " +
                                  std::to_string(accessor.bufferView) + " (" + std::to_string(view.byteLength) +
                                  " bytes)");
        }
        if (accessor.byteOffset % componentSize(accessor.componentType) != 0) {
            fail(file, where + ".byteOffset", std::to_string(accessor.byteOffset) + " is not aligned to its component size");
        }
        if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
            // Non-finite values poison bounds and the simplifier; refuse them wherever they are.
            const unsigned char* base =
                model.buffers[view.buffer].data.data() + view.byteOffset + accessor.byteOffset;
            const int components = accessorComponentCount(accessor);
            for (std::uint64_t e = 0; e < count; ++e) {
                for (int c = 0; c < components; ++c) {
                    float value;
                    std::memcpy(&value, base + e * stride + 4u * c, 4);
                    if (!std::isfinite(value)) fail(file, where, "element " + std::to_string(e) + " is not finite");
                }
            }
        }
    } else if (accessor.bufferView != -1) {
        fail(file, where + ".bufferView", std::to_string(accessor.bufferView) + " does not exist");
    } else if (accessor.byteOffset != 0) {
        fail(file, where + ".byteOffset", "is set but the accessor has no bufferView");
    } else if (accessor.count > allowance / elementSize) {
        // All zeros: nothing in the file backs the allocation, so cap it by the file's data.
        fail(file, where, "count " + std::to_string(accessor.count) + " without a bufferView would decode to more bytes (" +
                              std::to_string(accessor.count * elementSize) + ") than the file's buffers hold");
    }
    if (!accessor.sparse.isSparse) return;
    const auto& sparse = accessor.sparse;
    const std::string sw = where + ".sparse";
    if (sparse.count <= 0 || static_cast<std::uint64_t>(sparse.count) > accessor.count) {
        fail(file, sw + ".count", std::to_string(sparse.count) + " is not in 1.." + std::to_string(accessor.count));
    }
    const std::uint64_t indexSize = componentSize(sparse.indices.componentType);
    if (indexSize == 0 || sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
        sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_INT ||
        sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        fail(file, sw + ".indices.componentType", "must be an unsigned byte, short or int");
    }
    struct Part {
        int view;
        int offset;
        std::uint64_t bytes;
        const char* name;
    };
    const Part parts[2] = {{sparse.indices.bufferView, sparse.indices.byteOffset, indexSize * sparse.count, ".indices"},
                           {sparse.values.bufferView, sparse.values.byteOffset, elementSize * sparse.count, ".values"}};
    for (const Part& part : parts) {
        RefChecker(model, file).check(part.view, model.bufferViews.size(), sw + part.name + ".bufferView",
                                      "bufferView", false);
        const std::uint64_t length = model.bufferViews[part.view].byteLength;
        if (part.offset < 0 || static_cast<std::uint64_t>(part.offset) > length || part.bytes > length - part.offset) {
            fail(file, sw + part.name, std::to_string(part.bytes) + " bytes from byte " + std::to_string(part.offset) +
                                           " run past bufferView " + std::to_string(part.view));
        }
    }
}

void checkReferences(const tinygltf::Model& model, const std::string& file) {
    RefChecker ref(model, file);
    for (int m = 0; m < static_cast<int>(model.meshes.size()); ++m) {
        const auto& primitives = model.meshes[m].primitives;
        for (int p = 0; p < static_cast<int>(primitives.size()); ++p) {
            const tinygltf::Primitive& primitive = primitives[p];
            const std::string where = element("meshes", m) + element(".primitives", p);
            for (const auto& [name, accessor] : primitive.attributes) {
                ref.accessor(accessor, where + ".attributes." + name, false);
            }
            ref.accessor(primitive.indices, where + ".indices");
            ref.check(primitive.material, model.materials.size(), where + ".material", "material");
            for (std::size_t t = 0; t < primitive.targets.size(); ++t) {
                for (const auto& [name, accessor] : primitive.targets[t]) {
                    ref.accessor(accessor, where + element(".targets", int(t)) + "." + name, false);
                }
            }
        }
    }
    for (int m = 0; m < static_cast<int>(model.materials.size()); ++m) {
        const tinygltf::Material& material = model.materials[m];
        const std::string where = element("materials", m);
        ref.texture(material.pbrMetallicRoughness.baseColorTexture, where + ".pbrMetallicRoughness.baseColorTexture");
        ref.texture(material.pbrMetallicRoughness.metallicRoughnessTexture,
                    where + ".pbrMetallicRoughness.metallicRoughnessTexture");
        ref.check(material.normalTexture.index, model.textures.size(), where + ".normalTexture", "texture");
        ref.check(material.occlusionTexture.index, model.textures.size(), where + ".occlusionTexture", "texture");
        ref.texture(material.emissiveTexture, where + ".emissiveTexture");
    }
    for (int t = 0; t < static_cast<int>(model.textures.size()); ++t) {
        ref.check(model.textures[t].source, model.images.size(), element("textures", t) + ".source", "image");
        ref.check(model.textures[t].sampler, model.samplers.size(), element("textures", t) + ".sampler", "sampler");
    }
    for (int i = 0; i < static_cast<int>(model.images.size()); ++i) {
        ref.check(model.images[i].bufferView, model.bufferViews.size(), element("images", i) + ".bufferView",
                  "bufferView");
    }
    for (int s = 0; s < static_cast<int>(model.skins.size()); ++s) {
        const tinygltf::Skin& skin = model.skins[s];
        const std::string where = element("skins", s);
        ref.accessor(skin.inverseBindMatrices, where + ".inverseBindMatrices");
        if (skin.skeleton != -1) ref.node(skin.skeleton, where + ".skeleton");
        for (std::size_t j = 0; j < skin.joints.size(); ++j) ref.node(skin.joints[j], where + element(".joints", int(j)));
    }
    for (int a = 0; a < static_cast<int>(model.animations.size()); ++a) {
        const tinygltf::Animation& animation = model.animations[a];
        const std::string where = element("animations", a);
        for (int c = 0; c < static_cast<int>(animation.channels.size()); ++c) {
            const auto& channel = animation.channels[c];
            ref.check(channel.sampler, animation.samplers.size(), where + element(".channels", c) + ".sampler",
                      "sampler", false);
            if (channel.target_node != -1) ref.node(channel.target_node, where + element(".channels", c) + ".target.node");
        }
        for (int s = 0; s < static_cast<int>(animation.samplers.size()); ++s) {
            ref.accessor(animation.samplers[s].input, where + element(".samplers", s) + ".input", false);
            ref.accessor(animation.samplers[s].output, where + element(".samplers", s) + ".output", false);
        }
    }
    for (int n = 0; n < static_cast<int>(model.nodes.size()); ++n) {
        const tinygltf::Node& node = model.nodes[n];
        const std::string where = element("nodes", n);
        ref.check(node.mesh, model.meshes.size(), where + ".mesh", "mesh");
        ref.check(node.camera, model.cameras.size(), where + ".camera", "camera");
        ref.check(node.skin, model.skins.size(), where + ".skin", "skin");
        for (std::size_t c = 0; c < node.children.size(); ++c) ref.node(node.children[c], where + element(".children", int(c)));
        if (!node.matrix.empty() && node.matrix.size() != 16) fail(file, where + ".matrix", "needs 16 numbers");
        if (!node.translation.empty() && node.translation.size() != 3) fail(file, where + ".translation", "needs 3 numbers");
        if (!node.scale.empty() && node.scale.size() != 3) fail(file, where + ".scale", "needs 3 numbers");
        if (!node.rotation.empty() && node.rotation.size() != 4) fail(file, where + ".rotation", "needs 4 numbers");
        for (const auto* values : {&node.matrix, &node.translation, &node.scale, &node.rotation}) {
            for (double v : *values) {
                if (!std::isfinite(v)) fail(file, where, "transform has a non-finite number");
            }
        }
    }
    for (int s = 0; s < static_cast<int>(model.scenes.size()); ++s) {
        const auto& roots = model.scenes[s].nodes;
        for (std::size_t r = 0; r < roots.size(); ++r) ref.node(roots[r], element("scenes", s) + element(".nodes", int(r)));
    }
    if (model.defaultScene != -1) ref.check(model.defaultScene, model.scenes.size(), "scene", "scene", false);
}

// Attribute formats, equal counts and index ranges of every primitive, drawn or not.
void checkPrimitives(const tinygltf::Model& model, const std::string& file) {
    for (int m = 0; m < static_cast<int>(model.meshes.size()); ++m) {
        const auto& primitives = model.meshes[m].primitives;
        for (int p = 0; p < static_cast<int>(primitives.size()); ++p) {
            const tinygltf::Primitive& primitive = primitives[p];
            const std::string where = element("meshes", m) + element(".primitives", p);
            std::uint64_t vertexCount = 0;
            bool haveCount = false;
            for (const auto& [name, index] : primitive.attributes) {
                const tinygltf::Accessor& accessor = model.accessors[index];
                const std::string what = where + ".attributes." + name;
                if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT ||
                    accessor.componentType == TINYGLTF_COMPONENT_TYPE_INT) {
                    fail(file, what, "vertex attributes cannot use 32-bit integer components");
                }
                const bool vec3 = name == "POSITION" || name == "NORMAL";
                const bool vec2 = name.rfind("TEXCOORD_", 0) == 0;
                if ((vec3 && accessor.type != TINYGLTF_TYPE_VEC3) || (vec2 && accessor.type != TINYGLTF_TYPE_VEC2)) {
                    fail(file, what, std::string("must be ") + (vec3 ? "VEC3" : "VEC2") + " (" + element("accessors", index) + ")");
                }
                if (haveCount && accessor.count != vertexCount) {
                    fail(file, what, "count " + std::to_string(accessor.count) + " differs from the other attributes (" +
                                         std::to_string(vertexCount) + ")");
                }
                vertexCount = accessor.count;
                haveCount = true;
            }
            if (primitive.indices < 0 || !haveCount) continue;
            const std::vector<std::uint32_t> indices = readIndices(model, primitive.indices, file, where + ".indices");
            const int type = model.accessors[primitive.indices].componentType;
            const std::uint32_t restart = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 0xFFu
                                          : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xFFFFu
                                                                                           : 0xFFFFFFFFu;
            for (std::uint32_t index : indices) {
                if (index == restart) {
                    fail(file, where + ".indices", "index " + std::to_string(index) +
                                                       " is the primitive-restart value, which glTF forbids");
                }
                if (index >= vertexCount) {
                    fail(file, where + ".indices",
                         "index " + std::to_string(index) + " >= vertex count " + std::to_string(vertexCount));
                }
            }
        }
    }
}

// The scene walks (gltf_scene_builder.cpp) recurse once per hierarchy level; real models nest
// a few dozen levels, so this bound keeps a hostile file far from the stack's end.
constexpr int kMaxNodeDepth = 1024;

// Parents, then cycles: with at most one parent per node, a loop is a walk up the parents
// that comes back to where it started. Then depths, bounded by kMaxNodeDepth.
std::vector<int> checkNodeGraph(const tinygltf::Model& model, const std::string& file) {
    const int count = static_cast<int>(model.nodes.size());
    std::vector<int> parent(count, -1);
    for (int n = 0; n < count; ++n) {
        for (int child : model.nodes[n].children) {
            if (child == n) fail(file, element("nodes", n) + ".children", "node " + std::to_string(n) + " is its own child (node loop)");
            if (parent[child] != -1) {
                fail(file, element("nodes", n) + ".children",
                     "node " + std::to_string(child) + " already has parent node " + std::to_string(parent[child]) +
                         " (a node may have one parent)");
            }
            parent[child] = n;
        }
    }
    std::vector<int> state(count, 0);  // 0 unknown, 1 on the current walk, 2 reaches a root
    for (int n = 0; n < count; ++n) {
        std::vector<int> walk;
        int at = n;
        while (at != -1 && state[at] == 0) {
            state[at] = 1;
            walk.push_back(at);
            at = parent[at];
        }
        if (at != -1 && state[at] == 1) {
            fail(file, element("nodes", at), "node loop: node " + std::to_string(at) + " is its own ancestor");
        }
        for (int w : walk) state[w] = 2;
    }
    std::vector<int> depth(count, -1);  // roots 0; filled walking up to the nearest known depth
    for (int n = 0; n < count; ++n) {
        std::vector<int> walk;
        int at = n;
        while (at != -1 && depth[at] == -1) {
            walk.push_back(at);
            at = parent[at];
        }
        int d = at == -1 ? -1 : depth[at];
        for (auto it = walk.rbegin(); it != walk.rend(); ++it) {
            depth[*it] = ++d;
            if (d > kMaxNodeDepth) {
                fail(file, element("nodes", *it),
                     "node hierarchy nested deeper than " + std::to_string(kMaxNodeDepth) + " levels");
            }
        }
    }
    for (int s = 0; s < static_cast<int>(model.scenes.size()); ++s) {
        const auto& roots = model.scenes[s].nodes;
        std::set<int> seen;
        for (std::size_t r = 0; r < roots.size(); ++r) {
            const std::string where = element("scenes", s) + element(".nodes", int(r));
            if (!seen.insert(roots[r]).second) fail(file, where, "node " + std::to_string(roots[r]) + " is listed twice");
        }
    }
    return parent;
}

// MSFT_lod "ids" as integers; `where` names the extension.
std::vector<int> lodIds(const tinygltf::ExtensionMap& extensions, const std::string& file, const std::string& where) {
    auto found = extensions.find("MSFT_lod");
    if (found == extensions.end()) return {};
    const tinygltf::Value& ids = found->second.Get("ids");
    if (!ids.IsArray() || ids.ArrayLen() == 0) fail(file, where + ".ids", "must be a non-empty array of indices");
    std::vector<int> result;
    for (std::size_t i = 0; i < ids.ArrayLen(); ++i) {
        const tinygltf::Value& id = ids.Get(int(i));
        const double value = id.IsNumber() ? id.GetNumberAsDouble() : -1.0;
        if (!id.IsNumber() || value != std::floor(value) || value < 0 || value > std::numeric_limits<int>::max()) {
            fail(file, where + element(".ids", int(i)), "is not an index");
        }
        result.push_back(static_cast<int>(value));
    }
    return result;
}

bool isAncestor(const std::vector<int>& parent, int ancestor, int node) {
    for (int at = parent[node]; at != -1; at = parent[at]) {
        if (at == ancestor) return true;
    }
    return false;
}

void checkLods(const tinygltf::Model& model, const std::string& file, ModelGraph& graph) {
    const int count = static_cast<int>(model.nodes.size());
    graph.nodeLods.assign(count, {});
    graph.lodLevelOf.assign(count, -1);
    for (int n = 0; n < count; ++n) {
        graph.nodeLods[n] = lodIds(model.nodes[n].extensions, file, element("nodes", n) + ".extensions.MSFT_lod");
    }
    for (int n = 0; n < count; ++n) {
        const auto& ids = graph.nodeLods[n];
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const std::string where = element("nodes", n) + ".extensions.MSFT_lod" + element(".ids", int(i));
            const int id = ids[i];
            if (id >= count) fail(file, where, "node " + std::to_string(id) + " does not exist (the file has " + std::to_string(count) + ")");
            if (id == n) fail(file, where, "node " + std::to_string(id) + " is the level-0 node itself");
            if (isAncestor(graph.parent, id, n)) fail(file, where, "node " + std::to_string(id) + " is an ancestor of node " + std::to_string(n));
            if (isAncestor(graph.parent, n, id)) fail(file, where, "node " + std::to_string(id) + " is a descendant of node " + std::to_string(n));
            if (!graph.nodeLods[id].empty()) {
                fail(file, where, "node " + std::to_string(id) + " has its own MSFT_lod (nested or looping LOD chains)");
            }
            if (graph.lodLevelOf[id] != -1) {
                fail(file, where, "node " + std::to_string(id) + " is already a level of node " + std::to_string(graph.lodLevelOf[id]));
            }
            graph.lodLevelOf[id] = n;
        }
    }
    // A level node below another chain's level-0 node, or nested in another level, would be
    // drawn twice: refuse it rather than guess.
    for (int n = 0; n < count; ++n) {
        if (graph.lodLevelOf[n] == -1) continue;
        for (int at = graph.parent[n]; at != -1; at = graph.parent[at]) {
            if (graph.lodLevelOf[at] != -1) {
                fail(file, element("nodes", graph.lodLevelOf[n]) + ".extensions.MSFT_lod",
                     "level node " + std::to_string(n) + " is inside level node " + std::to_string(at));
            }
        }
    }
    const int materials = static_cast<int>(model.materials.size());
    graph.materialLods.assign(materials, {});
    for (int m = 0; m < materials; ++m) {
        graph.materialLods[m] = lodIds(model.materials[m].extensions, file, element("materials", m) + ".extensions.MSFT_lod");
    }
    for (int m = 0; m < materials; ++m) {
        const auto& ids = graph.materialLods[m];
        for (std::size_t i = 0; i < ids.size(); ++i) {
            const std::string where = element("materials", m) + ".extensions.MSFT_lod" + element(".ids", int(i));
            if (ids[i] >= materials) fail(file, where, "material " + std::to_string(ids[i]) + " does not exist");
            if (ids[i] == m) fail(file, where, "material " + std::to_string(ids[i]) + " is the level-0 material itself");
            if (!graph.materialLods[ids[i]].empty()) {
                fail(file, where, "material " + std::to_string(ids[i]) + " has its own MSFT_lod (nested or looping LOD chains)");
            }
        }
    }
}

}  // namespace

std::uint64_t accessorElementSize(const tinygltf::Accessor& accessor) {
    return componentSize(accessor.componentType) * static_cast<std::uint64_t>(accessorComponentCount(accessor));
}

int accessorComponentCount(const tinygltf::Accessor& accessor) {
    switch (accessor.type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
    }
}

bool isUnderstoodExtension(const std::string& name) {
    // Decoded before validation (gltf_meshopt.cpp, gltf_draco.cpp, WebP in
    // gltf_materials_views.cpp), read by the loader, or drawn by the renderer; the
    // specular-glossiness model is approximated by its diffuse color.
    static const std::set<std::string> kUnderstood = {
        "KHR_mesh_quantization", "KHR_materials_unlit",        "MSFT_lod",
        "KHR_materials_pbrSpecularGlossiness", "EXT_meshopt_compression", "KHR_draco_mesh_compression",
        "EXT_texture_webp",      "KHR_texture_transform",      "KHR_materials_emissive_strength"};
    return kUnderstood.count(name) != 0;
}

ModelGraph validateModel(const tinygltf::Model& model, const std::string& file, std::uint64_t decodedBytesAllowance) {
    const std::string& version = model.asset.version;
    if (version.size() < 3 || version.compare(0, 2, "2.") != 0) {
        fail(file, "asset.version", "'" + version + "' is not glTF 2.x");
    }
    // Extensions we either implement or can safely approximate; any other required one
    // changes the meaning of the data (e.g. Draco-compressed accessors read as zeros).
    for (const std::string& name : model.extensionsRequired) {
        if (!isUnderstoodExtension(name)) fail(file, "extensionsRequired", name + " is not supported");
    }
    checkBuffersAndViews(model, file);
    for (int a = 0; a < static_cast<int>(model.accessors.size()); ++a) checkAccessor(model, a, file, decodedBytesAllowance);
    checkReferences(model, file);
    checkPrimitives(model, file);
    ModelGraph graph;
    graph.parent = checkNodeGraph(model, file);
    checkLods(model, file, graph);
    return graph;
}

}  // namespace lodopt::scenes::gltf_detail
