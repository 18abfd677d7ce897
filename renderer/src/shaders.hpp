// GLSL sources of the renderer's two shadings (docs/renderer.md "Shading"). Private.
#pragma once

namespace lodopt::renderer::shaders {

// The papers' shading: Lambert + ambient with the base color only, lit from both sides.
extern const char* const kLambertVertex;
extern const char* const kLambertFragment;

// glTF 2.0 metallic-roughness (spec Appendix B) under the fixed light rig, Khronos PBR Neutral
// tone mapping, sRGB output.
extern const char* const kPbrVertex;
extern const char* const kPbrFragment;
// kPbrFragment's first line for its fragment-list variant (SSBOs need GLSL 4.30): the same
// shading, and every fragment appended to a buffer (PbrPass::listBlendedFragments).
inline constexpr const char* kPbrFragmentListVersion = "#version 430 core\n#define LODOPT_FRAGMENT_LIST\n";

// Vertex attribute locations shared by both programs.
enum AttributeLocation { kPosition = 0, kNormal = 1, kUv0 = 2, kUv1 = 3, kTangent = 4, kColor = 5 };

// Texture units of the PBR program's maps, in Material order.
enum TextureUnit {
    kBaseColorUnit = 0,
    kMetallicRoughnessUnit = 1,
    kNormalUnit = 2,
    kOcclusionUnit = 3,
    kEmissiveUnit = 4
};
inline constexpr int kTextureUnits = 5;

}  // namespace lodopt::renderer::shaders
