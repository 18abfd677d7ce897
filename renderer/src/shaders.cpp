// The renderer's GLSL. The Lambert program is the papers' shading and must not change what it
// draws: every figure measured with `--shading lambert` depends on its exact bytes.
#include "shaders.hpp"

namespace lodopt::renderer::shaders {

// The triangle's own normal (glTF's flat normals for a primitive without NORMAL), from the
// screen-space derivatives of the world position: their cross product faces the viewer (window
// x right, y up), so the geometric normal is that on a front face and its opposite on a back
// face, where the caller flips it as it flips an interpolated one.
#define LODOPT_FLAT_NORMAL                                                            \
    "vec3 flatNormal(vec3 worldPosition) {\n"                                          \
    "    vec3 face = cross(dFdx(worldPosition), dFdy(worldPosition));\n"               \
    "    float faceLen = length(face);\n"                                              \
    "    vec3 towardViewer = faceLen > 1e-30 ? face / faceLen : vec3(0.0, 1.0, 0.0);\n" \
    "    return gl_FrontFacing ? towardViewer : -towardViewer;\n"                      \
    "}\n"

// The base color's KHR_texture_transform applies only when it is not the identity, so that every
// other texture coordinate is the attribute itself, as before the transform was read.
const char* const kLambertVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
uniform mat4 uModelViewProjection;
uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform bool uTransformUv;
uniform mat3 uUvTransform;
out vec3 vNormal;
out vec3 vWorldPosition;
out vec2 vUv;
void main() {
    gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
    vNormal = uNormalMatrix * aNormal;
    vWorldPosition = (uModel * vec4(aPosition, 1.0)).xyz;
    vUv = uTransformUv ? (uUvTransform * vec3(aUv, 1.0)).xy : aUv;
}
)";

// Lambert + ambient, lit from both sides: leaf cards and open meshes have no back side.
const char* const kLambertFragment = R"(#version 330 core
in vec3 vNormal;
in vec3 vWorldPosition;
in vec2 vUv;
uniform vec4 uBaseColor;
uniform sampler2D uBaseColorTexture;
uniform bool uHasTexture;
uniform bool uFlatNormals;
uniform vec3 uToLight;
uniform float uAmbient;
out vec4 fragColor;
)" LODOPT_FLAT_NORMAL R"(
void main() {
    float len = length(vNormal);
    vec3 n = uFlatNormals ? flatNormal(vWorldPosition) : (len > 1e-20 ? vNormal / len : vec3(0.0, 1.0, 0.0));
    if (!gl_FrontFacing) n = -n;
    float diffuse = max(dot(n, uToLight), 0.0);
    vec4 color = uBaseColor;
    if (uHasTexture) color *= texture(uBaseColorTexture, vUv);
    fragColor = vec4(clamp(color.rgb * (uAmbient + (1.0 - uAmbient) * diffuse), 0.0, 1.0), 1.0);
}
)";

const char* const kPbrVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv0;
layout(location = 3) in vec2 aUv1;
layout(location = 4) in vec4 aTangent;
layout(location = 5) in vec4 aColor;
uniform mat4 uModelViewProjection;
uniform mat4 uModel;
uniform mat3 uNormalMatrix;
out vec3 vWorldPosition;
out vec3 vNormal;
out vec4 vTangent;
out vec2 vUv0;
out vec2 vUv1;
out vec4 vColor;
void main() {
    gl_Position = uModelViewProjection * vec4(aPosition, 1.0);
    vWorldPosition = (uModel * vec4(aPosition, 1.0)).xyz;
    vNormal = uNormalMatrix * aNormal;
    vTangent = vec4(mat3(uModel) * aTangent.xyz, aTangent.w);
    vUv0 = aUv0;
    vUv1 = aUv1;
    vColor = aColor;
}
)";

// glTF 2.0 Appendix B: f = (1 - F) c_diff / pi + F D Vis, with c_diff = base (1 - metallic),
// f0 = mix(0.04, base, metallic), alpha = roughness^2, Schlick's F, GGX D and the height-
// correlated Smith visibility. One directional key light (irradiance uKeyIrradiance on a
// surface facing it) and a hemisphere ambient (diffuse only, scaled by occlusion). Roughness is
// clamped to >= 0.03 so that alpha^2 >= 8.1e-7: at 0 the GGX lobe is a delta and D divides by
// zero where n = h. Then Khronos PBR Neutral tone mapping and the sRGB transfer function.
const char* const kPbrFragment = R"(#version 330 core
in vec3 vWorldPosition;
in vec3 vNormal;
in vec4 vTangent;
in vec2 vUv0;
in vec2 vUv1;
in vec4 vColor;
uniform sampler2D uBaseColorMap;
uniform sampler2D uMetallicRoughnessMap;
uniform sampler2D uNormalMap;
uniform sampler2D uOcclusionMap;
uniform sampler2D uEmissiveMap;
// Per map, in that order: present, UV set, KHR_texture_transform matrix.
uniform int uMapPresent[5];
uniform int uMapUvSet[5];
uniform mat3 uMapTransform[5];
uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor;
uniform float uRoughnessFactor;
uniform float uNormalScale;
uniform float uOcclusionStrength;
uniform vec3 uEmissive;       // emissiveFactor x emissiveStrength
uniform int uAlphaMode;       // 0 opaque, 1 mask, 2 blend
uniform float uAlphaCutoff;
uniform bool uUnlit;
uniform bool uFlatNormals;
uniform float uMirror;        // -1 when the model transform mirrors (flips the bitangent)
uniform vec3 uCameraPosition;
uniform vec3 uToLight;
uniform vec3 uKeyIrradiance;
uniform vec3 uSkyIrradiance;
uniform vec3 uGroundIrradiance;
out vec4 fragColor;
#ifdef LODOPT_FRAGMENT_LIST
// The fragment-list variant (kPbrFragmentListVersion): every fragment that passes the depth
// test, appended with the color the blend unit receives. Early tests, so that a fragment the
// depth buffer hides is never listed.
layout(early_fragment_tests) in;
struct ListedFragment {
    uint pixel;  // x | y << 16, window coordinates (bottom-left origin)
    float depth;
    uint color;  // RGBA8
    uint draw;   // the mesh draw's index in the pass: fragments blend in (draw, primitive) order
    uint primitive;
};
layout(std430, binding = 0) buffer FragmentList {
    uint listedCount;
    uint listCapacity;
    ListedFragment listed[];
};
uniform uint uDrawIndex;
#endif

const float kPi = 3.14159265358979;
)" LODOPT_FLAT_NORMAL R"(
vec4 sampleMap(sampler2D map, int index) {
    vec2 uv = uMapUvSet[index] == 1 ? vUv1 : vUv0;
    return texture(map, (uMapTransform[index] * vec3(uv, 1.0)).xy);
}

vec3 neutralToneMap(vec3 color) {
    const float startCompression = 0.8 - 0.04;
    const float desaturation = 0.15;
    float x = min(color.r, min(color.g, color.b));
    float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
    color -= offset;
    float peak = max(color.r, max(color.g, color.b));
    if (peak < startCompression) return color;
    const float d = 1.0 - startCompression;
    float newPeak = 1.0 - d * d / (peak + d - startCompression);
    color *= newPeak / peak;
    float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
    return mix(color, vec3(newPeak), g);
}

vec3 encodeSrgb(vec3 linear) {
    vec3 c = clamp(linear, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    // Before any discard: derivatives need the whole pixel quad.
    vec3 faceNormal = uFlatNormals ? flatNormal(vWorldPosition) : vec3(0.0);
    vec4 base = uBaseColorFactor * vColor;
    if (uMapPresent[0] != 0) base *= sampleMap(uBaseColorMap, 0);
    if (uAlphaMode == 1 && base.a < uAlphaCutoff) discard;
    float alpha = uAlphaMode == 2 ? clamp(base.a, 0.0, 1.0) : 1.0;
    vec3 color;
    if (uUnlit) {
        color = base.rgb;
    } else {
        float len = length(vNormal);
        vec3 n = uFlatNormals ? faceNormal : (len > 1e-20 ? vNormal / len : vec3(0.0, 1.0, 0.0));
        if (uMapPresent[2] != 0) {
            vec3 t = vTangent.xyz - n * dot(n, vTangent.xyz);
            float tLen = length(t);
            if (tLen > 1e-20) {
                t /= tLen;
                vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0) * uMirror;
                vec3 mapped = sampleMap(uNormalMap, 2).xyz * 2.0 - 1.0;
                mapped.xy *= uNormalScale;
                vec3 perturbed = mat3(t, b, n) * mapped;
                float pLen = length(perturbed);
                if (pLen > 1e-20) n = perturbed / pLen;
            }
        }
        if (!gl_FrontFacing) n = -n;  // double-sided: the back face's normal (spec 3.9.6)
        float metallic = uMetallicFactor, roughness = uRoughnessFactor;
        if (uMapPresent[1] != 0) {
            vec4 mr = sampleMap(uMetallicRoughnessMap, 1);
            roughness *= mr.g;
            metallic *= mr.b;
        }
        metallic = clamp(metallic, 0.0, 1.0);
        roughness = clamp(roughness, 0.03, 1.0);
        vec3 toEye = uCameraPosition - vWorldPosition;
        float eyeLen = length(toEye);
        vec3 v = eyeLen > 1e-20 ? toEye / eyeLen : n;
        vec3 l = uToLight;
        vec3 h = normalize(l + v);
        float nDotL = clamp(dot(n, l), 0.0, 1.0);
        float nDotV = clamp(abs(dot(n, v)), 1e-4, 1.0);
        float nDotH = clamp(dot(n, h), 0.0, 1.0);
        float vDotH = clamp(dot(v, h), 0.0, 1.0);
        vec3 cDiff = mix(base.rgb, vec3(0.0), metallic);
        vec3 f0 = mix(vec3(0.04), base.rgb, metallic);
        float a = roughness * roughness;
        float a2 = a * a;
        vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vDotH, 5.0);
        float dDenominator = nDotH * nDotH * (a2 - 1.0) + 1.0;
        float distribution = a2 / (kPi * dDenominator * dDenominator);
        float visDenominator = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2) +
                               nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
        float visibility = visDenominator > 0.0 ? 0.5 / visDenominator : 0.0;
        vec3 brdf = (1.0 - fresnel) * cDiff / kPi + fresnel * distribution * visibility;
        color = brdf * nDotL * uKeyIrradiance;
        float occlusion = 1.0;
        if (uMapPresent[3] != 0) occlusion = 1.0 + uOcclusionStrength * (sampleMap(uOcclusionMap, 3).r - 1.0);
        vec3 hemisphere = mix(uGroundIrradiance, uSkyIrradiance, 0.5 * n.y + 0.5);
        color += cDiff / kPi * hemisphere * occlusion;
    }
    vec3 emissive = uEmissive;
    if (uMapPresent[4] != 0) emissive *= sampleMap(uEmissiveMap, 4).rgb;
    color += emissive;
    vec4 result = vec4(encodeSrgb(neutralToneMap(color)), alpha);
#ifdef LODOPT_FRAGMENT_LIST
    uint slot = atomicAdd(listedCount, 1u);
    if (slot < listCapacity) {
        listed[slot] = ListedFragment(uint(gl_FragCoord.x) | (uint(gl_FragCoord.y) << 16u), gl_FragCoord.z,
                                      packUnorm4x8(result), uDrawIndex, uint(gl_PrimitiveID));
    }
#endif
    fragColor = result;
}
)";

}  // namespace lodopt::renderer::shaders
