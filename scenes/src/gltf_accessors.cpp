// Accessor decoding and primitive assembly for the glTF loader.
//
// Every accessor was range-checked by validateModel(), so reads here index without further
// bounds checks; values are still checked (non-finite floats, indices past the vertex count).
// Component conversion follows the glTF 2.0 spec §3.11 (normalized integers) and
// KHR_mesh_quantization (any integer type for positions, normals and texture coordinates).
#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gltf_detail.hpp"

namespace lodopt::scenes::gltf_detail {

namespace {

template <typename T>
T load(const unsigned char* at) {
    T value;
    std::memcpy(&value, at, sizeof(T));
    return value;
}

float componentAsFloat(const unsigned char* at, int componentType, bool normalized) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(at);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        float v = load<std::int8_t>(at);
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        float v = load<std::uint8_t>(at);
        return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        float v = load<std::int16_t>(at);
        return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        float v = load<std::uint16_t>(at);
        return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_INT: return static_cast<float>(load<std::int32_t>(at));
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return static_cast<float>(load<std::uint32_t>(at));
    default: return 0.0f;
    }
}

std::uint32_t componentAsIndex(const unsigned char* at, int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<std::uint8_t>(at);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<std::uint16_t>(at);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<std::uint32_t>(at);
    default: return 0;
    }
}

// Start of element 0 and the stride, for an accessor validated to have a bufferView.
const unsigned char* elementBase(const tinygltf::Model& model, const tinygltf::Accessor& accessor,
                                 std::uint64_t& stride) {
    const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
    stride = view.byteStride != 0 ? view.byteStride : accessorElementSize(accessor);
    return model.buffers[view.buffer].data.data() + view.byteOffset + accessor.byteOffset;
}

const unsigned char* viewBase(const tinygltf::Model& model, int view, int offset) {
    const tinygltf::BufferView& bufferView = model.bufferViews[view];
    return model.buffers[bufferView.buffer].data.data() + bufferView.byteOffset + offset;
}

}  // namespace

std::vector<float> readFloats(const tinygltf::Model& model, int index, int components, const std::string& file,
                              const std::string& what) {
    const tinygltf::Accessor& accessor = model.accessors[index];
    const std::string where = what + " (" + element("accessors", index) + ")";
    if (accessorComponentCount(accessor) != components || accessor.type == TINYGLTF_TYPE_MAT2) {
        fail(file, where, "expected " + std::string(components == 1 ? "SCALAR" : "VEC" + std::to_string(components)) +
                              " elements, got type " + std::to_string(accessor.type));
    }
    const std::uint64_t componentBytes = componentSize(accessor.componentType);
    std::vector<float> values(accessor.count * std::size_t(components), 0.0f);
    if (accessor.bufferView >= 0) {
        std::uint64_t stride = 0;
        const unsigned char* base = elementBase(model, accessor, stride);
        for (std::size_t e = 0; e < accessor.count; ++e) {
            const unsigned char* at = base + e * stride;
            for (int c = 0; c < components; ++c) {
                values[e * components + c] = componentAsFloat(at + c * componentBytes, accessor.componentType, accessor.normalized);
            }
        }
    }
    if (accessor.sparse.isSparse) {
        const auto& sparse = accessor.sparse;
        const unsigned char* indices = viewBase(model, sparse.indices.bufferView, sparse.indices.byteOffset);
        const unsigned char* replacements = viewBase(model, sparse.values.bufferView, sparse.values.byteOffset);
        const std::uint64_t indexBytes = componentSize(sparse.indices.componentType);
        for (int s = 0; s < sparse.count; ++s) {
            const std::uint32_t target = componentAsIndex(indices + s * indexBytes, sparse.indices.componentType);
            if (target >= accessor.count) {
                fail(file, where + ".sparse.indices", "index " + std::to_string(target) + " >= count " + std::to_string(accessor.count));
            }
            for (int c = 0; c < components; ++c) {
                values[std::size_t(target) * components + c] = componentAsFloat(
                    replacements + (s * components + c) * componentBytes, accessor.componentType, accessor.normalized);
            }
        }
    }
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) {
            fail(file, where, "element " + std::to_string(i / components) + " is not finite");
        }
    }
    return values;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& file,
                                       const std::string& what) {
    const tinygltf::Accessor& accessor = model.accessors[index];
    if (accessor.type != TINYGLTF_TYPE_SCALAR ||
        (accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
        fail(file, what + " (" + element("accessors", index) + ")",
             "indices must be SCALAR unsigned byte, short or int (componentType " +
                 std::to_string(accessor.componentType) + ")");
    }
    std::vector<std::uint32_t> indices(accessor.count, 0u);
    if (accessor.bufferView >= 0) {
        std::uint64_t stride = 0;
        const unsigned char* base = elementBase(model, accessor, stride);
        for (std::size_t e = 0; e < accessor.count; ++e) indices[e] = componentAsIndex(base + e * stride, accessor.componentType);
    }
    if (accessor.sparse.isSparse) {
        // Rare for indices, but legal. Substituted as integers: a float holds only 24 bits.
        const auto& sparse = accessor.sparse;
        const unsigned char* targets = viewBase(model, sparse.indices.bufferView, sparse.indices.byteOffset);
        const unsigned char* replacements = viewBase(model, sparse.values.bufferView, sparse.values.byteOffset);
        const std::uint64_t targetBytes = componentSize(sparse.indices.componentType);
        const std::uint64_t valueBytes = componentSize(accessor.componentType);
        for (int s = 0; s < sparse.count; ++s) {
            const std::uint32_t target = componentAsIndex(targets + s * targetBytes, sparse.indices.componentType);
            if (target >= accessor.count) {
                fail(file, what + " (" + element("accessors", index) + ").sparse.indices",
                     "index " + std::to_string(target) + " >= count " + std::to_string(accessor.count));
            }
            indices[target] = componentAsIndex(replacements + s * valueBytes, accessor.componentType);
        }
    }
    return indices;
}

namespace {

// Triangle list from a strip or fan (glTF 2.0 spec §3.7.2.1), dropping degenerate
// triangles that strips use as restarts.
std::vector<std::uint32_t> toTriangles(const std::vector<std::uint32_t>& source, int mode) {
    std::vector<std::uint32_t> triangles;
    if (source.size() < 3) return triangles;
    triangles.reserve((source.size() - 2) * 3);
    for (std::size_t i = 0; i + 2 < source.size(); ++i) {
        std::uint32_t a, b, c;
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            a = source[i];
            b = source[i + 1 + (i % 2)];
            c = source[i + 2 - (i % 2)];
        } else {
            a = source[i + 1];
            b = source[i + 2];
            c = source[0];
        }
        if (a == b || b == c || a == c) continue;
        triangles.insert(triangles.end(), {a, b, c});
    }
    return triangles;
}

const char* modeName(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    default: return "unknown";
    }
}

}  // namespace

DecodedPrimitive decodePrimitive(const tinygltf::Model& model, int meshIndex, int primitiveIndex,
                                 const std::string& file, bool skipNonTriangles, std::vector<std::string>* warnings) {
    const tinygltf::Primitive& primitive = model.meshes[meshIndex].primitives[primitiveIndex];
    const std::string where = element("meshes", meshIndex) + element(".primitives", primitiveIndex);
    DecodedPrimitive out;
    out.material = primitive.material;
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        const std::string message = std::to_string(mode) + " (" + modeName(mode) + ") is not a triangle mode";
        if (!skipNonTriangles) fail(file, where + ".mode", message + " (lodopt draws triangles only)");
        if (warnings) warnings->push_back(file + ": " + where + ".mode: " + message + "; primitive skipped");
        out.skipped = true;
        return out;
    }
    auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) {
        // Valid glTF (the primitive is simply not drawn), so a warning, not an error.
        if (warnings) warnings->push_back(file + ": " + where + ": no POSITION attribute; primitive skipped");
        out.skipped = true;
        return out;
    }
    std::vector<float> positions = readFloats(model, position->second, 3, file, where + ".attributes.POSITION");
    const std::size_t vertexCount = positions.size() / 3;
    out.positions.resize(vertexCount);
    std::memcpy(out.positions.data(), positions.data(), positions.size() * sizeof(float));

    auto readAttribute = [&](const char* name, int components) {
        auto found = primitive.attributes.find(name);
        if (found == primitive.attributes.end()) return std::vector<float>();
        const std::string what = where + ".attributes." + name;
        std::vector<float> values = readFloats(model, found->second, components, file, what);
        if (values.size() / components != vertexCount) {
            fail(file, what, "count " + std::to_string(values.size() / components) + " != POSITION count " +
                                 std::to_string(vertexCount));
        }
        return values;
    };
    std::vector<float> normals = readAttribute("NORMAL", 3);
    if (!normals.empty()) {
        out.normals.resize(vertexCount);
        std::memcpy(out.normals.data(), normals.data(), normals.size() * sizeof(float));
    }
    auto copyInto = [&](auto& target, const std::vector<float>& values) {
        if (values.empty()) return;
        target.resize(vertexCount);
        std::memcpy(target.data(), values.data(), values.size() * sizeof(float));
    };
    copyInto(out.uvs, readAttribute("TEXCOORD_0", 2));
    copyInto(out.uvs1, readAttribute("TEXCOORD_1", 2));
    copyInto(out.tangents, readAttribute("TANGENT", 4));
    auto color = primitive.attributes.find("COLOR_0");
    if (color != primitive.attributes.end() && color->second >= 0 &&
        color->second < static_cast<int>(model.accessors.size())) {
        // COLOR_0 is VEC3 or VEC4 (spec §3.7.2.1); VEC3 colors are opaque.
        const bool rgb = model.accessors[color->second].type == TINYGLTF_TYPE_VEC3;
        const std::vector<float> values = readAttribute("COLOR_0", rgb ? 3 : 4);
        out.colors.resize(vertexCount);
        for (std::size_t v = 0; v < vertexCount; ++v) {
            out.colors[v] = rgb ? glm::vec4(values[3 * v], values[3 * v + 1], values[3 * v + 2], 1.0f)
                                : glm::vec4(values[4 * v], values[4 * v + 1], values[4 * v + 2], values[4 * v + 3]);
        }
    }

    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0) {
        indices = readIndices(model, primitive.indices, file, where + ".indices");
        for (std::uint32_t index : indices) {
            if (index >= vertexCount) {
                fail(file, where + ".indices", "index " + std::to_string(index) + " >= vertex count " + std::to_string(vertexCount));
            }
        }
    } else {
        indices.resize(vertexCount);
        for (std::size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (indices.size() % 3 != 0) {
            fail(file, where + (primitive.indices >= 0 ? ".indices" : ".attributes.POSITION"),
                 std::to_string(indices.size()) + " vertices is not a multiple of 3 for TRIANGLES");
        }
        out.indices = std::move(indices);
    } else {
        out.indices = toTriangles(indices, mode);
    }
    return out;
}

glm::mat4 localTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 matrix = glm::make_mat4(node.matrix.data());  // column-major, as glTF stores it
        return glm::mat4(matrix);
    }
    glm::dvec3 translation(0.0), scale(1.0);
    glm::dquat rotation(1.0, 0.0, 0.0, 0.0);
    if (node.translation.size() == 3) translation = glm::make_vec3(node.translation.data());
    if (node.scale.size() == 3) scale = glm::make_vec3(node.scale.data());
    if (node.rotation.size() == 4) {
        // glTF stores x, y, z, w; glm's constructor takes w first.
        rotation = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double length = glm::length(rotation);
        rotation = length > 0.0 ? rotation / length : glm::dquat(1.0, 0.0, 0.0, 0.0);
    }
    glm::dmat4 matrix = glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) *
                        glm::scale(glm::dmat4(1.0), scale);
    return glm::mat4(matrix);
}

}  // namespace lodopt::scenes::gltf_detail
