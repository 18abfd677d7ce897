#include "pbr_pass.hpp"

#include <algorithm>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

namespace lodopt::renderer {
namespace {

GLint glWrap(scenes::WrapMode mode) {
    switch (mode) {
        case scenes::WrapMode::ClampToEdge:
            return GL_CLAMP_TO_EDGE;
        case scenes::WrapMode::MirroredRepeat:
            return GL_MIRRORED_REPEAT;
        case scenes::WrapMode::Repeat:
            break;
    }
    return GL_REPEAT;
}

GLint glMinFilter(const scenes::SamplerState& state) {
    const bool linear = state.minFilter == scenes::FilterMode::Linear;
    switch (state.mipmap) {
        case scenes::MipmapMode::None:
            return linear ? GL_LINEAR : GL_NEAREST;
        case scenes::MipmapMode::Nearest:
            return linear ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
        case scenes::MipmapMode::Linear:
            break;
    }
    return linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
}

// The Material's maps in the PBR program's texture-unit order.
std::array<const scenes::TextureRef*, shaders::kTextureUnits> mapsOf(const scenes::Material& material) {
    return {&material.baseColorTexture, &material.metallicRoughnessTexture, &material.normalTexture,
            &material.occlusionTexture, &material.emissiveTexture};
}

// Base color and emissive hold sRGB-encoded values (spec §3.9.2, §3.9.3): GL decodes them
// before filtering, as engines do. The other maps are linear data.
bool isSrgbUnit(int unit) {
    return unit == shaders::kBaseColorUnit || unit == shaders::kEmissiveUnit;
}

}  // namespace

PbrPass::PbrPass(const scenes::Scene& scene, const RenderSettings& settings) : mScene(scene), mSettings(settings) {
    mProgram = gl::linkProgram(shaders::kPbrVertex, shaders::kPbrFragment);
    auto at = [&](const char* name) { return glGetUniformLocation(mProgram, name); };
    mUniforms = {at("uModel"),           at("uModelViewProjection"), at("uNormalMatrix"),
                 at("uMirror"),          at("uMapPresent"),          at("uMapUvSet"),
                 at("uMapTransform"),    at("uBaseColorFactor"),     at("uMetallicFactor"),
                 at("uRoughnessFactor"), at("uNormalScale"),         at("uOcclusionStrength"),
                 at("uEmissive"),        at("uAlphaMode"),           at("uAlphaCutoff"),
                 at("uUnlit"),           at("uCameraPosition"),      at("uToLight"),
                 at("uKeyIrradiance"),   at("uSkyIrradiance"),       at("uGroundIrradiance")};
    glUseProgram(mProgram);
    const char* samplerNames[shaders::kTextureUnits] = {"uBaseColorMap", "uMetallicRoughnessMap", "uNormalMap",
                                                        "uOcclusionMap", "uEmissiveMap"};
    for (int unit = 0; unit < shaders::kTextureUnits; ++unit) glUniform1i(at(samplerNames[unit]), unit);
    glUseProgram(0);
    gl::checkGl("PBR program set-up");
    // Each texture in the color space its slots read it in, sometimes both.
    std::vector<bool> linear(scene.textures.size(), false), srgb(scene.textures.size(), false);
    for (const scenes::Material& material : scene.materials) {
        const auto references = mapsOf(material);
        for (int unit = 0; unit < shaders::kTextureUnits; ++unit) {
            if (!references[unit]->present()) continue;
            (isSrgbUnit(unit) ? srgb : linear)[std::size_t(references[unit]->texture)] = true;
            samplerFor(references[unit]->sampler);
        }
    }
    mLinearTextures.assign(scene.textures.size(), 0);
    mSrgbTextures.assign(scene.textures.size(), 0);
    for (std::size_t t = 0; t < scene.textures.size(); ++t) {
        if (linear[t]) mLinearTextures[t] = gl::uploadTexture(scene.textures[t], GL_RGBA8);
        if (srgb[t]) mSrgbTextures[t] = gl::uploadTexture(scene.textures[t], GL_SRGB8_ALPHA8);
    }
}

PbrPass::~PbrPass() {
    for (const std::vector<GLuint>* pool : {&mLinearTextures, &mSrgbTextures}) {
        for (GLuint texture : *pool) {
            if (texture != 0) glDeleteTextures(1, &texture);
        }
    }
    for (const auto& [state, sampler] : mSamplers) glDeleteSamplers(1, &sampler);
    glDeleteProgram(mProgram);
}

GLuint PbrPass::samplerFor(const scenes::SamplerState& state) {
    const auto key = std::make_tuple(int(state.wrapS), int(state.wrapT), int(state.magFilter), int(state.minFilter),
                                     int(state.mipmap));
    auto [entry, added] = mSamplers.try_emplace(key, 0);
    if (added) {
        glGenSamplers(1, &entry->second);
        glSamplerParameteri(entry->second, GL_TEXTURE_WRAP_S, glWrap(state.wrapS));
        glSamplerParameteri(entry->second, GL_TEXTURE_WRAP_T, glWrap(state.wrapT));
        glSamplerParameteri(entry->second, GL_TEXTURE_MAG_FILTER,
                            state.magFilter == scenes::FilterMode::Linear ? GL_LINEAR : GL_NEAREST);
        glSamplerParameteri(entry->second, GL_TEXTURE_MIN_FILTER, glMinFilter(state));
        gl::checkGl("sampler creation");
    }
    return entry->second;
}

// Engines' order: opaque and masked surfaces first (object order), then blended ones back
// to front by the distance of their object's bounds from the eye, without depth writes.
void PbrPass::draw(const scenes::Combination& combination, const scenes::Camera& camera,
                   const glm::mat4& viewProjection, const gl::GpuMeshes& meshes) {
    glUseProgram(mProgram);
    const glm::vec3 toLight = -glm::normalize(mSettings.lightDirection);
    const glm::vec3 keyIrradiance(mSettings.keyIlluminance);
    glUniform3fv(mUniforms.cameraPosition, 1, glm::value_ptr(camera.position));
    glUniform3fv(mUniforms.toLight, 1, glm::value_ptr(toLight));
    glUniform3fv(mUniforms.keyIrradiance, 1, glm::value_ptr(keyIrradiance));
    glUniform3fv(mUniforms.skyIrradiance, 1, glm::value_ptr(mSettings.skyIrradiance));
    glUniform3fv(mUniforms.groundIrradiance, 1, glm::value_ptr(mSettings.groundIrradiance));
    mBlended.clear();
    for (std::size_t o = 0; o < combination.size(); ++o) {
        const int level = combination[o];
        if (level == scenes::kNotDrawn) continue;
        if (drawObject(o, level, viewProjection, meshes, false)) {
            const scenes::Bounds bounds = scenes::worldBounds(mScene.objects[o], level);
            mBlended.emplace_back(glm::length(bounds.sphereCenter - camera.position), o);
        }
    }
    if (mBlended.empty()) return;
    std::sort(mBlended.begin(), mBlended.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    for (const auto& [distance, o] : mBlended) drawObject(o, combination[o], viewProjection, meshes, true);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

// Draws object `o`'s meshes whose material blends (`blendPass`) or does not; returns
// whether it has meshes of the other kind.
bool PbrPass::drawObject(std::size_t o, int level, const glm::mat4& viewProjection, const gl::GpuMeshes& meshes,
                         bool blendPass) {
    const glm::mat4& model = mScene.objects[o].transform;
    const glm::mat4 mvp = viewProjection * model;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
    const bool mirrored = glm::determinant(glm::mat3(model)) < 0.0f;
    glUniformMatrix4fv(mUniforms.model, 1, GL_FALSE, glm::value_ptr(model));
    glUniformMatrix4fv(mUniforms.modelViewProjection, 1, GL_FALSE, glm::value_ptr(mvp));
    glUniformMatrix3fv(mUniforms.normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
    glUniform1f(mUniforms.mirror, mirrored ? -1.0f : 1.0f);
    // A mirroring transform turns counter-clockwise front faces clockwise.
    glFrontFace(mirrored ? GL_CW : GL_CCW);
    static const scenes::Material kDefaultMaterial;
    bool otherKind = false;
    for (const gl::GpuMesh& mesh : meshes[o][level]) {
        const scenes::Material& material =
            mesh.material >= 0 ? mScene.materials[std::size_t(mesh.material)] : kDefaultMaterial;
        if ((material.alphaMode == scenes::AlphaMode::Blend) != blendPass) {
            otherKind = true;
            continue;
        }
        bindMaterial(material, mesh.hasTangents);
        glBindVertexArray(mesh.vertexArray);
        glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glFrontFace(GL_CCW);
    return otherKind;
}

void PbrPass::bindMaterial(const scenes::Material& material, bool hasTangents) {
    GLint present[shaders::kTextureUnits] = {}, uvSet[shaders::kTextureUnits] = {};
    float transforms[shaders::kTextureUnits * 9] = {};
    const auto maps = mapsOf(material);
    for (int unit = 0; unit < shaders::kTextureUnits; ++unit) {
        const scenes::TextureRef& map = *maps[unit];
        const bool usable = map.present() && (unit != shaders::kNormalUnit || hasTangents);
        present[unit] = usable ? 1 : 0;
        uvSet[unit] = map.texCoord;
        const glm::mat3 transform = map.transform.matrix();
        std::memcpy(&transforms[unit * 9], glm::value_ptr(transform), sizeof(float) * 9);
        glActiveTexture(GLenum(GL_TEXTURE0 + unit));
        const std::vector<GLuint>& pool = isSrgbUnit(unit) ? mSrgbTextures : mLinearTextures;
        glBindTexture(GL_TEXTURE_2D, usable ? pool[std::size_t(map.texture)] : 0);
        glBindSampler(GLuint(unit), usable ? samplerFor(map.sampler) : 0);
    }
    glUniform1iv(mUniforms.mapPresent, shaders::kTextureUnits, present);
    glUniform1iv(mUniforms.mapUvSet, shaders::kTextureUnits, uvSet);
    glUniformMatrix3fv(mUniforms.mapTransform, shaders::kTextureUnits, GL_FALSE, transforms);
    glUniform4fv(mUniforms.baseColorFactor, 1, glm::value_ptr(material.baseColorFactor));
    glUniform1f(mUniforms.metallicFactor, material.metallicFactor);
    glUniform1f(mUniforms.roughnessFactor, material.roughnessFactor);
    glUniform1f(mUniforms.normalScale, material.normalScale);
    glUniform1f(mUniforms.occlusionStrength, material.occlusionStrength);
    const glm::vec3 emissive = material.emissiveFactor * material.emissiveStrength;
    glUniform3fv(mUniforms.emissive, 1, glm::value_ptr(emissive));
    glUniform1i(mUniforms.alphaMode, int(material.alphaMode));
    glUniform1f(mUniforms.alphaCutoff, material.alphaCutoff);
    glUniform1i(mUniforms.unlit, material.unlit ? 1 : 0);
    // Single-sided materials cull back faces (spec §3.9.6); double-sided ones light them
    // with the reversed normal.
    if (material.doubleSided) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
    }
}

}  // namespace lodopt::renderer
