#include "pbr_pass.hpp"

#include <algorithm>
#include <cstring>
#include <string>
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

PbrPass::Program PbrPass::linkPbrProgram(const char* fragmentSource) {
    Program program;
    program.id = gl::linkProgram(shaders::kPbrVertex, fragmentSource);
    auto at = [&](const char* name) { return glGetUniformLocation(program.id, name); };
    program.uniforms = {at("uModel"),           at("uModelViewProjection"), at("uNormalMatrix"),
                        at("uMirror"),          at("uMapPresent"),          at("uMapUvSet"),
                        at("uMapTransform"),    at("uBaseColorFactor"),     at("uMetallicFactor"),
                        at("uRoughnessFactor"), at("uNormalScale"),         at("uOcclusionStrength"),
                        at("uEmissive"),        at("uAlphaMode"),           at("uAlphaCutoff"),
                        at("uUnlit"),           at("uCameraPosition"),      at("uToLight"),
                        at("uKeyIrradiance"),   at("uSkyIrradiance"),       at("uGroundIrradiance")};
    program.uniforms.flatNormals = at("uFlatNormals");
    program.drawIndex = at("uDrawIndex");
    glUseProgram(program.id);
    const char* samplerNames[shaders::kTextureUnits] = {"uBaseColorMap", "uMetallicRoughnessMap", "uNormalMap",
                                                        "uOcclusionMap", "uEmissiveMap"};
    for (int unit = 0; unit < shaders::kTextureUnits; ++unit) glUniform1i(at(samplerNames[unit]), unit);
    glUseProgram(0);
    gl::checkGl("PBR program set-up");
    return program;
}

PbrPass::PbrPass(const scenes::Scene& scene, const RenderSettings& settings) : mScene(scene), mSettings(settings) {
    mMain = linkPbrProgram(shaders::kPbrFragment);
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
    mBlends.resize(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        for (const scenes::Level& level : scene.objects[o].levels) {
            const bool blended = std::any_of(level.meshes.begin(), level.meshes.end(), [&](const scenes::Mesh& mesh) {
                return mesh.material >= 0 && !mesh.indices.empty() &&
                       scene.materials[std::size_t(mesh.material)].alphaMode == scenes::AlphaMode::Blend;
            });
            mBlends[o].push_back(blended ? 1 : 0);
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
    if (mFragmentBuffer != 0) glDeleteBuffers(1, &mFragmentBuffer);
    if (mFragmentList.id != 0) glDeleteProgram(mFragmentList.id);
    glDeleteProgram(mMain.id);
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

float PbrPass::blendDistance(std::size_t object, int level, const scenes::Camera& camera) const {
    return glm::length(scenes::worldBounds(mScene.objects[object], level).sphereCenter - camera.position);
}

void PbrPass::use(Program& program, const scenes::Camera& camera) {
    mActive = &program;
    glUseProgram(program.id);
    const Uniforms& u = program.uniforms;
    const glm::vec3 toLight = -glm::normalize(mSettings.lightDirection);
    const glm::vec3 keyIrradiance(mSettings.keyIlluminance);
    glUniform3fv(u.cameraPosition, 1, glm::value_ptr(camera.position));
    glUniform3fv(u.toLight, 1, glm::value_ptr(toLight));
    glUniform3fv(u.keyIrradiance, 1, glm::value_ptr(keyIrradiance));
    glUniform3fv(u.skyIrradiance, 1, glm::value_ptr(mSettings.skyIrradiance));
    glUniform3fv(u.groundIrradiance, 1, glm::value_ptr(mSettings.groundIrradiance));
}

void PbrPass::sortBlended(const scenes::Combination& combination, const scenes::Camera& camera) {
    mBlended.clear();
    for (std::size_t o = 0; o < combination.size(); ++o) {
        const int level = combination[o];
        if (level != scenes::kNotDrawn && blends(o, level)) mBlended.emplace_back(blendDistance(o, level, camera), o);
    }
    std::sort(mBlended.begin(), mBlended.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
}

// Engines' order: opaque and masked surfaces first (object order), then blended ones back
// to front by blendDistance, without depth writes.
void PbrPass::draw(const scenes::Combination& combination, const scenes::Camera& camera,
                   const glm::mat4& viewProjection, const gl::GpuMeshes& meshes, Surfaces surfaces) {
    use(mMain, camera);
    if (surfaces != Surfaces::Blended) {
        for (std::size_t o = 0; o < combination.size(); ++o) {
            if (combination[o] != scenes::kNotDrawn) drawObject(o, combination[o], viewProjection, meshes, false);
        }
    }
    if (surfaces == Surfaces::Opaque) return;
    sortBlended(combination, camera);
    if (mBlended.empty()) return;
    // Over transparent black this blending leaves the color premultiplied by the coverage and
    // the coverage in alpha, which composite() then lays over what is behind.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    for (const auto& [distance, o] : mBlended) drawObject(o, combination[o], viewProjection, meshes, true);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

std::vector<PbrPass::ListedFragment> PbrPass::listBlendedFragments(const scenes::Combination& combination,
                                                                   const scenes::Camera& camera,
                                                                   const glm::mat4& viewProjection,
                                                                   const gl::GpuMeshes& meshes) {
    static_assert(sizeof(ListedFragment) == 20, "the layout of the shader's std430 ListedFragment");
    if (mFragmentList.id == 0) {
        // The same source with its first line (#version) replaced.
        const std::string source =
            std::string(shaders::kPbrFragmentListVersion) + (std::strchr(shaders::kPbrFragment, '\n') + 1);
        mFragmentList = linkPbrProgram(source.c_str());
        glGenBuffers(1, &mFragmentBuffer);
    }
    sortBlended(combination, camera);
    std::vector<ListedFragment> fragments;
    if (mBlended.empty()) return fragments;
    const std::size_t header = 2 * sizeof(std::uint32_t);
    // A first pass counts (or fits); a second, when the buffer was too small, fits.
    for (int attempt = 0; attempt < 2; ++attempt) {
        if (mFragmentCapacity == 0) mFragmentCapacity = std::size_t(1) << 16;
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, mFragmentBuffer);
        const std::uint32_t start[2] = {0, std::uint32_t(mFragmentCapacity)};
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(header + mFragmentCapacity * sizeof(ListedFragment)),
                     nullptr, GL_DYNAMIC_READ);
        glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(header), start);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, mFragmentBuffer);
        use(mFragmentList, camera);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glDepthMask(GL_FALSE);
        mDrawIndex = 0;
        for (const auto& [distance, o] : mBlended) drawObject(o, combination[o], viewProjection, meshes, true);
        glDepthMask(GL_TRUE);
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        std::uint32_t count = 0;
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(count), &count);
        gl::checkGl("blended fragment list");
        if (count <= mFragmentCapacity) {
            fragments.resize(count);
            if (count > 0) {
                glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, GLintptr(header), GLsizeiptr(count * sizeof(ListedFragment)),
                                   fragments.data());
            }
            glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
            mActive = &mMain;
            return fragments;
        }
        mFragmentCapacity = count;
    }
    throw RenderError("blended fragment list: the fragment count changed between two identical passes");
}

// Draws object `o`'s meshes whose material blends (`blendPass`) or does not.
void PbrPass::drawObject(std::size_t o, int level, const glm::mat4& viewProjection, const gl::GpuMeshes& meshes,
                         bool blendPass) {
    const glm::mat4& model = mScene.objects[o].transform;
    const glm::mat4 mvp = viewProjection * model;
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
    const bool mirrored = glm::determinant(glm::mat3(model)) < 0.0f;
    const Uniforms& u = mActive->uniforms;
    glUniformMatrix4fv(u.model, 1, GL_FALSE, glm::value_ptr(model));
    glUniformMatrix4fv(u.modelViewProjection, 1, GL_FALSE, glm::value_ptr(mvp));
    glUniformMatrix3fv(u.normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
    glUniform1f(u.mirror, mirrored ? -1.0f : 1.0f);
    // A mirroring transform turns counter-clockwise front faces clockwise.
    glFrontFace(mirrored ? GL_CW : GL_CCW);
    static const scenes::Material kDefaultMaterial;
    for (const gl::GpuMesh& mesh : meshes[o][level]) {
        const scenes::Material& material =
            mesh.material >= 0 ? mScene.materials[std::size_t(mesh.material)] : kDefaultMaterial;
        if ((material.alphaMode == scenes::AlphaMode::Blend) != blendPass) continue;
        bindMaterial(material, mesh.hasTangents);
        glUniform1i(mActive->uniforms.flatNormals, mesh.flatNormals ? 1 : 0);
        if (mActive->drawIndex >= 0) glUniform1ui(mActive->drawIndex, GLuint(mDrawIndex++));
        glBindVertexArray(mesh.vertexArray);
        glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glFrontFace(GL_CCW);
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
    const Uniforms& u = mActive->uniforms;
    glUniform1iv(u.mapPresent, shaders::kTextureUnits, present);
    glUniform1iv(u.mapUvSet, shaders::kTextureUnits, uvSet);
    glUniformMatrix3fv(u.mapTransform, shaders::kTextureUnits, GL_FALSE, transforms);
    glUniform4fv(u.baseColorFactor, 1, glm::value_ptr(material.baseColorFactor));
    glUniform1f(u.metallicFactor, material.metallicFactor);
    glUniform1f(u.roughnessFactor, material.roughnessFactor);
    glUniform1f(u.normalScale, material.normalScale);
    glUniform1f(u.occlusionStrength, material.occlusionStrength);
    const glm::vec3 emissive = material.emissiveFactor * material.emissiveStrength;
    glUniform3fv(u.emissive, 1, glm::value_ptr(emissive));
    glUniform1i(u.alphaMode, int(material.alphaMode));
    glUniform1f(u.alphaCutoff, material.alphaCutoff);
    glUniform1i(u.unlit, material.unlit ? 1 : 0);
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
