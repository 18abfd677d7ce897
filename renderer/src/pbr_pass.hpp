// The PBR shading's GL state and draw pass (docs/renderer.md "Shading"): its program and
// uniforms, the textures in the color space each material slot reads, one sampler object per
// sampler state, and the engine-order draw (opaque and masked, then blended back to front).
// Private to the renderer; the Renderer owns the context, framebuffer and meshes.
#pragma once

#include <array>
#include <map>
#include <tuple>
#include <vector>

#include "gl_common.hpp"
#include "renderer/renderer.hpp"
#include "shaders.hpp"

namespace lodopt::renderer {

class PbrPass {
public:
    // Creates the program and uploads every texture a material uses (the context is current).
    PbrPass(const scenes::Scene& scene, const RenderSettings& settings);
    ~PbrPass();
    PbrPass(const PbrPass&) = delete;
    PbrPass& operator=(const PbrPass&) = delete;

    // Draws `combination` with the program bound, into whatever framebuffer and scissor are set.
    void draw(const scenes::Combination& combination, const scenes::Camera& camera, const glm::mat4& viewProjection,
              const gl::GpuMeshes& meshes);

private:
    struct Uniforms {
        GLint model = -1, modelViewProjection = -1, normalMatrix = -1, mirror = -1;
        GLint mapPresent = -1, mapUvSet = -1, mapTransform = -1;
        GLint baseColorFactor = -1, metallicFactor = -1, roughnessFactor = -1, normalScale = -1, occlusionStrength = -1;
        GLint emissive = -1, alphaMode = -1, alphaCutoff = -1, unlit = -1;
        GLint cameraPosition = -1, toLight = -1, keyIrradiance = -1, skyIrradiance = -1, groundIrradiance = -1;
    };

    GLuint samplerFor(const scenes::SamplerState& state);
    bool drawObject(std::size_t object, int level, const glm::mat4& viewProjection, const gl::GpuMeshes& meshes,
                    bool blendPass);
    void bindMaterial(const scenes::Material& material, bool hasTangents);

    const scenes::Scene& mScene;
    const RenderSettings& mSettings;
    GLuint mProgram = 0;
    Uniforms mUniforms;
    std::vector<GLuint> mLinearTextures;  // per scene texture, 0 when no linear slot reads it
    std::vector<GLuint> mSrgbTextures;    // per scene texture, 0 when no sRGB slot reads it
    std::map<std::tuple<int, int, int, int, int>, GLuint> mSamplers;
    std::vector<std::pair<float, std::size_t>> mBlended;  // (distance from the eye, object)
};

}  // namespace lodopt::renderer
