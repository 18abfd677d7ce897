// Materials, textures, views and camera paths of the glTF loader (the SceneBuilder parts
// that are not geometry). Materials are glTF 2.0 metallic-roughness (spec §3.9) with their
// samplers, KHR_texture_transform, KHR_materials_emissive_strength and KHR_materials_unlit;
// KHR_materials_pbrSpecularGlossiness becomes a dielectric with its diffuse as base color.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>
#include <webp/decode.h>

#include "gltf_scene_builder.hpp"

namespace lodopt::scenes::gltf_detail {

namespace {

constexpr const char* kSpecGloss = "KHR_materials_pbrSpecularGlossiness";

// The glTF texture index of a material's base color, -1 for none.
int baseColorTextureOf(const tinygltf::Material& material) {
    auto specGloss = material.extensions.find(kSpecGloss);
    if (specGloss != material.extensions.end() && specGloss->second.Has("diffuseTexture")) {
        const tinygltf::Value& index = specGloss->second.Get("diffuseTexture").Get("index");
        return index.IsNumber() ? index.GetNumberAsInt() : -2;
    }
    return material.pbrMetallicRoughness.baseColorTexture.index;
}

glm::vec4 baseColorFactorOf(const tinygltf::Material& material) {
    std::vector<double> factor = material.pbrMetallicRoughness.baseColorFactor;
    auto specGloss = material.extensions.find(kSpecGloss);
    if (specGloss != material.extensions.end() && specGloss->second.Has("diffuseFactor")) {
        const tinygltf::Value& diffuse = specGloss->second.Get("diffuseFactor");
        if (diffuse.IsArray() && diffuse.ArrayLen() == 4) {
            factor.clear();
            for (int i = 0; i < 4; ++i) factor.push_back(diffuse.Get(i).GetNumberAsDouble());
        }
    }
    glm::vec4 color(1.0f);
    for (int i = 0; i < 4 && i < static_cast<int>(factor.size()); ++i) {
        color[i] = std::isfinite(factor[i]) ? static_cast<float>(factor[i]) : 1.0f;
    }
    return color;
}

float finiteOr(double value, float fallback) {
    return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

WrapMode wrapMode(int code) {
    if (code == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return WrapMode::ClampToEdge;
    if (code == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return WrapMode::MirroredRepeat;
    return WrapMode::Repeat;
}

// glTF samplers (spec §3.8.4); an undefined filter leaves the choice to the renderer, and
// lodopt then filters linearly with trilinear mipmaps as engines commonly do.
SamplerState samplerState(const tinygltf::Sampler& sampler) {
    SamplerState state;
    state.wrapS = wrapMode(sampler.wrapS);
    state.wrapT = wrapMode(sampler.wrapT);
    if (sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) state.magFilter = FilterMode::Nearest;
    switch (sampler.minFilter) {
        case TINYGLTF_TEXTURE_FILTER_NEAREST:
        case TINYGLTF_TEXTURE_FILTER_LINEAR: state.mipmap = MipmapMode::None; break;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: state.mipmap = MipmapMode::Nearest; break;
        default: break;  // *_MIPMAP_LINEAR or undefined
    }
    if (sampler.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ||
        sampler.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
        sampler.minFilter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR) {
        state.minFilter = FilterMode::Nearest;
    }
    return state;
}

// Width and height from a PNG's IHDR, to refuse a decompression bomb before decoding.
bool pngSize(const std::vector<unsigned char>& bytes, std::uint64_t& width, std::uint64_t& height) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (bytes.size() < 24 || std::memcmp(bytes.data(), kSignature, 8) != 0) return false;
    auto be32 = [&](std::size_t at) {
        return (std::uint64_t(bytes[at]) << 24) | (std::uint64_t(bytes[at + 1]) << 16) |
               (std::uint64_t(bytes[at + 2]) << 8) | std::uint64_t(bytes[at + 3]);
    };
    width = be32(16);
    height = be32(20);
    return true;
}

// Width and height from a JPEG's frame header (SOF0..SOF15 but DHT, JPG and DAC), walking
// the marker segments before the first scan. False when there is none.
bool jpegSize(const std::vector<unsigned char>& bytes, std::uint64_t& width, std::uint64_t& height) {
    if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return false;
    std::size_t at = 2;
    while (at + 4 <= bytes.size()) {
        if (bytes[at] != 0xFF) return false;
        const unsigned char marker = bytes[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) {  // no length
            at += 2;
            continue;
        }
        if (marker == 0xDA || marker == 0xD9) return false;  // a scan or the end before any frame
        const std::size_t length = (std::size_t(bytes[at + 2]) << 8) | bytes[at + 3];
        const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame) {
            if (at + 9 > bytes.size()) return false;
            height = (std::uint64_t(bytes[at + 5]) << 8) | bytes[at + 6];
            width = (std::uint64_t(bytes[at + 7]) << 8) | bytes[at + 8];
            return true;
        }
        if (length < 2) return false;
        at += 2 + length;
    }
    return false;
}

// Width and height from a WebP's RIFF header (VP8, VP8L or VP8X chunk, libwebp's
// WebPGetInfo reads no pixels). False when the bytes are not a WebP file.
bool webpSize(const std::vector<unsigned char>& bytes, std::uint64_t& width, std::uint64_t& height) {
    if (bytes.size() < 12 || std::memcmp(bytes.data(), "RIFF", 4) != 0 || std::memcmp(bytes.data() + 8, "WEBP", 4) != 0) {
        return false;
    }
    int w = 0, h = 0;
    if (!WebPGetInfo(bytes.data(), bytes.size(), &w, &h) || w <= 0 || h <= 0) return false;
    width = static_cast<std::uint64_t>(w);
    height = static_cast<std::uint64_t>(h);
    return true;
}

glm::vec3 jsonVec3(const nlohmann::json& value, const std::string& file, const std::string& where) {
    if (!value.is_array() || value.size() != 3) fail(file, where, "expected an array of 3 numbers");
    glm::vec3 v;
    for (int i = 0; i < 3; ++i) {
        if (!value[i].is_number() || !std::isfinite(value[i].get<double>())) fail(file, where, "expected finite numbers");
        v[i] = value[i].get<float>();
    }
    return v;
}

float jsonFloat(const nlohmann::json& object, const char* key, float fallback, const std::string& file,
                const std::string& where) {
    if (!object.contains(key)) return fallback;
    const nlohmann::json& value = object[key];
    if (!value.is_number() || !std::isfinite(value.get<double>())) fail(file, where + "." + key, "expected a finite number");
    return value.get<float>();
}

}  // namespace

Texture SceneBuilder::decodeImage(int imageIndex) {
    const tinygltf::Image& image = mModel.images[imageIndex];
    const std::string where = element("images", imageIndex);
    Texture texture;
    texture.name = image.name;
    if (texture.name.empty() && !image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
        texture.name = std::filesystem::path(image.uri).stem().string();
    }
    if (texture.name.empty()) texture.name = "image" + std::to_string(imageIndex);
    if (static_cast<std::size_t>(imageIndex) >= mEncodedImages.size() || mEncodedImages[imageIndex].empty()) {
        std::string reason = "no image data (missing bufferView data)";
        if (!image.uri.empty()) {
            reason = "no image data ('";
            reason.append(image.uri, 0, 64);
            reason += "' could not be read)";
        }
        fail(mFile, where, reason);
    }
    const std::vector<unsigned char>& bytes = mEncodedImages[imageIndex];
    // glTF 2.0 images are PNG or JPEG, and WebP with EXT_texture_webp; stb_image would also
    // decode BMP, PSD, TGA, ... whose headers are not checked here. The decoded size is checked
    // before any decoder allocates.
    std::uint64_t width = 0, height = 0, bytesPerPixel = 4;
    bool webp = false;
    if (pngSize(bytes, width, height)) {
        if (bytes.size() > 24 && bytes[24] == 16) bytesPerPixel = 8;
    } else if (!jpegSize(bytes, width, height)) {
        webp = webpSize(bytes, width, height);
        if (!webp) {
            fail(mFile, where, "cannot be decoded as PNG, JPEG or WebP (no PNG header, JPEG frame header or WebP header)");
        }
    }
    if (width * height * bytesPerPixel > mOptions.maxBytes) {
        fail(mFile, where, std::to_string(width) + "x" + std::to_string(height) + " pixels is over the byte limit");
    }
    if (webp) {
        int decodedWidth = 0, decodedHeight = 0;
        std::uint8_t* pixels = WebPDecodeRGBA(bytes.data(), bytes.size(), &decodedWidth, &decodedHeight);
        if (!pixels) fail(mFile, where, "cannot be decoded as WebP (corrupt or truncated data)");
        texture.width = decodedWidth;
        texture.height = decodedHeight;
        texture.rgba.assign(pixels, pixels + std::size_t(decodedWidth) * std::size_t(decodedHeight) * 4);
        WebPFree(pixels);
        mEncodedImages[imageIndex].clear();
        mEncodedImages[imageIndex].shrink_to_fit();
        return texture;
    }
    tinygltf::Image decoded;
    std::string error, warning;
    if (!tinygltf::LoadImageData(&decoded, imageIndex, &error, &warning, 0, 0, bytes.data(), static_cast<int>(bytes.size()),
                                 nullptr)) {
        fail(mFile, where, "cannot be decoded as PNG or JPEG");
    }
    const std::size_t pixels = std::size_t(decoded.width) * std::size_t(decoded.height);
    if (decoded.component != 4 || (decoded.bits != 8 && decoded.bits != 16) ||
        decoded.image.size() != pixels * 4 * (decoded.bits / 8)) {
        fail(mFile, where, "unexpected decoded pixel layout");
    }
    texture.width = decoded.width;
    texture.height = decoded.height;
    if (decoded.bits == 8) {
        texture.rgba = std::move(decoded.image);
    } else {
        texture.rgba.resize(pixels * 4);
        for (std::size_t i = 0; i < pixels * 4; ++i) {
            std::uint16_t value;
            std::memcpy(&value, decoded.image.data() + 2 * i, 2);
            texture.rgba[i] = static_cast<std::uint8_t>((value + 128u) / 257u);
        }
    }
    mEncodedImages[imageIndex].clear();
    mEncodedImages[imageIndex].shrink_to_fit();
    return texture;
}

int SceneBuilder::sceneTexture(int gltfTexture, const std::string& where) {
    if (gltfTexture == -1) return -1;
    if (gltfTexture < 0 || gltfTexture >= static_cast<int>(mModel.textures.size())) {
        fail(mFile, where, "texture " + std::to_string(gltfTexture) + " does not exist");
    }
    const int source = mModel.textures[gltfTexture].source;
    if (source < 0) {
        warn(where + ": texture " + std::to_string(gltfTexture) + " has no source image; ignored");
        return -1;
    }
    return mImageToTexture[source];
}

void SceneBuilder::buildMaterials() {
    // Decode the images materials use, in image order, so that an exported scene (texture i is
    // image i) loads back with the same texture indices.
    std::set<int> images;
    auto addImageOf = [&](int texture) {
        if (texture >= 0 && texture < static_cast<int>(mModel.textures.size()) && mModel.textures[texture].source >= 0) {
            images.insert(mModel.textures[texture].source);
        }
    };
    for (const tinygltf::Material& material : mModel.materials) {
        addImageOf(baseColorTextureOf(material));
        addImageOf(material.pbrMetallicRoughness.metallicRoughnessTexture.index);
        addImageOf(material.normalTexture.index);
        addImageOf(material.occlusionTexture.index);
        addImageOf(material.emissiveTexture.index);
    }
    mImageToTexture.assign(mModel.images.size(), -1);
    for (int image : images) {
        mImageToTexture[image] = static_cast<int>(mScene.textures.size());
        mScene.textures.push_back(decodeImage(image));
    }
    for (int m = 0; m < static_cast<int>(mModel.materials.size()); ++m) {
        mScene.materials.push_back(buildMaterial(m));
    }
}

Material SceneBuilder::buildMaterial(int index) {
    const tinygltf::Material& source = mModel.materials[index];
    const std::string where = element("materials", index);
    Material material;
    material.name = source.name.empty() ? "material" + std::to_string(index) : source.name;
    const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
    material.baseColorFactor = baseColorFactorOf(source);
    material.baseColorTexture =
        textureRef(baseColorTextureOf(source), pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions,
                   where + ".pbrMetallicRoughness.baseColorTexture");
    material.metallicFactor = finiteOr(pbr.metallicFactor, 1.0f);
    material.roughnessFactor = finiteOr(pbr.roughnessFactor, 1.0f);
    material.metallicRoughnessTexture =
        textureRef(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                   pbr.metallicRoughnessTexture.extensions, where + ".pbrMetallicRoughness.metallicRoughnessTexture");
    if (auto specGloss = source.extensions.find(kSpecGloss); specGloss != source.extensions.end()) {
        // Specular-glossiness drawn as a dielectric with the diffuse color as base color.
        const tinygltf::Value& glossiness = specGloss->second.Get("glossinessFactor");
        material.metallicFactor = 0.0f;
        material.roughnessFactor = glossiness.IsNumber() ? 1.0f - float(glossiness.GetNumberAsDouble()) : 0.0f;
        material.metallicRoughnessTexture = {};
    }
    material.normalTexture = textureRef(source.normalTexture.index, source.normalTexture.texCoord,
                                        source.normalTexture.extensions, where + ".normalTexture");
    material.normalScale = finiteOr(source.normalTexture.scale, 1.0f);
    material.occlusionTexture = textureRef(source.occlusionTexture.index, source.occlusionTexture.texCoord,
                                           source.occlusionTexture.extensions, where + ".occlusionTexture");
    material.occlusionStrength = std::clamp(finiteOr(source.occlusionTexture.strength, 1.0f), 0.0f, 1.0f);
    material.emissiveTexture = textureRef(source.emissiveTexture.index, source.emissiveTexture.texCoord,
                                          source.emissiveTexture.extensions, where + ".emissiveTexture");
    for (int c = 0; c < 3 && c < static_cast<int>(source.emissiveFactor.size()); ++c) {
        material.emissiveFactor[c] = std::max(finiteOr(source.emissiveFactor[c], 0.0f), 0.0f);
    }
    if (auto strength = source.extensions.find("KHR_materials_emissive_strength");
        strength != source.extensions.end()) {
        const tinygltf::Value& value = strength->second.Get("emissiveStrength");
        if (value.IsNumber()) material.emissiveStrength = std::max(finiteOr(value.GetNumberAsDouble(), 1.0f), 0.0f);
    }
    if (source.alphaMode == "MASK") {
        material.alphaMode = AlphaMode::Mask;
    } else if (source.alphaMode == "BLEND") {
        material.alphaMode = AlphaMode::Blend;
    } else if (!source.alphaMode.empty() && source.alphaMode != "OPAQUE") {
        fail(mFile, where + ".alphaMode", "'" + source.alphaMode + "' is not OPAQUE, MASK or BLEND");
    }
    material.alphaCutoff = std::max(finiteOr(source.alphaCutoff, 0.5f), 0.0f);
    material.doubleSided = source.doubleSided;
    material.unlit = source.extensions.count("KHR_materials_unlit") > 0;
    return material;
}

TextureRef SceneBuilder::textureRef(int gltfTexture, int texCoord, const tinygltf::ExtensionMap& extensions,
                                    const std::string& where) {
    TextureRef reference;
    reference.texture = sceneTexture(gltfTexture, where);
    if (!reference.present()) return {};
    reference.texCoord = texCoord;
    if (auto transform = extensions.find("KHR_texture_transform"); transform != extensions.end()) {
        const tinygltf::Value& value = transform->second;
        auto pair = [&](const char* key, glm::vec2 fallback) {
            const tinygltf::Value& entry = value.Get(key);
            if (!entry.IsArray() || entry.ArrayLen() != 2) return fallback;
            return glm::vec2(finiteOr(entry.Get(0).GetNumberAsDouble(), fallback.x),
                             finiteOr(entry.Get(1).GetNumberAsDouble(), fallback.y));
        };
        reference.transform.offset = pair("offset", glm::vec2(0.0f));
        reference.transform.scale = pair("scale", glm::vec2(1.0f));
        if (value.Get("rotation").IsNumber()) {
            reference.transform.rotation = finiteOr(value.Get("rotation").GetNumberAsDouble(), 0.0f);
        }
        if (value.Get("texCoord").IsNumber()) reference.texCoord = value.Get("texCoord").GetNumberAsInt();
    }
    if (reference.texCoord < 0 || reference.texCoord > 1) {
        warn(where + ": uses TEXCOORD_" + std::to_string(reference.texCoord) +
             "; lodopt reads TEXCOORD_0 and _1, so TEXCOORD_0");
        reference.texCoord = 0;
    }
    const int sampler = mModel.textures[gltfTexture].sampler;
    if (sampler >= 0 && sampler < static_cast<int>(mModel.samplers.size())) {
        reference.sampler = samplerState(mModel.samplers[sampler]);
    }
    return reference;
}

void SceneBuilder::buildViews() {
    Bounds sceneBounds;
    sceneBounds.min = glm::vec3(std::numeric_limits<float>::max());
    sceneBounds.max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Object& object : mScene.objects) {
        if (object.levels[0].stats.bounds.empty()) continue;
        const Bounds world = worldBounds(object, 0);
        sceneBounds.min = glm::min(sceneBounds.min, world.min);
        sceneBounds.max = glm::max(sceneBounds.max, world.max);
    }
    const bool haveBounds = !sceneBounds.empty();
    const glm::vec3 center = haveBounds ? 0.5f * (sceneBounds.min + sceneBounds.max) : glm::vec3(0.0f);
    const float radius = haveBounds ? 0.5f * glm::length(sceneBounds.max - sceneBounds.min) : 0.0f;

    for (const auto& [node, world] : mCameraNodes) {
        const tinygltf::Node& n = mModel.nodes[node];
        const tinygltf::Camera& source = mModel.cameras[n.camera];
        const std::string where = element("nodes", node) + " (" + element("cameras", n.camera) + ")";
        if (source.type != "perspective") {
            warn(where + ": " + source.type + " camera ignored (lodopt views are perspective)");
            continue;
        }
        const auto& perspective = source.perspective;
        if (!(perspective.yfov > 0.0 && perspective.yfov < M_PI) || !(perspective.znear > 0.0) ||
            !(perspective.zfar == 0.0 || perspective.zfar > perspective.znear)) {
            fail(mFile, where, "perspective needs 0 < yfov < pi and 0 < znear < zfar");
        }
        Camera camera;
        camera.name = !n.name.empty() ? n.name : (!source.name.empty() ? source.name : "camera" + std::to_string(n.camera));
        camera.position = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        // glTF cameras look down their local -Z with +Y up (spec §3.10.1).
        glm::vec3 forward = glm::vec3(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
        glm::vec3 up = glm::vec3(world * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
        if (!(glm::length(forward) > 1e-12f) || !(glm::length(up) > 1e-12f)) {
            warn(where + ": degenerate camera transform; ignored");
            continue;
        }
        forward = glm::normalize(forward);
        camera.up = glm::normalize(up);
        camera.fovYDegrees = static_cast<float>(perspective.yfov * 180.0 / M_PI);
        camera.nearPlane = static_cast<float>(perspective.znear);
        // An infinite projection (no zfar) gets a far plane behind the whole scene.
        const float reach = glm::length(center - camera.position) + radius;
        camera.farPlane = perspective.zfar > 0.0 ? static_cast<float>(perspective.zfar)
                                                 : std::max(camera.nearPlane * 1000.0f, 2.0f * reach);
        // The target only fixes the direction; keep the one lodopt wrote, else aim at the
        // depth of the scene's center (or one unit ahead).
        float depth = glm::dot(center - camera.position, forward);
        if (!(depth > camera.nearPlane)) depth = 1.0f;
        camera.target = camera.position + forward * depth;
        if (n.extras.IsObject() && n.extras.Has("lodopt_target")) {
            std::optional<std::vector<float>> target;
            const tinygltf::Value& value = n.extras.Get("lodopt_target");
            if (value.IsArray() && value.ArrayLen() == 3) {
                glm::vec3 t(value.Get(0).GetNumberAsDouble(), value.Get(1).GetNumberAsDouble(), value.Get(2).GetNumberAsDouble());
                if (std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z) && glm::length(t - camera.position) > 0.0f) {
                    camera.target = t;
                }
            }
        }
        mScene.views.push_back(camera);
    }
}

void SceneBuilder::buildPaths(int sceneIndex) {
    const std::string& text = mModel.scenes[sceneIndex].extras_json_string;
    if (text.empty()) return;
    const std::string where = element("scenes", sceneIndex) + ".extras.lodopt_camera_paths";
    nlohmann::json extras = nlohmann::json::parse(text, nullptr, false);
    if (extras.is_discarded() || !extras.is_object() || !extras.contains("lodopt_camera_paths")) return;
    const nlohmann::json& paths = extras["lodopt_camera_paths"];
    if (!paths.is_array()) fail(mFile, where, "expected an array");
    for (std::size_t p = 0; p < paths.size(); ++p) {
        const nlohmann::json& source = paths[p];
        const std::string at = where + "[" + std::to_string(p) + "]";
        if (!source.is_object() || !source.contains("frames") || !source["frames"].is_array()) {
            fail(mFile, at, "expected an object with a frames array");
        }
        CameraPath path;
        if (source.contains("name") && source["name"].is_string()) path.name = source["name"].get<std::string>();
        path.framesPerSecond = jsonFloat(source, "fps", 30.0f, mFile, at);
        if (!(path.framesPerSecond > 0.0f)) fail(mFile, at + ".fps", "must be > 0");
        const nlohmann::json& frames = source["frames"];
        for (std::size_t f = 0; f < frames.size(); ++f) {
            const nlohmann::json& frame = frames[f];
            const std::string fat = at + ".frames[" + std::to_string(f) + "]";
            if (!frame.is_object() || !frame.contains("position") || !frame.contains("target")) {
                fail(mFile, fat, "expected an object with position and target");
            }
            Camera camera;
            camera.name = path.name + "#" + std::to_string(f);
            if (frame.contains("name") && frame["name"].is_string()) camera.name = frame["name"].get<std::string>();
            camera.position = jsonVec3(frame["position"], mFile, fat + ".position");
            camera.target = jsonVec3(frame["target"], mFile, fat + ".target");
            if (frame.contains("up")) camera.up = jsonVec3(frame["up"], mFile, fat + ".up");
            camera.fovYDegrees = jsonFloat(frame, "fov", camera.fovYDegrees, mFile, fat);
            camera.nearPlane = jsonFloat(frame, "near", camera.nearPlane, mFile, fat);
            camera.farPlane = jsonFloat(frame, "far", camera.farPlane, mFile, fat);
            if (!(camera.fovYDegrees > 0.0f && camera.fovYDegrees < 180.0f) || !(camera.nearPlane > 0.0f) ||
                !(camera.farPlane > camera.nearPlane)) {
                fail(mFile, fat, "needs 0 < fov < 180 and 0 < near < far");
            }
            path.frames.push_back(camera);
        }
        mScene.paths.push_back(std::move(path));
    }
}

}  // namespace lodopt::scenes::gltf_detail
