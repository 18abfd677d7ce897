// glTF 2.0 loading (Khronos glTF 2.0 specification; MSFT_lod vendor extension) into the
// lodopt scene model: which nodes become objects, where their discrete levels come from,
// materials, textures, cameras and camera paths. Parsing is tinygltf's; validateModel()
// (gltf_validate.cpp) checks the parsed model before anything here indexes it, and
// decodePrimitive() (gltf_accessors.cpp) reads the geometry. docs/gltf.md is the reference.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "gltf_detail.hpp"
#include "gltf_scene_builder.hpp"
#include "scenes/gltf_io.hpp"

namespace lodopt::scenes {

namespace fs = std::filesystem;
using namespace gltf_detail;

namespace {

// Encoded image bytes kept by the deferred image loader: only base-color images are
// decoded, after validation (normal and occlusion maps never are).
struct DeferredImages {
    std::vector<std::vector<unsigned char>> encoded;
    const tinygltf::Model* model = nullptr;  // the model being parsed: its buffers are loaded
};

// tinygltf 2.7 hands an image's bufferView to the loader without checking that the view lies
// inside its buffer (a 728-byte view of a 188-byte buffer was read past the end: fuzzing,
// tests/fuzz/regressions/gltf/), so the range is checked here before any byte is read.
bool imageViewInsideBuffer(const tinygltf::Image& image, const tinygltf::Model& model, std::string* error) {
    if (image.bufferView < 0) return true;  // from a uri: tinygltf read exactly that file
    const auto& view = model.bufferViews.at(static_cast<std::size_t>(image.bufferView));
    const auto& buffer = model.buffers.at(static_cast<std::size_t>(view.buffer));
    const std::uint64_t end = std::uint64_t(view.byteOffset) + std::uint64_t(view.byteLength);
    if (end <= buffer.data.size()) return true;
    if (error) {
        *error += "bufferViews[" + std::to_string(image.bufferView) + "] (an image) runs past the end of buffers[" +
                  std::to_string(view.buffer) + "]: bytes " + std::to_string(view.byteOffset) + ".." +
                  std::to_string(end) + " of " + std::to_string(buffer.data.size()) + "\n";
    }
    return false;
}

bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* error, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto* deferred = static_cast<DeferredImages*>(user);
    if (deferred->model && !imageViewInsideBuffer(*image, *deferred->model, error)) return false;
    if (index < 0 || size <= 0) return true;
    if (deferred->encoded.size() <= static_cast<std::size_t>(index)) deferred->encoded.resize(index + 1);
    deferred->encoded[index].assign(bytes, bytes + size);
    image->width = image->height = -1;
    return true;
}

// tinygltf's own FileExists fopen()s the file, which blocks forever on a FIFO: a uri naming
// anything but a regular file (a FIFO, a device, a folder) counts as missing.
bool regularFileExists(const std::string& path, void*) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

// Reads an external file (a .bin or image next to the .gltf) unless it is over the limit or
// not a regular file: a uri naming /dev/zero, a FIFO or a folder would read forever or block.
bool readCappedFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const std::uint64_t limit = *static_cast<const std::uint64_t*>(user);
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        if (err) *err += "file " + path + " is not a regular file\n";
        return false;
    }
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec && size > limit) {
        if (err) *err += "file " + path + " is larger than the limit of " + std::to_string(limit) + " bytes\n";
        return false;
    }
    return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t at) {
    std::uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;  // GLB is little-endian, like every platform lodopt builds on
}

// The GLB container (glTF 2.0 spec §4.4): header, then chunks that must fit in the file.
void checkGlbContainer(const std::vector<unsigned char>& bytes, const std::string& file) {
    if (bytes.size() < 12) fail(file, "GLB header", "truncated (" + std::to_string(bytes.size()) + " of 12 bytes)");
    const std::uint32_t version = readU32(bytes, 4), length = readU32(bytes, 8);
    if (version != 2) fail(file, "GLB header", "version " + std::to_string(version) + " is not 2");
    if (length > bytes.size()) {
        fail(file, "GLB header", "declares " + std::to_string(length) + " bytes but the file has " +
                                     std::to_string(bytes.size()) + " (truncated)");
    }
    std::size_t at = 12;
    int jsonChunks = 0, binChunks = 0;
    for (int chunk = 0; at < length; ++chunk) {
        const std::string where = "GLB chunk " + std::to_string(chunk);
        if (length - at < 8) fail(file, where, "header is truncated");
        const std::uint32_t chunkLength = readU32(bytes, at), type = readU32(bytes, at + 4);
        if (chunkLength > length - at - 8) {
            fail(file, where, std::to_string(chunkLength) + " bytes run past the end of the file (truncated)");
        }
        if (chunk == 0 && type != 0x4E4F534Au) fail(file, where, "the first chunk is not JSON");
        if (chunkLength % 4 != 0) fail(file, where, "length " + std::to_string(chunkLength) + " is not a multiple of 4");
        jsonChunks += type == 0x4E4F534Au;
        binChunks += type == 0x004E4942u;
        if (jsonChunks > 1 || binChunks > 1) fail(file, where, "a second JSON or BIN chunk");
        at += 8 + std::size_t(chunkLength);
    }
    if (at == 12) fail(file, "GLB", "no JSON chunk");
}

// tinygltf converts extras and extensions to its Value type recursively, and nlohmann::json
// dumps them recursively: a few hundred kilobytes of "[[[[..." would overflow the stack. No
// glTF needs more than a few levels; refuse deeper JSON before any parser sees it.
constexpr int kMaxJsonDepth = 256;

void checkJsonDepth(const unsigned char* text, std::size_t length, const std::string& file) {
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < length; ++i) {
        const unsigned char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonDepth) {
                fail(file, "JSON", "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels (at byte " +
                                       std::to_string(i) + ")");
            }
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

std::string joinLines(const std::string& text) {
    std::string joined;
    for (char c : text) {
        if (c == '\n') {
            if (!joined.empty() && joined.back() != ' ') joined += "; ";
        } else {
            joined += c;
        }
    }
    while (!joined.empty() && (joined.back() == ' ' || joined.back() == ';')) joined.pop_back();
    return joined;
}

// tinygltf's messages for two common failures do not name the element; look at the JSON
// again to say what is wrong. Returns "" when nothing better is found.
std::string diagnoseParseFailure(const std::vector<unsigned char>& bytes, bool binary) {
    const char* begin = reinterpret_cast<const char*>(bytes.data());
    std::size_t length = bytes.size();
    if (binary) {
        if (bytes.size() < 20) return "";
        length = std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20);
        begin += 20;
    }
    const nlohmann::json document = nlohmann::json::parse(begin, begin + length, nullptr, false);
    if (document.is_discarded() || !document.is_object()) return "";
    if (document.contains("extensionsRequired") && document["extensionsRequired"].is_array()) {
        for (const auto& name : document["extensionsRequired"]) {
            if (name.is_string() && !isUnderstoodExtension(name.get<std::string>())) {
                return "extensionsRequired: " + name.get<std::string>() + " is not supported";
            }
        }
    }
    if (document.contains("buffers") && document["buffers"].is_array()) {
        const auto& buffers = document["buffers"];
        for (std::size_t b = binary ? 1 : 0; b < buffers.size(); ++b) {
            if (buffers[b].is_object() && !buffers[b].contains("uri")) {
                return element("buffers", int(b)) + ".uri: missing (only the first buffer of a .glb may have no uri)";
            }
        }
    }
    return "";
}

std::vector<unsigned char> readFile(const std::string& path, std::uint64_t maxBytes) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw SceneError(path + ": no such file");
    if (!fs::is_regular_file(path, ec)) throw SceneError(path + ": not a regular file");
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) throw SceneError(path + ": cannot read the file size (" + ec.message() + ")");
    if (size > maxBytes || size > std::numeric_limits<unsigned int>::max()) {
        throw SceneError(path + ": " + std::to_string(size) + " bytes is over the limit of " + std::to_string(maxBytes));
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(path + ": cannot open the file");
    std::vector<unsigned char> bytes(size);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
    if (!in && size > 0) throw SceneError(path + ": read failed");
    if (size == 0) throw SceneError(path + ": the file is empty");
    return bytes;
}

}  // namespace

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
    std::vector<unsigned char> bytes = readFile(path, options.maxBytes);
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    if (binary) {
        checkGlbContainer(bytes, path);
        if (bytes.size() >= 20) checkJsonDepth(bytes.data() + 20, std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20), path);
    } else {
        checkJsonDepth(bytes.data(), bytes.size(), path);
    }

    std::vector<int> fallbackBuffers;
    bytes = rewriteForTinygltf(std::move(bytes), binary, fallbackBuffers);

    tinygltf::TinyGLTF parser;
    DeferredImages deferred;
    parser.SetImageLoader(&keepEncodedImage, &deferred);
    parser.SetStoreOriginalJSONForExtrasAndExtensions(true);
    std::uint64_t limit = options.maxBytes;
    parser.SetFsCallbacks({&regularFileExists, &tinygltf::ExpandFilePath, &readCappedFile, &tinygltf::WriteWholeFile,
                           &limit});
    tinygltf::Model model;
    deferred.model = &model;
    std::string error, warning;
    const std::string baseDir = fs::path(path).parent_path().string();
    auto parse = [&](const std::vector<unsigned char>& file) {
        model = tinygltf::Model();
        deferred.encoded.clear();
        error.clear();
        warning.clear();
        try {
            return binary ? parser.LoadBinaryFromMemory(&model, &error, &warning, file.data(),
                                                        static_cast<unsigned int>(file.size()), baseDir)
                          : parser.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(file.data()),
                                                       static_cast<unsigned int>(file.size()), baseDir);
        } catch (const std::exception& e) {
            // nlohmann::json throws for numbers it cannot hold (1e309) in some tinygltf paths.
            throw SceneError(path + ": " + e.what());
        }
    };
    bool parsed = parse(bytes);
    if (!parsed) {
        // Valid glTF tinygltf refuses: once more with stand-ins for what it cannot read.
        const std::string firstError = error;
        std::vector<std::string> notes;
        std::vector<unsigned char> retried = standInsForUnreadableObjects(bytes, binary, notes);
        if (!retried.empty() && parse(retried)) {
            parsed = true;
            bytes = std::move(retried);
            if (options.warnings) {
                for (const std::string& note : notes) options.warnings->push_back(path + ": " + note);
            }
        } else {
            error = firstError;
        }
    }
    if (!parsed) {
        std::string reason = diagnoseParseFailure(bytes, binary);
        if (reason.empty()) reason = error.empty() ? std::string("not a glTF 2.0 file") : joinLines(error);
        throw SceneError(path + ": " + reason);
    }
    bytes.clear();
    bytes.shrink_to_fit();
    if (options.warnings && !warning.empty()) options.warnings->push_back(path + ": " + joinLines(warning));

    std::uint64_t bufferBytes = 0;
    for (const tinygltf::Buffer& buffer : model.buffers) bufferBytes += buffer.data.size();
    for (const auto& image : deferred.encoded) bufferBytes += image.size();
    if (bufferBytes > options.maxBytes) {
        throw SceneError(path + ": buffers and images hold " + std::to_string(bufferBytes) + " bytes, over the limit of " +
                         std::to_string(options.maxBytes));
    }
    // Extensions first: refuse what cannot be drawn before decoding anything, then decode
    // compressed views and primitives within what the byte limit leaves.
    checkRequiredExtensions(model, path);
    warnUnimplementedExtensions(model, path, options.warnings);
    resolveTextureSources(model, path);
    std::uint64_t byteBudget = options.maxBytes - bufferBytes;
    decodeMeshoptViews(model, path, fallbackBuffers, byteBudget);
    decodeDracoPrimitives(model, path, byteBudget);
    bufferBytes = options.maxBytes - byteBudget;
    const ModelGraph graph = validateModel(model, path, bufferBytes + (std::uint64_t(1) << 20));
    SceneBuilder builder(model, graph, path, options, std::move(deferred.encoded));
    return builder.build();
}

}  // namespace lodopt::scenes
