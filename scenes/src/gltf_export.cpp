// glTF 2.0 export of a lodopt Scene (Khronos glTF 2.0 specification; MSFT_lod vendor
// extension for the levels). The JSON is written with nlohmann::json rather than through a
// tinygltf::Model so that extensions and extras are plain JSON; tinygltf only encodes PNGs.
// Layout (docs/gltf.md): one buffer, one bufferView per accessor, one scene root node per
// object (level 0, with MSFT_lod naming the coarser level nodes, which are not in the scene)
// and one per view.
#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "scenes/atomic_file.hpp"
#include "scenes/gltf_io.hpp"
#include "scenes/engine_lod.hpp"

namespace lodopt::scenes {

namespace {

using nlohmann::json;

constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;

const char kBase64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string base64Encode(const unsigned char* data, std::size_t size) {
    std::string out;
    out.reserve((size + 2) / 3 * 4);
    for (std::size_t i = 0; i < size; i += 3) {
        const std::uint32_t chunk = (std::uint32_t(data[i]) << 16) | (i + 1 < size ? std::uint32_t(data[i + 1]) << 8 : 0u) |
                                    (i + 2 < size ? std::uint32_t(data[i + 2]) : 0u);
        out += kBase64[(chunk >> 18) & 63];
        out += kBase64[(chunk >> 12) & 63];
        out += i + 1 < size ? kBase64[(chunk >> 6) & 63] : '=';
        out += i + 2 < size ? kBase64[chunk & 63] : '=';
    }
    return out;
}

std::vector<unsigned char> base64Decode(const std::string& text) {
    std::vector<unsigned char> out;
    std::uint32_t chunk = 0;
    int bits = 0;
    for (char c : text) {
        const char* at = std::strchr(kBase64, c);
        if (c == '=' || c == '\0' || at == nullptr) continue;
        chunk = (chunk << 6) | std::uint32_t(at - kBase64);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<unsigned char>((chunk >> bits) & 0xFF));
        }
    }
    return out;
}

json vec(const float* values, int count) {
    json array = json::array();
    for (int i = 0; i < count; ++i) array.push_back(values[i]);
    return array;
}

json vec3(const glm::vec3& v) { return vec(&v.x, 3); }

// Collects the binary data and its bufferViews/accessors.
class BinaryWriter {
public:
    int addView(const void* data, std::size_t bytes, int target) {
        while (mBytes.size() % 4 != 0) mBytes.push_back(0);  // accessors need aligned offsets
        json view = {{"buffer", 0}, {"byteOffset", mBytes.size()}, {"byteLength", bytes}};
        if (target != 0) view["target"] = target;
        const auto* begin = static_cast<const unsigned char*>(data);
        mBytes.insert(mBytes.end(), begin, begin + bytes);
        mViews.push_back(std::move(view));
        return static_cast<int>(mViews.size()) - 1;
    }

    int addAccessor(const void* data, std::size_t count, int componentType, const char* type, int components,
                    int target, json extra = json::object()) {
        const int view = addView(data, count * components * 4, target);
        json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
        accessor.update(extra);
        mAccessors.push_back(std::move(accessor));
        return static_cast<int>(mAccessors.size()) - 1;
    }

    std::vector<unsigned char>& bytes() { return mBytes; }
    json& views() { return mViews; }
    json& accessors() { return mAccessors; }

private:
    std::vector<unsigned char> mBytes;
    json mViews = json::array();
    json mAccessors = json::array();
};

json meshJson(const std::string& name, const std::vector<Mesh>& meshes, BinaryWriter& writer) {
    json primitives = json::array();
    for (const Mesh& mesh : meshes) {
        if (mesh.indices.empty() || mesh.positions.empty()) continue;
        glm::vec3 low = mesh.positions[0], high = mesh.positions[0];
        for (const glm::vec3& p : mesh.positions) {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
        json attributes;
        attributes["POSITION"] = writer.addAccessor(mesh.positions.data(), mesh.positions.size(), kFloat, "VEC3", 3,
                                                    kArrayBuffer, {{"min", vec3(low)}, {"max", vec3(high)}});
        // Without NORMAL a reader draws flat normals (and ignores TANGENT), as lodopt did.
        if (!mesh.flatNormals) {
            attributes["NORMAL"] =
                writer.addAccessor(mesh.normals.data(), mesh.normals.size(), kFloat, "VEC3", 3, kArrayBuffer);
        }
        if (!mesh.uvs.empty()) {
            attributes["TEXCOORD_0"] = writer.addAccessor(mesh.uvs.data(), mesh.uvs.size(), kFloat, "VEC2", 2, kArrayBuffer);
        }
        if (!mesh.uvs1.empty()) {
            attributes["TEXCOORD_1"] =
                writer.addAccessor(mesh.uvs1.data(), mesh.uvs1.size(), kFloat, "VEC2", 2, kArrayBuffer);
        }
        if (!mesh.tangents.empty() && !mesh.flatNormals) {
            attributes["TANGENT"] =
                writer.addAccessor(mesh.tangents.data(), mesh.tangents.size(), kFloat, "VEC4", 4, kArrayBuffer);
        }
        if (!mesh.colors.empty()) {
            attributes["COLOR_0"] =
                writer.addAccessor(mesh.colors.data(), mesh.colors.size(), kFloat, "VEC4", 4, kArrayBuffer);
        }
        json primitive = {{"attributes", attributes},
                          {"indices", writer.addAccessor(mesh.indices.data(), mesh.indices.size(), kUnsignedInt, "SCALAR",
                                                         1, kElementArrayBuffer)},
                          {"mode", 4}};
        if (mesh.material >= 0) primitive["material"] = mesh.material;
        primitives.push_back(std::move(primitive));
    }
    if (primitives.empty()) return nullptr;
    return {{"name", name}, {"primitives", primitives}};
}

bool isIdentity(const glm::mat4& m) { return m == glm::mat4(1.0f); }

// A glTF sampler (spec §3.8.4) with the GL codes the spec uses.
json samplerJson(const SamplerState& state) {
    auto wrap = [](WrapMode mode) {
        return mode == WrapMode::ClampToEdge ? 33071 : mode == WrapMode::MirroredRepeat ? 33648 : 10497;
    };
    const bool linear = state.minFilter == FilterMode::Linear;
    const int minFilter = state.mipmap == MipmapMode::None      ? (linear ? 9729 : 9728)
                          : state.mipmap == MipmapMode::Nearest ? (linear ? 9985 : 9984)
                                                                : (linear ? 9987 : 9986);
    return {{"magFilter", state.magFilter == FilterMode::Linear ? 9729 : 9728},
            {"minFilter", minFilter},
            {"wrapS", wrap(state.wrapS)},
            {"wrapT", wrap(state.wrapT)}};
}

// PNG bytes of an RGBA8 texture, through tinygltf's stb_image_write (as a data URI).
std::string pngDataUri(const Texture& texture) {
    tinygltf::Image image;
    image.width = texture.width;
    image.height = texture.height;
    image.component = 4;
    image.bits = 8;
    image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image.image = texture.rgba;
    const std::string base, filename = "texture.png";
    std::string uri;
    if (!tinygltf::WriteImageData(&base, &filename, &image, true, &uri, nullptr) || uri.empty()) {
        throw SceneError("texture '" + texture.name + "': PNG encoding failed");
    }
    return uri;
}

json cameraPathsJson(const std::vector<CameraPath>& paths) {
    json array = json::array();
    for (const CameraPath& path : paths) {
        json frames = json::array();
        for (const Camera& c : path.frames) {
            frames.push_back({{"name", c.name}, {"position", vec3(c.position)}, {"target", vec3(c.target)},
                              {"up", vec3(c.up)}, {"fov", c.fovYDegrees}, {"near", c.nearPlane}, {"far", c.farPlane}});
        }
        array.push_back({{"name", path.name}, {"fps", path.framesPerSecond}, {"frames", frames}});
    }
    return array;
}

}  // namespace

void exportGltf(const Scene& scene, const std::string& path, const GltfExportOptions& options) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension != ".gltf" && extension != ".glb") {
        throw SceneError(path + ": the file name must end in .gltf or .glb");
    }
    const bool binary = extension == ".glb";
    validateScene(scene);

    BinaryWriter writer;
    json nodes = json::array(), meshes = json::array(), roots = json::array();
    bool anyLods = false;
    for (const Object& object : scene.objects) {
        const int root = static_cast<int>(nodes.size());
        roots.push_back(root);
        nodes.push_back(json::object());
        json ids = json::array();
        for (std::size_t k = 0; k < object.levels.size(); ++k) {
            json node = {{"name", k == 0 ? object.name : object.name + "_LOD" + std::to_string(k)}};
            // Coarser levels carry the same transform: the loader places them like level 0.
            if (!isIdentity(object.transform)) node["matrix"] = vec(&object.transform[0][0], 16);
            json mesh = meshJson(node["name"].get<std::string>(), object.levels[k].meshes, writer);
            if (!mesh.is_null()) {
                node["mesh"] = meshes.size();
                meshes.push_back(std::move(mesh));
            }
            if (k == 0) {
                nodes[root] = std::move(node);
            } else {
                ids.push_back(nodes.size());
                nodes.push_back(std::move(node));
            }
        }
        if (!ids.empty()) {
            anyLods = true;
            nodes[root]["extensions"] = {{"MSFT_lod", {{"ids", ids}}}};
            const bool allCoverage = std::all_of(object.levels.begin(), object.levels.end(),
                                                 [](const Level& level) { return level.screenCoverage.has_value(); });
            if (allCoverage) {
                json coverage = json::array();
                const Bounds bounds = worldBounds(object, 0);
                for (const Level& level : object.levels) {
                    coverage.push_back(options.coverage == CoverageConvention::UnityRelativeHeight
                                           ? unityRelativeHeight(*level.screenCoverage, bounds)
                                           : double(*level.screenCoverage));
                }
                nodes[root]["extras"] = {{"MSFT_screencoverage", coverage}};
            }
        }
    }
    json cameras = json::array();
    for (const Camera& view : scene.views) {
        // The camera node's transform is the inverse view matrix: camera space → world.
        const glm::mat4 cameraToWorld = glm::inverse(viewMatrix(view));
        const glm::quat rotation = glm::normalize(glm::quat_cast(glm::mat3(cameraToWorld)));
        const float quaternion[4] = {rotation.x, rotation.y, rotation.z, rotation.w};
        roots.push_back(nodes.size());
        nodes.push_back({{"name", view.name},
                         {"camera", cameras.size()},
                         {"translation", vec3(view.position)},
                         {"rotation", vec(quaternion, 4)},
                         {"extras", {{"lodopt_target", vec3(view.target)}}}});
        cameras.push_back({{"name", view.name},
                           {"type", "perspective"},
                           {"perspective",
                            {{"yfov", glm::radians(view.fovYDegrees)}, {"znear", view.nearPlane}, {"zfar", view.farPlane}}}});
    }
    // A glTF texture is an image with a sampler: one per distinct pair the materials use.
    json materials = json::array(), textures = json::array(), samplers = json::array();
    std::vector<SamplerState> samplerStates;
    std::map<std::pair<int, int>, int> textureOf;  // (image, sampler) → textures[]
    std::set<std::string> extensionsUsed;
    auto textureInfo = [&](const TextureRef& reference) {
        auto found = std::find(samplerStates.begin(), samplerStates.end(), reference.sampler);
        const int sampler = int(found - samplerStates.begin());
        if (found == samplerStates.end()) {
            samplerStates.push_back(reference.sampler);
            samplers.push_back(samplerJson(reference.sampler));
        }
        auto [entry, added] = textureOf.try_emplace({reference.texture, sampler}, int(textures.size()));
        if (added) textures.push_back({{"source", reference.texture}, {"sampler", sampler}});
        json info = {{"index", entry->second}};
        if (reference.texCoord != 0) info["texCoord"] = reference.texCoord;
        if (!reference.transform.isIdentity()) {
            const TextureTransform& transform = reference.transform;
            info["extensions"] = {{"KHR_texture_transform",
                                   {{"offset", vec(&transform.offset.x, 2)},
                                    {"rotation", transform.rotation},
                                    {"scale", vec(&transform.scale.x, 2)}}}};
            extensionsUsed.insert("KHR_texture_transform");
        }
        return info;
    };
    for (const Material& material : scene.materials) {
        json pbr = {{"baseColorFactor", vec(&material.baseColorFactor.x, 4)},
                    {"metallicFactor", material.metallicFactor},
                    {"roughnessFactor", material.roughnessFactor}};
        if (material.baseColorTexture.present()) pbr["baseColorTexture"] = textureInfo(material.baseColorTexture);
        if (material.metallicRoughnessTexture.present()) {
            pbr["metallicRoughnessTexture"] = textureInfo(material.metallicRoughnessTexture);
        }
        json out = {{"name", material.name}, {"pbrMetallicRoughness", pbr}};
        if (material.normalTexture.present()) {
            out["normalTexture"] = textureInfo(material.normalTexture);
            out["normalTexture"]["scale"] = material.normalScale;
        }
        if (material.occlusionTexture.present()) {
            out["occlusionTexture"] = textureInfo(material.occlusionTexture);
            out["occlusionTexture"]["strength"] = material.occlusionStrength;
        }
        if (material.emissiveTexture.present()) out["emissiveTexture"] = textureInfo(material.emissiveTexture);
        if (material.emissiveFactor != glm::vec3(0.0f)) out["emissiveFactor"] = vec3(material.emissiveFactor);
        if (material.emissiveStrength != 1.0f) {
            out["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", material.emissiveStrength}};
            extensionsUsed.insert("KHR_materials_emissive_strength");
        }
        if (material.unlit) {
            out["extensions"]["KHR_materials_unlit"] = json::object();
            extensionsUsed.insert("KHR_materials_unlit");
        }
        if (material.alphaMode == AlphaMode::Mask) {
            out["alphaMode"] = "MASK";
            out["alphaCutoff"] = material.alphaCutoff;
        } else if (material.alphaMode == AlphaMode::Blend) {
            out["alphaMode"] = "BLEND";
        }
        if (material.doubleSided) out["doubleSided"] = true;
        materials.push_back(std::move(out));
    }
    json images = json::array();
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        const std::string uri = pngDataUri(scene.textures[t]);
        json image = {{"name", scene.textures[t].name}};
        if (binary) {
            const std::vector<unsigned char> png = base64Decode(uri.substr(uri.find(',') + 1));
            image["bufferView"] = writer.addView(png.data(), png.size(), 0);
            image["mimeType"] = "image/png";
        } else {
            image["uri"] = uri;
        }
        images.push_back(std::move(image));
    }

    json sceneJson = {{"nodes", roots}};
    if (!scene.name.empty()) sceneJson["name"] = scene.name;
    if (!scene.paths.empty()) sceneJson["extras"] = {{"lodopt_camera_paths", cameraPathsJson(scene.paths)}};
    json document = {{"asset", {{"version", "2.0"}, {"generator", "lodopt"}}}, {"scene", 0}, {"scenes", json::array({sceneJson})}};
    if (options.coverage == CoverageConvention::UnityRelativeHeight) {
        document["asset"]["extras"] = {
            {"lodopt_screencoverage", "unity_relative_height"},
            {"lodopt_screencoverage_note",
             "MSFT_screencoverage[k]: level k is drawn while the object's bounds' largest extent over the view height "
             "is at least this value (UnityGLTF's LOD.screenRelativeTransitionHeight); the last level's 0 never culls"}};
    }
    if (!nodes.empty()) document["nodes"] = nodes;
    if (!meshes.empty()) document["meshes"] = meshes;
    if (!materials.empty()) document["materials"] = materials;
    if (!textures.empty()) document["textures"] = textures;
    if (!samplers.empty()) document["samplers"] = samplers;
    if (!images.empty()) document["images"] = images;
    if (!cameras.empty()) document["cameras"] = cameras;
    if (anyLods) extensionsUsed.insert("MSFT_lod");
    if (!extensionsUsed.empty()) document["extensionsUsed"] = extensionsUsed;
    std::vector<unsigned char>& bin = writer.bytes();
    while (bin.size() % 4 != 0) bin.push_back(0);
    if (!bin.empty()) {
        json buffer = {{"byteLength", bin.size()}};
        if (!binary) buffer["uri"] = "data:application/octet-stream;base64," + base64Encode(bin.data(), bin.size());
        document["buffers"] = json::array({buffer});
        document["bufferViews"] = writer.views();
        document["accessors"] = writer.accessors();
    }

    std::string text = document.dump(binary ? -1 : 1);
    writeFileAtomically(path, [&](const std::string& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        if (!out) throw SceneError(path + ": cannot open for writing");
        if (binary) {
            while (text.size() % 4 != 0) text.push_back(' ');  // GLB pads JSON with spaces
            const std::uint32_t total = 12 + 8 + std::uint32_t(text.size()) + (bin.empty() ? 0 : 8 + std::uint32_t(bin.size()));
            const std::uint32_t header[3] = {0x46546C67u, 2u, total};
            const std::uint32_t jsonChunk[2] = {std::uint32_t(text.size()), 0x4E4F534Au};
            out.write(reinterpret_cast<const char*>(header), sizeof(header));
            out.write(reinterpret_cast<const char*>(jsonChunk), sizeof(jsonChunk));
            out.write(text.data(), static_cast<std::streamsize>(text.size()));
            if (!bin.empty()) {
                const std::uint32_t binChunk[2] = {std::uint32_t(bin.size()), 0x004E4942u};
                out.write(reinterpret_cast<const char*>(binChunk), sizeof(binChunk));
                out.write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
            }
        } else {
            out.write(text.data(), static_cast<std::streamsize>(text.size()));
        }
        out.close();
        if (!out) throw SceneError(path + ": write failed");
    });
}

}  // namespace lodopt::scenes
