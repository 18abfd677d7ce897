// EXT_meshopt_compression (Khronos glTF extension registry, EXT_meshopt_compression/README.md):
// a bufferView's extension names compressed bytes (buffer, byteOffset, byteLength) and how to
// decode them (mode, count, byteStride, filter) with meshoptimizer's decoders; the view's own
// buffer is then often a "fallback" buffer without data. Decoded views move to one new buffer,
// so that everything after the pre-pass reads plain bufferViews.
#include <algorithm>
#include <cstring>

#include <meshoptimizer.h>

#include "gltf_detail.hpp"

namespace lodopt::scenes::gltf_detail {

namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";

// The decoders' contracts (meshoptimizer.h): these are asserts there, so they are checked here
// before any call, with the extension's rules (strides and filters per mode).
void checkModeAndFilter(const std::string& mode, const std::string& filter, std::uint64_t count,
                        std::uint64_t stride, const std::string& file, const std::string& where) {
    if (mode == "ATTRIBUTES") {
        if (stride % 4 != 0 || stride > 256) {
            fail(file, where + ".byteStride", std::to_string(stride) + " must be a multiple of 4 in 4..256 for ATTRIBUTES");
        }
        if (filter == "OCTAHEDRAL" && stride != 4 && stride != 8) {
            fail(file, where + ".byteStride", std::to_string(stride) + " must be 4 or 8 for the OCTAHEDRAL filter");
        }
        if (filter == "QUATERNION" && stride != 8) {
            fail(file, where + ".byteStride", std::to_string(stride) + " must be 8 for the QUATERNION filter");
        }
        if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL") {
            fail(file, where + ".filter", "'" + filter + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
        }
        return;
    }
    if (mode != "TRIANGLES" && mode != "INDICES") {
        fail(file, where + ".mode", "'" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
    }
    if (stride != 2 && stride != 4) fail(file, where + ".byteStride", std::to_string(stride) + " must be 2 or 4 for " + mode);
    if (filter != "NONE") fail(file, where + ".filter", "must be NONE for " + mode);
    if (mode == "TRIANGLES" && count % 3 != 0) {
        fail(file, where + ".count", std::to_string(count) + " is not a multiple of 3 for TRIANGLES");
    }
}

std::string stringProperty(const tinygltf::Value& object, const char* key, const char* fallback, const std::string& file,
                           const std::string& where) {
    if (!object.Has(key)) {
        if (fallback) return fallback;
        fail(file, where + "." + key, "is missing");
    }
    const tinygltf::Value& value = object.Get(key);
    if (!value.IsString()) fail(file, where + "." + key, "is not a string");
    return value.Get<std::string>();
}

}  // namespace

void decodeMeshoptViews(tinygltf::Model& model, const std::string& file, const std::vector<int>& fallbackBuffers,
                        std::uint64_t& byteBudget) {
    const auto isFallback = [&](int buffer) {
        return std::find(fallbackBuffers.begin(), fallbackBuffers.end(), buffer) != fallbackBuffers.end();
    };
    std::vector<unsigned char> decoded;
    const int decodedBuffer = static_cast<int>(model.buffers.size());
    for (int v = 0; v < static_cast<int>(model.bufferViews.size()); ++v) {
        tinygltf::BufferView& view = model.bufferViews[v];
        const auto extension = view.extensions.find(kMeshopt);
        if (extension == view.extensions.end()) {
            if (isFallback(view.buffer)) {
                fail(file, element("bufferViews", v),
                     "lies in buffers[" + std::to_string(view.buffer) + "], an " + kMeshopt +
                         " fallback buffer without data, and is not compressed");
            }
            continue;
        }
        const std::string where = element("bufferViews", v) + ".extensions." + kMeshopt;
        const tinygltf::Value& meshopt = extension->second;
        if (!meshopt.IsObject()) fail(file, where, "is not an object");
        const std::uint64_t bufferIndex = requiredExtensionInteger(meshopt, "buffer", 0x7FFFFFFF, file, where);
        const std::uint64_t offset = extensionInteger(meshopt, "byteOffset", 0, ~std::uint64_t(0) >> 12, file, where);
        const std::uint64_t length = requiredExtensionInteger(meshopt, "byteLength", ~std::uint64_t(0) >> 12, file, where);
        const std::uint64_t stride = requiredExtensionInteger(meshopt, "byteStride", 256, file, where);
        const std::uint64_t count = requiredExtensionInteger(meshopt, "count", ~std::uint64_t(0) >> 12, file, where);
        const std::string mode = stringProperty(meshopt, "mode", nullptr, file, where);
        const std::string filter = stringProperty(meshopt, "filter", "NONE", file, where);
        if (bufferIndex >= model.buffers.size()) {
            fail(file, where + ".buffer", "buffer " + std::to_string(bufferIndex) + " does not exist (the file has " +
                                              std::to_string(model.buffers.size()) + ")");
        }
        if (isFallback(static_cast<int>(bufferIndex))) {
            fail(file, where + ".buffer", "buffer " + std::to_string(bufferIndex) + " is a fallback buffer without data");
        }
        const std::vector<unsigned char>& source = model.buffers[bufferIndex].data;
        if (offset > source.size() || length > source.size() - offset) {
            fail(file, where, "bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                                  " run past the end of buffer " + std::to_string(bufferIndex) + " (" +
                                  std::to_string(source.size()) + " bytes)");
        }
        if (count == 0) fail(file, where + ".count", "is 0");
        if (stride == 0) fail(file, where + ".byteStride", "is 0");
        checkModeAndFilter(mode, filter, count, stride, file, where);
        if (mode == "ATTRIBUTES" && view.byteStride != 0 && std::uint64_t(view.byteStride) != stride) {
            fail(file, where + ".byteStride", std::to_string(stride) + " differs from the bufferView's byteStride " +
                                                  std::to_string(view.byteStride));
        }
        // count and stride are bounded above, so the product cannot overflow.
        const std::uint64_t size = count * stride;
        if (size > byteBudget) {
            fail(file, where, "decodes to " + std::to_string(size) + " bytes, over what the byte limit leaves (" +
                                  std::to_string(byteBudget) + ")");
        }
        byteBudget -= size;
        const std::size_t at = (decoded.size() + 15) & ~std::size_t(15);
        decoded.resize(at + size);
        unsigned char* target = decoded.data() + at;
        const unsigned char* compressed = source.data() + offset;
        int result = 0;
        if (mode == "ATTRIBUTES") {
            result = meshopt_decodeVertexBuffer(target, count, stride, compressed, length);
            if (result == 0 && filter == "OCTAHEDRAL") meshopt_decodeFilterOct(target, count, stride);
            if (result == 0 && filter == "QUATERNION") meshopt_decodeFilterQuat(target, count, stride);
            if (result == 0 && filter == "EXPONENTIAL") meshopt_decodeFilterExp(target, count, stride);
        } else if (mode == "TRIANGLES") {
            result = meshopt_decodeIndexBuffer(target, count, stride, compressed, length);
        } else {
            result = meshopt_decodeIndexSequence(target, count, stride, compressed, length);
        }
        if (result != 0) {
            fail(file, where, mode + " data of " + std::to_string(length) + " bytes cannot be decoded (meshoptimizer error " +
                                  std::to_string(result) + ": truncated, corrupt or a newer format)");
        }
        view.buffer = decodedBuffer;
        view.byteOffset = at;
        view.byteLength = size;
    }
    if (decoded.empty()) return;
    tinygltf::Buffer buffer;
    buffer.name = "decoded EXT_meshopt_compression views";
    buffer.data = std::move(decoded);
    model.buffers.push_back(std::move(buffer));
}

}  // namespace lodopt::scenes::gltf_detail
