// KHR_draco_mesh_compression (Khronos glTF extension registry,
// KHR_draco_mesh_compression/README.md): a primitive's extension names a bufferView holding a
// Draco mesh and maps attribute semantics to Draco attribute ids; the primitive's own accessors
// declare type, component type and count but usually have no bufferView. Each compressed
// triangle primitive is decoded with Debian's libdraco into new accessors (the declared types,
// 32-bit indices) in one new buffer, so that everything after the pre-pass reads plain glTF.
#include <cstring>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>

#include "gltf_detail.hpp"

namespace lodopt::scenes::gltf_detail {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

std::size_t appendAligned(std::vector<unsigned char>& bytes, std::uint64_t size) {
    const std::size_t at = (bytes.size() + 15) & ~std::size_t(15);
    bytes.resize(at + size);
    return at;
}

// Writes every point's value of `attribute` as `components` values of type T.
template <typename T>
bool convertAttribute(const draco::PointAttribute& attribute, std::uint32_t points, int components, unsigned char* out) {
    T value[16];
    for (std::uint32_t p = 0; p < points; ++p) {
        const draco::AttributeValueIndex index = attribute.mapped_index(draco::PointIndex(p));
        if (index.value() >= attribute.size()) return false;
        if (!attribute.ConvertValue<T>(index, static_cast<int8_t>(components), value)) return false;
        std::memcpy(out + std::size_t(p) * components * sizeof(T), value, components * sizeof(T));
    }
    return true;
}

bool writeAttribute(const draco::PointAttribute& attribute, int componentType, std::uint32_t points, int components,
                    unsigned char* out) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return convertAttribute<float>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_BYTE: return convertAttribute<std::int8_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return convertAttribute<std::uint8_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return convertAttribute<std::int16_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return convertAttribute<std::uint16_t>(attribute, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return convertAttribute<std::uint32_t>(attribute, points, components, out);
    default: return false;
    }
}

int addView(tinygltf::Model& model, int buffer, std::size_t offset, std::uint64_t length) {
    tinygltf::BufferView view;
    view.buffer = buffer;
    view.byteOffset = offset;
    view.byteLength = length;
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size()) - 1;
}

void decodePrimitive(tinygltf::Model& model, int m, int p, const std::string& file, int decodedBuffer,
                     std::vector<unsigned char>& decoded, std::uint64_t& byteBudget) {
    const std::string where = element("meshes", m) + element(".primitives", p) + ".extensions." + kDraco;
    // Copied: the primitive is changed below, and model.accessors grows.
    const tinygltf::Value draco = model.meshes[m].primitives[p].extensions.at(kDraco);
    if (!draco.IsObject()) fail(file, where, "is not an object");
    const int mode = model.meshes[m].primitives[p].mode;
    if (mode != -1 && mode != TINYGLTF_MODE_TRIANGLES) {
        fail(file, where, "compresses a primitive of mode " + std::to_string(mode) + "; lodopt decodes TRIANGLES only");
    }
    const std::uint64_t viewIndex = requiredExtensionInteger(draco, "bufferView", 0x7FFFFFFF, file, where);
    if (viewIndex >= model.bufferViews.size()) {
        fail(file, where + ".bufferView", "bufferView " + std::to_string(viewIndex) + " does not exist (the file has " +
                                              std::to_string(model.bufferViews.size()) + ")");
    }
    const tinygltf::BufferView& view = model.bufferViews[viewIndex];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model.buffers.size())) {
        fail(file, where + ".bufferView", "bufferView " + std::to_string(viewIndex) + " names no buffer");
    }
    const std::vector<unsigned char>& source = model.buffers[view.buffer].data;
    if (view.byteOffset > source.size() || view.byteLength > source.size() - view.byteOffset) {
        fail(file, where + ".bufferView", "bufferView " + std::to_string(viewIndex) + " (bytes " +
                                              std::to_string(view.byteOffset) + ".." +
                                              std::to_string(std::uint64_t(view.byteOffset) + view.byteLength) +
                                              ") runs past the end of buffer " + std::to_string(view.buffer) + " (" +
                                              std::to_string(source.size()) + " bytes)");
    }
    if (!draco.Has("attributes") || !draco.Get("attributes").IsObject()) {
        fail(file, where + ".attributes", "must be an object");
    }
    const tinygltf::Value& attributes = draco.Get("attributes");

    draco::DecoderBuffer input;
    input.Init(reinterpret_cast<const char*>(source.data() + view.byteOffset), view.byteLength);
    draco::Decoder decoder;
    auto result = decoder.DecodeMeshFromBuffer(&input);
    if (!result.ok()) fail(file, where, "Draco data cannot be decoded (" + result.status().error_msg_string() + ")");
    const std::unique_ptr<draco::Mesh> mesh = std::move(result).value();
    const std::uint32_t points = mesh->num_points();
    const std::uint32_t faces = mesh->num_faces();
    if (points == 0 || faces == 0) fail(file, where, "the Draco mesh has no points or no faces");

    for (const std::string& name : attributes.Keys()) {
        const std::string at = where + ".attributes." + name;
        const std::uint64_t id = requiredExtensionInteger(attributes, name.c_str(), 0x7FFFFFFF, file, where + ".attributes");
        auto& primitiveAttributes = model.meshes[m].primitives[p].attributes;
        const auto accessorOf = primitiveAttributes.find(name);
        if (accessorOf == primitiveAttributes.end()) fail(file, at, "the primitive has no attribute " + name);
        const int accessorIndex = accessorOf->second;
        if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model.accessors.size())) {
            fail(file, at, "the primitive's accessor " + std::to_string(accessorIndex) + " does not exist");
        }
        const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
        if (!attribute) fail(file, at, "Draco attribute id " + std::to_string(id) + " is not in the Draco data");
        tinygltf::Accessor accessor = model.accessors[accessorIndex];
        const int components = accessorComponentCount(accessor);
        const std::uint64_t elementSize = accessorElementSize(accessor);
        if (components == 0 || components > 4 || elementSize == 0) {
            fail(file, at, element("accessors", accessorIndex) + " has a type or component type Draco cannot fill");
        }
        const std::uint64_t size = std::uint64_t(points) * elementSize;
        if (size > byteBudget) {
            fail(file, at, "decodes to " + std::to_string(size) + " bytes, over what the byte limit leaves (" +
                               std::to_string(byteBudget) + ")");
        }
        byteBudget -= size;
        const std::size_t offset = appendAligned(decoded, size);
        if (!writeAttribute(*attribute, accessor.componentType, points, components, decoded.data() + offset)) {
            fail(file, at, "Draco values do not convert to " + element("accessors", accessorIndex) + "'s component type");
        }
        accessor.bufferView = addView(model, decodedBuffer, offset, size);
        accessor.byteOffset = 0;
        accessor.count = points;
        accessor.sparse = {};
        model.accessors.push_back(accessor);
        primitiveAttributes[name] = static_cast<int>(model.accessors.size()) - 1;
    }

    const std::uint64_t size = std::uint64_t(faces) * 3 * 4;
    if (size > byteBudget) {
        fail(file, where, "indices decode to " + std::to_string(size) + " bytes, over what the byte limit leaves (" +
                              std::to_string(byteBudget) + ")");
    }
    byteBudget -= size;
    const std::size_t offset = appendAligned(decoded, size);
    for (std::uint32_t f = 0; f < faces; ++f) {
        const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(f));
        for (int corner = 0; corner < 3; ++corner) {
            const std::uint32_t index = face[corner].value();
            if (index >= points) fail(file, where, "face " + std::to_string(f) + " names point " + std::to_string(index));
            std::memcpy(decoded.data() + offset + (std::size_t(f) * 3 + corner) * 4, &index, 4);
        }
    }
    tinygltf::Accessor indices;
    indices.bufferView = addView(model, decodedBuffer, offset, size);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.type = TINYGLTF_TYPE_SCALAR;
    indices.count = std::size_t(faces) * 3;
    model.accessors.push_back(indices);
    tinygltf::Primitive& primitive = model.meshes[m].primitives[p];
    primitive.indices = static_cast<int>(model.accessors.size()) - 1;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.extensions.erase(kDraco);
}

}  // namespace

void decodeDracoPrimitives(tinygltf::Model& model, const std::string& file, std::uint64_t& byteBudget) {
    std::vector<unsigned char> decoded;
    const int decodedBuffer = static_cast<int>(model.buffers.size());
    for (int m = 0; m < static_cast<int>(model.meshes.size()); ++m) {
        for (int p = 0; p < static_cast<int>(model.meshes[m].primitives.size()); ++p) {
            if (model.meshes[m].primitives[p].extensions.count(kDraco) == 0) continue;
            decodePrimitive(model, m, p, file, decodedBuffer, decoded, byteBudget);
        }
    }
    if (decoded.empty()) return;
    tinygltf::Buffer buffer;
    buffer.name = "decoded KHR_draco_mesh_compression primitives";
    buffer.data = std::move(decoded);
    model.buffers.push_back(std::move(buffer));
}

}  // namespace lodopt::scenes::gltf_detail
