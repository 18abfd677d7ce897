// Which glTF extensions the loader accepts, refuses or warns about, and the small model
// rewrites that let tinygltf 2.7 parse what it would misread (docs/gltf.md, "Extensions").
//
// A required extension (extensionsRequired) is accepted only when lodopt decodes it or draws
// it faithfully enough; any other is refused by name. A used-but-not-required extension that
// changes how the model looks and is not implemented gets one warning naming it: the model is
// still drawn, without it.
#include <algorithm>
#include <map>
#include <cmath>
#include <cstring>
#include <set>

#include <nlohmann/json.hpp>

#include "gltf_detail.hpp"

namespace lodopt::scenes::gltf_detail {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// Used-but-not-required extensions that change nothing lodopt draws: metadata, and animation
// targets (animations are not played).
const std::set<std::string>& nonVisualExtensions() {
    static const std::set<std::string> kNames = {"KHR_xmp_json_ld", "KHR_xmp", "KHR_animation_pointer"};
    return kNames;
}

std::uint32_t readU32(const std::vector<unsigned char>& bytes, std::size_t at) {
    std::uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;
}

void appendU32(std::vector<unsigned char>& bytes, std::uint32_t value) {
    unsigned char le[4];
    std::memcpy(le, &value, 4);
    bytes.insert(bytes.end(), le, le + 4);
}

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// RFC 4648 base64 with padding (tinygltf's encoder is not in its shared library's header).
std::string base64Encode(const std::string& bytes) {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t group = std::uint32_t(static_cast<unsigned char>(bytes[i])) << 16;
        if (i + 1 < bytes.size()) group |= std::uint32_t(static_cast<unsigned char>(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) group |= std::uint32_t(static_cast<unsigned char>(bytes[i + 2]));
        text += kAlphabet[(group >> 18) & 63];
        text += kAlphabet[(group >> 12) & 63];
        text += i + 1 < bytes.size() ? kAlphabet[(group >> 6) & 63] : '=';
        text += i + 2 < bytes.size() ? kAlphabet[group & 63] : '=';
    }
    return text;
}

// The uri to hand tinygltf so that it reads what the uri means (RFC 2397 data uris, RFC 3986
// relative references), or `uri` itself:
//  - a buffer's data uri "data:application/gltf-buffer,<bytes>" or
//    "data:application/octet-stream,<bytes>" (percent-encoded, not base64) becomes base64;
//  - an image's "data:image/webp;base64,..." becomes application/octet-stream (the loader
//    sniffs the image bytes);
//  - a relative path's '+' becomes %2B: tinygltf's percent-decoding reads '+' as a space.
// Other data uris (other media types, malformed headers) stay as they are and fail to load.
std::string tinygltfReadableUri(const std::string& uri, bool image) {
    if (uri.rfind("data:", 0) != 0) {
        if (uri.find('+') == std::string::npos) return uri;
        std::string escaped;
        for (char c : uri) escaped += c == '+' ? std::string("%2B") : std::string(1, c);
        return escaped;
    }
    static const std::string kOctets = "data:application/octet-stream;base64,";
    static const std::string kWebp = "data:image/webp;base64,";
    if (image) return uri.rfind(kWebp, 0) == 0 ? kOctets + uri.substr(kWebp.size()) : uri;
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos) return uri;
    const std::string header = uri.substr(5, comma - 5);
    if (header != "application/gltf-buffer" && header != "application/octet-stream") return uri;
    std::string bytes;
    for (std::size_t i = comma + 1; i < uri.size(); ++i) {
        const int high = uri[i] == '%' && i + 2 < uri.size() ? hexValue(uri[i + 1]) : -1;
        const int low = high >= 0 ? hexValue(uri[i + 2]) : -1;
        if (low >= 0) {
            bytes += static_cast<char>(high * 16 + low);
            i += 2;
        } else {
            bytes += uri[i];
        }
    }
    if (bytes.empty()) return uri;
    return kOctets + base64Encode(bytes);
}

// True when some "uri" string needs tinygltfReadableUri(): a cheap scan, so that only those
// files (and meshopt fallbacks, Draco primitives) pay for a second JSON parse. JSON escapes
// are not decoded: an escaped uri only costs that parse.
bool hasUriToRewrite(const char* text, std::size_t length) {
    static const char kKey[] = "\"uri\"";
    const char* end = text + length;
    for (const char* at = std::search(text, end, kKey, kKey + 5); at != end; at = std::search(at + 5, end, kKey, kKey + 5)) {
        const char* p = at + 5;
        while (p != end && (*p == ' ' || *p == ':' || *p == '\t' || *p == '\n' || *p == '\r')) ++p;
        if (p == end || *p != '"') continue;
        const char* close = std::find(p + 1, end, '"');
        const std::string uri(p + 1, close);
        if (tinygltfReadableUri(uri, false) != uri || tinygltfReadableUri(uri, true) != uri) return true;
    }
    return false;
}

// The file `bytes` (a .gltf, or a .glb whose JSON chunk is replaced) with `document` as its
// JSON; empty when the document cannot be written (invalid UTF-8).
std::vector<unsigned char> withJson(const std::vector<unsigned char>& bytes, bool binary, const nlohmann::json& document) {
    std::string json;
    try {
        json = document.dump();
    } catch (const nlohmann::json::exception&) {
        return {};  // invalid UTF-8: let tinygltf report what it finds
    }
    if (!binary) return std::vector<unsigned char>(json.begin(), json.end());
    while (json.size() % 4 != 0) json += ' ';
    // Same container, new JSON chunk, the rest (BIN chunk) byte for byte.
    const std::size_t jsonBegin = 20;
    const std::size_t jsonLength = std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20);
    const std::size_t restBegin = jsonBegin + jsonLength;
    const std::size_t total = std::min<std::size_t>(readU32(bytes, 8), bytes.size());
    std::vector<unsigned char> rebuilt(bytes.begin(), bytes.begin() + 8);
    appendU32(rebuilt, static_cast<std::uint32_t>(12 + 8 + json.size() + (total - std::min(total, restBegin))));
    appendU32(rebuilt, static_cast<std::uint32_t>(json.size()));
    appendU32(rebuilt, 0x4E4F534Au);
    rebuilt.insert(rebuilt.end(), json.begin(), json.end());
    if (restBegin < total) rebuilt.insert(rebuilt.end(), bytes.begin() + restBegin, bytes.begin() + total);
    return rebuilt;
}

}  // namespace

std::uint64_t extensionInteger(const tinygltf::Value& object, const char* key, std::uint64_t fallback,
                               std::uint64_t max, const std::string& file, const std::string& where) {
    if (!object.IsObject() || !object.Has(key)) return fallback;
    const tinygltf::Value& value = object.Get(key);
    const double number = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
    if (!value.IsNumber() || !(number >= 0.0) || number != std::floor(number) || number > double(max)) {
        fail(file, where + "." + key, "is not an integer in 0.." + std::to_string(max));
    }
    return static_cast<std::uint64_t>(number);
}

std::uint64_t requiredExtensionInteger(const tinygltf::Value& object, const char* key, std::uint64_t max,
                                       const std::string& file, const std::string& where) {
    if (!object.IsObject() || !object.Has(key)) fail(file, where + "." + key, "is missing");
    return extensionInteger(object, key, 0, max, file, where);
}

std::vector<unsigned char> rewriteForTinygltf(std::vector<unsigned char> bytes, bool binary,
                                              std::vector<int>& fallbackBuffers) {
    std::size_t jsonBegin = 0, jsonLength = bytes.size();
    if (binary) {  // checkGlbContainer() has run: the JSON chunk lies inside the file
        if (bytes.size() < 20) return bytes;
        jsonBegin = 20;
        jsonLength = std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20);
    }
    const char* text = reinterpret_cast<const char*>(bytes.data()) + jsonBegin;
    const std::string_view view(text, jsonLength);
    if (view.find("\"fallback\"") == std::string_view::npos && view.find(kDraco) == std::string_view::npos &&
        !hasUriToRewrite(text, jsonLength)) {
        return bytes;
    }

    nlohmann::json document = nlohmann::json::parse(text, text + jsonLength, nullptr, false);
    if (document.is_discarded() || !document.is_object()) return bytes;  // tinygltf names the error
    bool changed = false;
    auto rewriteUri = [&](nlohmann::json& owner, bool image) {
        if (!owner.is_object() || !owner.contains("uri") || !owner["uri"].is_string()) return;
        const std::string uri = owner["uri"].get<std::string>();
        const std::string readable = tinygltfReadableUri(uri, image);
        if (readable == uri) return;
        owner["uri"] = readable;
        changed = true;
    };
    if (document.contains("buffers") && document["buffers"].is_array()) {
        auto& buffers = document["buffers"];
        for (std::size_t b = 0; b < buffers.size(); ++b) {
            nlohmann::json& buffer = buffers[b];
            if (!buffer.is_object()) continue;
            const auto extensions = buffer.find("extensions");
            bool fallback = false;
            if (extensions != buffer.end() && extensions->is_object()) {
                const auto meshopt = extensions->find("EXT_meshopt_compression");
                if (meshopt != extensions->end() && meshopt->is_object()) {
                    const auto flag = meshopt->find("fallback");
                    fallback = flag != meshopt->end() && flag->is_boolean() && flag->get<bool>();
                }
            }
            if (fallback && !buffer.contains("uri")) {
                // No data: every view on it must be decoded. A placeholder keeps tinygltf from
                // failing on the missing uri, or, in a .glb, copying unrelated BIN bytes.
                buffer["uri"] = "data:application/octet-stream;base64,AAAAAA==";
                buffer["byteLength"] = 4;
                fallbackBuffers.push_back(static_cast<int>(b));
                changed = true;
            } else {
                rewriteUri(buffer, false);
            }
        }
    }
    if (document.contains("meshes") && document["meshes"].is_array()) {
        for (auto& mesh : document["meshes"]) {
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (auto& primitive : mesh["primitives"]) {
                if (!primitive.is_object() || !primitive.contains("indices") || !primitive.contains("extensions")) continue;
                const nlohmann::json& extensions = primitive["extensions"];
                if (!extensions.is_object() || !extensions.contains(kDraco)) continue;
                // tinygltf refuses an index accessor without a bufferView, which is how a Draco
                // primitive declares its indices; decodeDracoPrimitives() writes new ones.
                primitive.erase("indices");
                changed = true;
            }
        }
    }
    if (document.contains("images") && document["images"].is_array()) {
        for (auto& image : document["images"]) rewriteUri(image, true);
    }
    if (!changed) return bytes;
    std::vector<unsigned char> rebuilt = withJson(bytes, binary, document);
    return rebuilt.empty() ? bytes : rebuilt;
}

// Integral numbers written as floats (`"byteLength": 1.0`, valid JSON and valid glTF) as
// integers, which tinygltf requires where the schema says integer; true when any changed.
bool integralFloatsToIntegers(nlohmann::json& value) {
    bool changed = false;
    if (value.is_number_float()) {
        const double number = value.get<double>();
        if (number == std::floor(number) && std::abs(number) < 9007199254740992.0) {
            value = static_cast<std::int64_t>(number);
            changed = true;
        }
    } else if (value.is_array() || value.is_object()) {
        for (auto& child : value) changed |= integralFloatsToIntegers(child);
    }
    return changed;
}

std::vector<unsigned char> standInsForUnreadableObjects(const std::vector<unsigned char>& bytes, bool binary,
                                                    std::vector<std::string>& notes) {
    std::size_t jsonBegin = 0, jsonLength = bytes.size();
    if (binary) {
        if (bytes.size() < 20) return {};
        jsonBegin = 20;
        jsonLength = std::min<std::size_t>(readU32(bytes, 12), bytes.size() - 20);
    }
    const char* text = reinterpret_cast<const char*>(bytes.data()) + jsonBegin;
    nlohmann::json document = nlohmann::json::parse(text, text + jsonLength, nullptr, false);
    if (document.is_discarded() || !document.is_object()) return {};
    auto arrayOf = [&](const char* key) -> nlohmann::json* {
        const auto found = document.find(key);
        return found != document.end() && found->is_array() ? &*found : nullptr;
    };
    auto indexIn = [](const nlohmann::json& owner, const char* key, std::set<std::int64_t>& into) {
        if (owner.is_object() && owner.contains(key) && owner[key].is_number_integer()) into.insert(owner[key].get<std::int64_t>());
    };
    bool changed = integralFloatsToIntegers(document);

    // What a drawn node reads: the accessors of its mesh's primitives (attributes, indices,
    // morph targets) and of its skin, and every animation's samplers; then the bufferViews of
    // those accessors (sparse ones included) and of every image, and their buffers.
    std::set<std::int64_t> drawnMeshes, drawnSkins, read, readViews, readBuffers;
    if (const nlohmann::json* nodes = arrayOf("nodes")) {
        for (const auto& node : *nodes) {
            indexIn(node, "mesh", drawnMeshes);
            indexIn(node, "skin", drawnSkins);
        }
    }
    if (const nlohmann::json* meshes = arrayOf("meshes")) {
        for (std::int64_t m : drawnMeshes) {
            if (m < 0 || m >= std::int64_t(meshes->size())) continue;
            const nlohmann::json& mesh = (*meshes)[std::size_t(m)];
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (const auto& primitive : mesh["primitives"]) {
                if (!primitive.is_object()) continue;
                indexIn(primitive, "indices", read);
                const auto addMap = [&](const nlohmann::json& map) {
                    if (!map.is_object()) return;
                    for (const auto& [name, index] : map.items()) {
                        if (index.is_number_integer()) read.insert(index.get<std::int64_t>());
                    }
                };
                if (primitive.contains("attributes")) addMap(primitive["attributes"]);
                if (primitive.contains("targets") && primitive["targets"].is_array()) {
                    for (const auto& target : primitive["targets"]) addMap(target);
                }
            }
        }
    }
    if (const nlohmann::json* skins = arrayOf("skins")) {
        for (std::int64_t k : drawnSkins) {
            if (k >= 0 && k < std::int64_t(skins->size())) indexIn((*skins)[std::size_t(k)], "inverseBindMatrices", read);
        }
    }
    if (const nlohmann::json* animations = arrayOf("animations")) {
        for (const auto& animation : *animations) {
            if (!animation.is_object() || !animation.contains("samplers") || !animation["samplers"].is_array()) continue;
            for (const auto& sampler : animation["samplers"]) {
                indexIn(sampler, "input", read);
                indexIn(sampler, "output", read);
            }
        }
    }
    nlohmann::json* accessors = arrayOf("accessors");
    if (accessors) {
        for (std::int64_t a : read) {
            if (a < 0 || a >= std::int64_t(accessors->size())) continue;
            const nlohmann::json& accessor = (*accessors)[std::size_t(a)];
            indexIn(accessor, "bufferView", readViews);
            if (accessor.is_object() && accessor.contains("sparse") && accessor["sparse"].is_object()) {
                for (const char* part : {"indices", "values"}) {
                    if (accessor["sparse"].contains(part)) indexIn(accessor["sparse"][part], "bufferView", readViews);
                }
            }
        }
    }
    if (const nlohmann::json* images = arrayOf("images")) {
        for (const auto& image : *images) indexIn(image, "bufferView", readViews);
    }
    if (const nlohmann::json* views = arrayOf("bufferViews")) {
        for (std::int64_t v : readViews) {
            if (v >= 0 && v < std::int64_t(views->size())) indexIn((*views)[std::size_t(v)], "buffer", readBuffers);
        }
    }

    // A buffer without uri (other than a .glb's own) has no data in the file: zeros of its
    // length stand in (up to 16 MiB), with a note when something drawn reads them.
    // Zeros written into the file in all, so that a small file cannot make a large one.
    std::uint64_t zeroBudget = std::uint64_t(16) << 20;
    if (nlohmann::json* buffers = arrayOf("buffers")) {
        for (std::size_t b = binary ? 1 : 0; b < buffers->size(); ++b) {
            nlohmann::json& buffer = (*buffers)[b];
            if (!buffer.is_object() || buffer.contains("uri")) continue;
            const auto length = buffer.find("byteLength");
            if (length == buffer.end() || !length->is_number_unsigned() || length->get<std::uint64_t>() == 0 ||
                length->get<std::uint64_t>() > zeroBudget) {
                continue;
            }
            zeroBudget -= length->get<std::uint64_t>();
            const std::string zeros(static_cast<std::size_t>(length->get<std::uint64_t>()), '\0');
            buffer["uri"] = "data:application/octet-stream;base64," + base64Encode(zeros);
            changed = true;
            if (readBuffers.count(std::int64_t(b)) != 0) {
                notes.push_back(element("buffers", int(b)) + " has no uri and the file holds no data for it: "
                                "what is drawn from it reads zeros");
            }
        }
    }

    if (accessors) {
        static const std::map<std::string, int> kComponents = {{"SCALAR", 1}, {"VEC2", 2},  {"VEC3", 3}, {"VEC4", 4},
                                                               {"MAT2", 4},   {"MAT3", 9},  {"MAT4", 16}};
        // An unused accessor of a type glTF does not define (valid: the validator warns):
        // a scalar stand-in.
        for (std::size_t a = 0; a < accessors->size(); ++a) {
            nlohmann::json& accessor = (*accessors)[a];
            if (!accessor.is_object() || read.count(std::int64_t(a)) != 0) continue;
            const auto type = accessor.find("type");
            if (type != accessor.end() && type->is_string() && kComponents.count(type->get<std::string>()) != 0) continue;
            accessor["type"] = "SCALAR";
            accessor.erase("min");
            accessor.erase("max");
            changed = true;
        }
        // An accessor without bufferView or sparse holds zeros (spec 3.6.2.1): one zero-filled
        // buffer, within what the budget leaves, stands in for all of them.
        std::vector<std::size_t> zeroed;
        std::uint64_t zeroBytes = 0;
        for (std::size_t a = 0; a < accessors->size(); ++a) {
            const nlohmann::json& accessor = (*accessors)[a];
            if (!accessor.is_object() || accessor.contains("bufferView") || accessor.contains("sparse")) continue;
            const auto type = accessor.find("type");
            const auto component = accessor.find("componentType");
            const auto count = accessor.find("count");
            if (type == accessor.end() || !type->is_string() || component == accessor.end() ||
                !component->is_number_integer() || count == accessor.end() || !count->is_number_unsigned()) {
                continue;
            }
            const auto components = kComponents.find(type->get<std::string>());
            // As the accessor reader sizes an element (accessorElementSize).
            const std::uint64_t element = components == kComponents.end()
                                              ? 0
                                              : std::uint64_t(components->second) * componentSize(component->get<int>());
            const std::uint64_t elements = count->get<std::uint64_t>();
            if (element == 0 || elements == 0 || elements > zeroBudget) continue;
            const std::uint64_t needed = elements * element;
            if (needed > zeroBudget) continue;
            zeroBytes = std::max(zeroBytes, needed);
            zeroed.push_back(a);
        }
        if (!zeroed.empty()) {
            nlohmann::json& buffers = document["buffers"];
            nlohmann::json& views = document["bufferViews"];
            if (buffers.is_null()) buffers = nlohmann::json::array();
            if (views.is_null()) views = nlohmann::json::array();
            if (!buffers.is_array() || !views.is_array()) return {};
            const std::string zeros(static_cast<std::size_t>(zeroBytes), '\0');
            buffers.push_back({{"uri", "data:application/octet-stream;base64," + base64Encode(zeros)},
                               {"byteLength", zeroBytes}});
            views.push_back({{"buffer", buffers.size() - 1}, {"byteLength", zeroBytes}});
            for (std::size_t a : zeroed) (*accessors)[a]["bufferView"] = views.size() - 1;
            changed = true;
        }
    }
    return changed ? withJson(bytes, binary, document) : std::vector<unsigned char>();
}

void checkRequiredExtensions(const tinygltf::Model& model, const std::string& file) {
    // Any other required extension changes the meaning of the data (e.g. KHR_texture_basisu
    // images lodopt cannot decode): refuse rather than draw something else.
    for (const std::string& name : model.extensionsRequired) {
        if (!isUnderstoodExtension(name)) fail(file, "extensionsRequired", name + " is not supported");
    }
}

void warnUnimplementedExtensions(const tinygltf::Model& model, const std::string& file,
                                 std::vector<std::string>* warnings) {
    if (!warnings) return;
    std::set<std::string> reported;
    for (const std::string& name : model.extensionsUsed) {
        if (isUnderstoodExtension(name) || nonVisualExtensions().count(name) != 0) continue;
        if (!reported.insert(name).second) continue;
        const bool required = std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(), name) !=
                              model.extensionsRequired.end();
        if (required) continue;  // refused by checkRequiredExtensions
        warnings->push_back(file + ": extensionsUsed: " + name +
                            " is not implemented; the model is drawn without it");
    }
}

int textureImageSource(const tinygltf::Model& model, int texture, const std::string& file) {
    const tinygltf::Texture& source = model.textures[texture];
    const auto webp = source.extensions.find("EXT_texture_webp");
    if (webp == source.extensions.end()) return source.source;
    const std::string where = element("textures", texture) + ".extensions.EXT_texture_webp";
    const std::uint64_t image = requiredExtensionInteger(webp->second, "source", 0x7FFFFFFF, file, where);
    if (image >= model.images.size()) {
        fail(file, where + ".source",
             "image " + std::to_string(image) + " does not exist (the file has " + std::to_string(model.images.size()) + ")");
    }
    return static_cast<int>(image);
}

void resolveTextureSources(tinygltf::Model& model, const std::string& file) {
    for (int t = 0; t < static_cast<int>(model.textures.size()); ++t) {
        model.textures[t].source = textureImageSource(model, t, file);
    }
}

}  // namespace lodopt::scenes::gltf_detail
