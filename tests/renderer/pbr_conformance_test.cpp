// The PBR shading against the property each Khronos conformance model's README names
// (../shared/data/gltf/render-tests), plus hand-made scenes for what no model isolates.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "scenes/mesh_builder.hpp"
#include "lodopt_test_paths.hpp"

using namespace lodopt;

namespace {

const std::filesystem::path kRenderTests = std::filesystem::path(LODOPT_SHARED_DATA_DIR) / "gltf" / "render-tests";

scenes::Scene loadRenderTest(const std::string& model) {
    const std::filesystem::path path = kRenderTests / model / "glTF" / (model + ".gltf");
    if (!std::filesystem::exists(path)) {
        ADD_FAILURE() << path << " is missing: the tests need ../shared/data beside the repository";
        return {};
    }
    scenes::GltfLoadOptions options;
    options.generateLods = false;
    scenes::Scene scene = scenes::loadGltf(path.string(), options);
    scenes::addDefaultViews(scene);
    return scene;
}

int objectNamed(const scenes::Scene& scene, const std::string& name) {
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        if (scene.objects[o].name == name) return int(o);
    }
    ADD_FAILURE() << "no object '" << name << "' in " << scene.name;
    return 0;
}

renderer::RenderSettings pbrSettings(int size) {
    renderer::RenderSettings settings;
    settings.shading = renderer::Shading::Pbr;
    settings.width = settings.height = size;
    return settings;
}

// Pixels of a frame for which `predicate(r, g, b)` holds.
std::size_t countPixels(const renderer::Frame& frame, const std::function<bool(int, int, int)>& predicate) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < frame.rgba.size(); i += 4) {
        count += predicate(frame.rgba[i], frame.rgba[i + 1], frame.rgba[i + 2]);
    }
    return count;
}

scenes::Combination only(const scenes::Scene& scene, int object) {
    scenes::Combination combination(scene.objects.size(), scenes::kNotDrawn);
    combination[std::size_t(object)] = 0;
    return combination;
}

}  // namespace

// AlphaBlendModeTest README: the MASK panels are cut at 0.25, 0.5 (default) and 0.75 of a
// vertical alpha ramp, so less of the panel stays the higher the cutoff; OPAQUE ignores alpha.
TEST(PbrConformance, AlphaMaskCutoffsKeepLessOfThePanelTheHigherTheyAre) {
    const scenes::Scene scene = loadRenderTest("AlphaBlendModeTest");
    ASSERT_FALSE(scene.objects.empty());
    renderer::Renderer renderer(scene, pbrSettings(256));
    const scenes::Camera& camera = scene.views[0];
    auto covered = [&](const char* name) {
        return renderer.renderLayer(objectNamed(scene, name), 0, camera).coveredPixels;
    };
    const std::uint64_t opaque = covered("TestOpaque"), cutoff25 = covered("TestCutoff25"),
                        cutoffDefault = covered("TestCutoffDefault"), cutoff75 = covered("TestCutoff75");
    EXPECT_GT(cutoff75, 0u);
    EXPECT_GT(cutoffDefault, cutoff75);
    EXPECT_GT(cutoff25, cutoffDefault);
    EXPECT_GT(opaque, cutoff25);
    // Lambert, the papers' shading, has no alpha: the masked panel is whole.
    renderer::RenderSettings lambert = pbrSettings(256);
    lambert.shading = renderer::Shading::Lambert;
    renderer::Renderer lambertRenderer(scene, lambert);
    EXPECT_EQ(lambertRenderer.renderLayer(objectNamed(scene, "TestCutoff75"), 0, camera).coveredPixels,
              lambertRenderer.renderLayer(objectNamed(scene, "TestOpaque"), 0, camera).coveredPixels);
}

// A BLEND panel shows what is behind it: its pixels change with the background; an OPAQUE
// panel's do not.
TEST(PbrConformance, BlendedPanelShowsTheBackgroundThroughIt) {
    const scenes::Scene scene = loadRenderTest("AlphaBlendModeTest");
    ASSERT_FALSE(scene.objects.empty());
    auto changedPanelPixels = [&](const char* name) {
        renderer::RenderSettings dark = pbrSettings(192), light = pbrSettings(192);
        dark.clearColor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
        light.clearColor = glm::vec4(1.0f, 1.0f, 1.0f, 1.0f);
        const int object = objectNamed(scene, name);
        renderer::Frame overDark = renderer::Renderer(scene, dark).render(only(scene, object), scene.views[0]);
        renderer::Frame overLight = renderer::Renderer(scene, light).render(only(scene, object), scene.views[0]);
        std::size_t changed = 0;
        for (std::size_t i = 0; i < overDark.rgba.size(); i += 4) {
            const bool backgroundDark = overDark.rgba[i] == 0 && overDark.rgba[i + 1] == 0 && overDark.rgba[i + 2] == 0;
            const bool backgroundLight =
                overLight.rgba[i] == 255 && overLight.rgba[i + 1] == 255 && overLight.rgba[i + 2] == 255;
            const bool differ = !std::equal(&overDark.rgba[i], &overDark.rgba[i] + 3, &overLight.rgba[i]);
            changed += differ && !backgroundDark && !backgroundLight;
        }
        return changed;
    };
    EXPECT_GT(changedPanelPixels("TestBlend"), 500u);
    EXPECT_EQ(changedPanelPixels("TestOpaque"), 0u);
}

// TextureTransformTest README: "A yellow image indicates that offset was not applied."
TEST(PbrConformance, TextureTransformOffsetsShowNoYellow) {
    const scenes::Scene scene = loadRenderTest("TextureTransformTest");
    ASSERT_FALSE(scene.objects.empty());
    // The texture's yellow is (192, 192, 0); lit from the side it comes out near (130, 130, 0).
    auto yellow = [](int r, int g, int b) { return r > 80 && g > 80 && std::abs(r - g) < 20 && b < r / 3; };
    renderer::Renderer renderer(scene, pbrSettings(256));
    scenes::Scene untransformed = scene;
    for (scenes::Material& material : untransformed.materials) material.baseColorTexture.transform = {};
    renderer::Renderer ignoring(untransformed, pbrSettings(256));
    for (const char* name : {"Offset U", "Offset V", "Offset UV"}) {
        const scenes::Combination combination = only(scene, objectNamed(scene, name));
        EXPECT_EQ(countPixels(renderer.render(combination, scene.views[0]), yellow), 0u) << name;
        EXPECT_GT(countPixels(ignoring.render(combination, scene.views[0]), yellow), 100u) << name;
    }
}

// The KHR_texture_transform matrix, worked by hand from the extension's definition:
// translation(offset) * rotation * scale, rotation rows (cos, sin) and (-sin, cos).
TEST(PbrConformance, TextureTransformMatrixIsTheExtensionsMatrix) {
    scenes::TextureTransform transform;
    transform.offset = {0.5f, 0.25f};
    transform.rotation = 3.14159265f / 2.0f;
    transform.scale = {2.0f, 3.0f};
    // (1, 1) -> scale (2, 3) -> rotate: (cos*2 + sin*3, -sin*2 + cos*3) = (3, -2) -> + offset.
    const glm::vec3 mapped = transform.matrix() * glm::vec3(1.0f, 1.0f, 1.0f);
    EXPECT_NEAR(mapped.x, 3.5f, 1e-5f);
    EXPECT_NEAR(mapped.y, -1.75f, 1e-5f);
    EXPECT_TRUE(scenes::TextureTransform{}.isIdentity());
    EXPECT_EQ(scenes::TextureTransform{}.matrix(), glm::mat3(1.0f));
}

// VertexColorTest README: an engine that ignores COLOR_0 shows cyan, magenta and yellow X
// marks over the test row's checks.
TEST(PbrConformance, VertexColorsRemoveTheXMarks) {
    const scenes::Scene scene = loadRenderTest("VertexColorTest");
    ASSERT_FALSE(scene.objects.empty());
    auto secondaryColor = [](int r, int g, int b) {
        const int high = (r > 150) + (g > 150) + (b > 150), low = (r < 60) + (g < 60) + (b < 60);
        return high == 2 && low == 1;
    };
    const scenes::Combination checks = only(scene, objectNamed(scene, "VertexColorTest"));
    scenes::Scene withoutColors = scene;
    for (scenes::Object& object : withoutColors.objects) {
        for (scenes::Mesh& mesh : object.levels[0].meshes) mesh.colors.clear();
    }
    const renderer::Frame applied = renderer::Renderer(scene, pbrSettings(256)).render(checks, scene.views[0]);
    const renderer::Frame ignored = renderer::Renderer(withoutColors, pbrSettings(256)).render(checks, scene.views[0]);
    EXPECT_LT(countPixels(applied, secondaryColor), 20u);
    EXPECT_GT(countPixels(ignored, secondaryColor), 300u);
}

// EmissiveStrengthTest: KHR_materials_emissive_strength 1, 2, 4, 8, 16 on the same factor make
// each cube brighter than the one before (until tone mapping saturates).
TEST(PbrConformance, EmissiveStrengthBrightensTheCubesInOrder) {
    const scenes::Scene scene = loadRenderTest("EmissiveStrengthTest");
    ASSERT_FALSE(scene.objects.empty());
    renderer::Renderer renderer(scene, pbrSettings(256));
    double previous = -1.0;
    for (const char* name : {"Cube1", "Cube2", "Cube4", "Cube8", "Cube16"}) {
        const renderer::Layer layer = renderer.renderLayer(objectNamed(scene, name), 0, scene.views[0]);
        ASSERT_GT(layer.coveredPixels, 0u) << name;
        double sum = 0.0;
        for (std::size_t i = 0; i < layer.depth.size(); ++i) {
            if (layer.depth[i] < 1.0f) sum += layer.rgba[4 * i] + layer.rgba[4 * i + 1] + layer.rgba[4 * i + 2];
        }
        const double mean = sum / double(layer.coveredPixels);
        EXPECT_GT(mean, previous + 1.0) << name;
        previous = mean;
    }
}

// NormalTangentMirrorTest supplies TANGENT (MikkTSpace, mirrored UV islands): computeTangents
// on the same mesh points the same way on nearly every vertex, with the same handedness.
TEST(PbrConformance, GeneratedTangentsAgreeWithTheSuppliedMikkTSpaceOnes) {
    const scenes::Scene scene = loadRenderTest("NormalTangentMirrorTest");
    ASSERT_FALSE(scene.objects.empty());
    std::size_t vertices = 0, sameDirection = 0, sameHandedness = 0;
    for (const scenes::Object& object : scene.objects) {
        for (const scenes::Mesh& supplied : object.levels[0].meshes) {
            if (supplied.tangents.empty() || supplied.uvs.empty()) continue;
            scenes::Mesh generated = supplied;
            generated.tangents.clear();
            scenes::computeTangents(generated);
            for (std::size_t v = 0; v < supplied.tangents.size(); ++v) {
                ++vertices;
                sameDirection += glm::dot(glm::vec3(supplied.tangents[v]), glm::vec3(generated.tangents[v])) > 0.9f;
                sameHandedness += supplied.tangents[v].w == generated.tangents[v].w;
            }
        }
    }
    ASSERT_GT(vertices, 1000u);
    EXPECT_GT(double(sameDirection) / double(vertices), 0.95);
    EXPECT_GT(double(sameHandedness) / double(vertices), 0.95);
}

// A single-sided quad seen from behind is culled; a double-sided one is lit from its back.
TEST(PbrConformance, SingleSidedMaterialsCullBackFaces) {
    scenes::Scene scene;
    scenes::Material material;
    material.metallicFactor = 0.0f;
    scene.materials.push_back(material);
    scenes::MeshBuilder quad(0);
    quad.addQuad({-1.0f, -1.0f, 0.0f}, {1.0f, -1.0f, 0.0f}, {1.0f, 1.0f, 0.0f}, {-1.0f, 1.0f, 0.0f});
    scenes::Object object;
    object.name = "quad";
    object.levels.push_back({});
    object.levels[0].meshes.push_back(quad.finish());
    scene.objects.push_back(object);
    scenes::updateStatistics(scene);
    scenes::Camera front, behind;
    front.position = {0.0f, 0.0f, 4.0f};
    behind.position = {0.0f, 0.0f, -4.0f};
    auto covered = [&](const scenes::Scene& s, const scenes::Camera& camera) {
        return renderer::Renderer(s, pbrSettings(64)).renderLayer(0, 0, camera).coveredPixels;
    };
    EXPECT_GT(covered(scene, front), 100u);
    EXPECT_EQ(covered(scene, behind), 0u);
    scene.materials[0].doubleSided = true;
    EXPECT_EQ(covered(scene, behind), covered(scene, front));
}

// A primitive without NORMAL is drawn with each triangle's own normal (spec §3.7.2.1), in both
// shadings: a welded sphere flagged flatNormals renders as the same sphere unwelded with explicit
// face normals (within 2 levels but at a few silhouette pixels), and unlike its smooth self.
TEST(PbrConformance, FlatNormalsAreEachTrianglesOwn) {
    scenes::MeshBuilder builder(0);
    builder.addEllipsoid({0.0f, 0.0f, 0.0f}, {1.0f, 0.8f, 1.0f}, 10, 6);
    const scenes::Mesh smooth = builder.finish();
    scenes::Mesh flagged = smooth;
    flagged.flatNormals = true;
    scenes::Mesh faceted;
    for (std::size_t i = 0; i + 2 < smooth.indices.size(); i += 3) {
        const glm::vec3 a = smooth.positions[smooth.indices[i]], b = smooth.positions[smooth.indices[i + 1]],
                        c = smooth.positions[smooth.indices[i + 2]];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (const glm::vec3& p : {a, b, c}) {
            faceted.indices.push_back(std::uint32_t(faceted.positions.size()));
            faceted.positions.push_back(p);
            faceted.normals.push_back(n);
        }
    }
    faceted.material = 0;
    auto sceneWith = [](const scenes::Mesh& mesh) {
        scenes::Scene scene;
        scenes::Material material;
        material.metallicFactor = 0.0f;
        material.roughnessFactor = 0.8f;
        scene.materials.push_back(material);
        scenes::Object object;
        object.name = "sphere";
        object.levels.push_back({});
        object.levels[0].meshes.push_back(mesh);
        scene.objects.push_back(object);
        scenes::updateStatistics(scene);
        return scene;
    };
    const scenes::Scene flatScene = sceneWith(flagged), facetedScene = sceneWith(faceted), smoothScene = sceneWith(smooth);
    scenes::Camera camera;
    camera.position = {1.5f, 1.8f, 3.0f};
    for (renderer::Shading shading : {renderer::Shading::Lambert, renderer::Shading::Pbr}) {
        renderer::RenderSettings settings = pbrSettings(128);
        settings.shading = shading;
        auto render = [&](const scenes::Scene& scene) {
            return renderer::Renderer(scene, settings).render({0}, camera);
        };
        const renderer::Frame flat = render(flatScene), explicitFaces = render(facetedScene), smoothed = render(smoothScene);
        std::size_t covered = 0, unlikeSmooth = 0, offFaces = 0;
        for (std::size_t i = 0; i < flat.depth.size(); ++i) {
            if (!(flat.depth[i] < 1.0f)) continue;
            ++covered;
            int againstFaces = 0, againstSmooth = 0;
            for (int c = 0; c < 3; ++c) {
                againstFaces = std::max(againstFaces, std::abs(flat.rgba[i * 4 + c] - explicitFaces.rgba[i * 4 + c]));
                againstSmooth = std::max(againstSmooth, std::abs(flat.rgba[i * 4 + c] - smoothed.rgba[i * 4 + c]));
            }
            offFaces += againstFaces > 2;
            unlikeSmooth += againstSmooth > 4;
        }
        const char* name = renderer::shadingName(shading);
        EXPECT_GT(covered, 3000u) << name;
        // A pixel quad that reaches past a grazing triangle's edge extrapolates its position far
        // along the plane; its derivatives lose precision there (measured: 1 silhouette pixel of
        // about 5,000 per shading).
        EXPECT_LE(offFaces, covered / 500) << name << ": flat normals against explicit face normals";
        EXPECT_GT(unlikeSmooth, covered / 5) << name << ": flat shading should not look smooth";
    }
}

// The layer path stays exact under PBR for opaque and masked objects: the composite of their
// layers equals the full render, bit for bit (the blended panels are left out).
TEST(PbrConformance, CompositeOfOpaqueAndMaskedLayersEqualsFullRender) {
    const scenes::Scene scene = loadRenderTest("AlphaBlendModeTest");
    ASSERT_FALSE(scene.objects.empty());
    const renderer::RenderSettings settings = pbrSettings(200);
    renderer::Renderer renderer(scene, settings);
    for (const scenes::Camera& camera : scene.views) {
        scenes::Combination combination;
        std::vector<renderer::Layer> layers;
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            const bool blended = scene.objects[o].name == "TestBlend" || scene.objects[o].name == "DecalBlend";
            combination.push_back(blended ? scenes::kNotDrawn : 0);
            layers.push_back(blended ? renderer::Layer{} : renderer.renderLayer(int(o), 0, camera));
        }
        std::vector<const renderer::Layer*> chosen;
        for (std::size_t o = 0; o < layers.size(); ++o) chosen.push_back(combination[o] == 0 ? &layers[o] : nullptr);
        const renderer::Frame full = renderer.render(combination, camera);
        renderer::Frame composed;
        renderer::composite(chosen, settings.width, settings.height, settings.clearColor, composed);
        EXPECT_EQ(full.rgba, composed.rgba) << camera.name;
    }
}

// Blended layers: composited back to front over the opaque composite, every AlphaBlendModeTest
// view equals the full render to the bit, blended panels included (the composite blends with the
// blend unit's arithmetic: docs/renderer.md "Layers and blending").
TEST(PbrConformance, CompositeWithBlendedLayersMatchesFullRender) {
    const scenes::Scene scene = loadRenderTest("AlphaBlendModeTest");
    ASSERT_FALSE(scene.objects.empty());
    const renderer::RenderSettings settings = pbrSettings(200);
    renderer::Renderer renderer(scene, settings);
    std::size_t blendedPixels = 0;
    for (const scenes::Camera& camera : scene.views) {
        std::vector<renderer::Layer> layers;
        std::vector<const renderer::Layer*> chosen;
        for (std::size_t o = 0; o < scene.objects.size(); ++o) layers.push_back(renderer.renderLayer(int(o), 0, camera));
        for (const renderer::Layer& layer : layers) chosen.push_back(&layer);
        const renderer::Frame full = renderer.render(scenes::referenceCombination(scene), camera);
        renderer::Frame composed;
        renderer::composite(chosen, settings.width, settings.height, settings.clearColor, composed);
        EXPECT_EQ(full.rgba, composed.rgba) << camera.name;
        EXPECT_EQ(full.depth, composed.depth) << camera.name;
        for (const renderer::Layer& layer : layers) {
            for (std::size_t i = 3; i < layer.blendRgba.size(); i += 4) blendedPixels += layer.blendRgba[i] != 0;
        }
    }
    EXPECT_GT(blendedPixels, 1000u);  // the blended panels are drawn, and cover something
}

// The same inputs give the same pixels under PBR too, blended panels included, however often a
// renderer draws them (each frame sorts its own blended objects afresh).
TEST(PbrConformance, RepeatedRendersAreBitIdentical) {
    const scenes::Scene scene = loadRenderTest("AlphaBlendModeTest");
    ASSERT_FALSE(scene.objects.empty());
    renderer::Renderer renderer(scene, pbrSettings(128));
    const scenes::Combination all = scenes::referenceCombination(scene);
    const renderer::Frame first = renderer.render(all, scene.views[0]);
    for (int repeat = 0; repeat < 2; ++repeat) {
        EXPECT_EQ(renderer.render(all, scene.views[0]).rgba, first.rgba) << "repeat " << repeat;
    }
    EXPECT_EQ(renderer::Renderer(scene, pbrSettings(128)).render(all, scene.views[0]).rgba, first.rgba);
}
