// exportGltf round trips: load(export(scene)) gives the same objects, levels, statistics,
// materials, textures, views, camera paths and name, for .gltf and .glb.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gltf_test_files.hpp"
#include "scenes/gltf_io.hpp"
#include "scenes/mesh_builder.hpp"

namespace lodopt::scenes {
namespace {

using testing::TempDir;

GltfLoadOptions noGeneration() {
    GltfLoadOptions options;
    options.generateLods = false;
    return options;
}

void expectNearVec(glm::vec3 a, glm::vec3 b, float tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

void expectSameCamera(const Camera& a, const Camera& b) {
    EXPECT_EQ(a.name, b.name);
    expectNearVec(a.position, b.position, 1e-5f);
    expectNearVec(a.target, b.target, 1e-5f);
    EXPECT_NEAR(a.fovYDegrees, b.fovYDegrees, 1e-4f);
    EXPECT_FLOAT_EQ(a.nearPlane, b.nearPlane);
    EXPECT_FLOAT_EQ(a.farPlane, b.farPlane);
    // `up` may come back orthogonalised: the view it gives must not change.
    const glm::mat4 va = viewMatrix(a), vb = viewMatrix(b);
    for (int c = 0; c < 4; ++c) {
        for (int r = 0; r < 4; ++r) EXPECT_NEAR(va[c][r], vb[c][r], 1e-4f) << a.name;
    }
}

void expectSameScene(const Scene& a, const Scene& b) {
    EXPECT_EQ(a.name, b.name);
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (std::size_t o = 0; o < a.objects.size(); ++o) {
        const Object& x = a.objects[o];
        const Object& y = b.objects[o];
        SCOPED_TRACE(x.name);
        EXPECT_EQ(x.name, y.name);
        for (int c = 0; c < 4; ++c) {
            for (int r = 0; r < 4; ++r) EXPECT_FLOAT_EQ(x.transform[c][r], y.transform[c][r]);
        }
        ASSERT_EQ(x.levels.size(), y.levels.size());
        for (std::size_t k = 0; k < x.levels.size(); ++k) {
            const LevelStats& s = x.levels[k].stats;
            const LevelStats& t = y.levels[k].stats;
            EXPECT_EQ(s.vertices, t.vertices) << "level " << k;
            EXPECT_EQ(s.triangles, t.triangles) << "level " << k;
            EXPECT_EQ(s.textureBytes, t.textureBytes) << "level " << k;
            EXPECT_EQ(s.drawCalls, t.drawCalls) << "level " << k;
            expectNearVec(s.bounds.min, t.bounds.min, 1e-5f);
            expectNearVec(s.bounds.max, t.bounds.max, 1e-5f);
            EXPECT_EQ(x.levels[k].screenCoverage.has_value(), y.levels[k].screenCoverage.has_value());
            if (x.levels[k].screenCoverage && y.levels[k].screenCoverage) {
                EXPECT_FLOAT_EQ(*x.levels[k].screenCoverage, *y.levels[k].screenCoverage);
            }
            ASSERT_EQ(x.levels[k].meshes.size(), y.levels[k].meshes.size());
            for (std::size_t m = 0; m < x.levels[k].meshes.size(); ++m) {
                EXPECT_EQ(x.levels[k].meshes[m].material, y.levels[k].meshes[m].material);
                EXPECT_EQ(x.levels[k].meshes[m].indices, y.levels[k].meshes[m].indices);
                EXPECT_EQ(x.levels[k].meshes[m].uvs.size(), y.levels[k].meshes[m].uvs.size());
            }
        }
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t m = 0; m < a.materials.size(); ++m) {
        EXPECT_EQ(a.materials[m].name, b.materials[m].name);
        EXPECT_EQ(a.materials[m].baseColorFactor, b.materials[m].baseColorFactor);
        EXPECT_EQ(a.materials[m].baseColorTexture.texture, b.materials[m].baseColorTexture.texture);
    }
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (std::size_t t = 0; t < a.textures.size(); ++t) {
        EXPECT_EQ(a.textures[t].name, b.textures[t].name);
        EXPECT_EQ(a.textures[t].width, b.textures[t].width);
        EXPECT_EQ(a.textures[t].height, b.textures[t].height);
        EXPECT_TRUE(a.textures[t].rgba == b.textures[t].rgba) << "texture " << t << " pixels differ";
    }
    ASSERT_EQ(a.views.size(), b.views.size());
    for (std::size_t v = 0; v < a.views.size(); ++v) expectSameCamera(a.views[v], b.views[v]);
    ASSERT_EQ(a.paths.size(), b.paths.size());
    for (std::size_t p = 0; p < a.paths.size(); ++p) {
        EXPECT_EQ(a.paths[p].name, b.paths[p].name);
        EXPECT_FLOAT_EQ(a.paths[p].framesPerSecond, b.paths[p].framesPerSecond);
        ASSERT_EQ(a.paths[p].frames.size(), b.paths[p].frames.size());
        for (std::size_t f = 0; f < a.paths[p].frames.size(); ++f) {
            expectSameCamera(a.paths[p].frames[f], b.paths[p].frames[f]);
            expectNearVec(a.paths[p].frames[f].up, b.paths[p].frames[f].up, 0.0f);
        }
    }
}

Texture checker(const std::string& name, int size, std::uint8_t shade) {
    Texture texture{name, size, size, {}};
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const bool dark = ((x + y) % 2) != 0;
            texture.rgba.insert(texture.rgba.end(), {std::uint8_t(dark ? shade : 255), std::uint8_t(x * 16), std::uint8_t(y * 16),
                                                     std::uint8_t(dark ? 128 : 255)});
        }
    }
    return texture;
}

// Two objects: a box with three authored levels (screen coverage on each) and a textured
// card with one level; two materials, two textures, two views and a three-frame path.
Scene handBuiltScene(bool withTextures) {
    Scene scene;
    scene.name = "handmade";
    scene.materials = {diffuseMaterial("stone", {0.5f, 0.4f, 0.3f}), diffuseMaterial("leaf", {1.0f, 1.0f, 1.0f})};
    if (withTextures) {
        scene.textures = {checker("bark", 4, 10), checker("leafy", 8, 60)};
        scene.materials[0].baseColorTexture.texture = 1;
        scene.materials[1].baseColorTexture.texture = 0;
    }
    Object box;
    box.name = "box";
    box.transform = glm::mat4(1.0f);
    box.transform[3] = glm::vec4(3.0f, 0.0f, -2.0f, 1.0f);
    const float coverage[3] = {0.4f, 0.1f, 0.02f};
    for (int k = 0; k < 3; ++k) {
        MeshBuilder builder(0);
        builder.addCylinder({0, 0, 0}, 2.0f, 1.0f, 0.5f, 16 >> k, true);
        Level level;
        level.meshes.push_back(builder.finish());
        if (k == 0) {
            MeshBuilder lid(1);
            lid.addBox({0, 2.2f, 0}, {0.2f, 0.2f, 0.2f});
            level.meshes.push_back(lid.finish());
        }
        level.screenCoverage = coverage[k];
        box.levels.push_back(std::move(level));
    }
    Object card;
    card.name = "card";
    MeshBuilder builder(1);
    builder.addDoubleSidedCard({-1, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1.5f);
    card.levels.emplace_back();
    card.levels[0].meshes.push_back(builder.finish());
    scene.objects = {box, card};
    scene.views = {Camera{"overview", {6, 4, 8}, {0, 1, 0}, {0, 1, 0}, 50.0f, 0.2f, 200.0f},
                   Camera{"top", {0, 10, 0.01f}, {0, 0, 0}, {0, 0, -1}, 30.0f, 1.0f, 50.0f}};
    CameraPath path{"orbit", 24.0f, {}};
    for (int f = 0; f < 3; ++f) {
        path.frames.push_back(Camera{"orbit#" + std::to_string(f), {8.0f * std::cos(f * 0.5f), 3, 8.0f * std::sin(f * 0.5f)},
                                     {0, 1, 0}, {0, 1, 0}, 45.0f + f, 0.1f, 100.0f});
    }
    scene.paths = {path};
    updateStatistics(scene);
    return scene;
}

TEST(GltfExport, HandBuiltSceneRoundTripsAsGltfAndGlb) {
    TempDir dir;
    const Scene scene = handBuiltScene(false);
    for (const char* name : {"scene.gltf", "scene.glb"}) {
        SCOPED_TRACE(name);
        exportGltf(scene, dir.file(name));
        expectSameScene(scene, loadGltf(dir.file(name), noGeneration()));
    }
}

TEST(GltfExport, ScreenCoverageAsUnityHeightsIsMarkedAndReadBackAsScreenSizes) {
    TempDir dir;
    const Scene scene = handBuiltScene(false);
    GltfExportOptions options;
    options.coverage = CoverageConvention::UnityRelativeHeight;
    exportGltf(scene, dir.file("unity.gltf"), options);
    std::ifstream file(dir.file("unity.gltf"));
    const nlohmann::json document = nlohmann::json::parse(file);
    EXPECT_EQ(document["asset"]["extras"]["lodopt_screencoverage"], "unity_relative_height");
    // The box's level-0 world bounds: its values are screen sizes times largest extent / diameter.
    const Bounds bounds = worldBounds(scene.objects[0], 0);
    const glm::vec3 size = bounds.max - bounds.min;
    const double factor = std::max({size.x, size.y, size.z}) / (2.0 * bounds.sphereRadius);
    const nlohmann::json& written = document["nodes"][0]["extras"]["MSFT_screencoverage"];
    ASSERT_EQ(written.size(), 3u);
    EXPECT_NEAR(written[0].get<double>(), 0.4 * factor, 1e-6);
    EXPECT_NEAR(written[2].get<double>(), 0.02 * factor, 1e-6);
    EXPECT_LT(factor, 0.99);  // a cylinder with a lid: not a cube, so the conventions differ
    // Read back: screen sizes again, everything else as exported.
    expectSameScene(scene, loadGltf(dir.file("unity.gltf"), noGeneration()));
}

TEST(GltfExport, TexturedSceneRoundTripsPixelForPixel) {
    TempDir dir;
    const Scene scene = handBuiltScene(true);
    for (const char* name : {"textured.gltf", "textured.GLB"}) {
        SCOPED_TRACE(name);
        exportGltf(scene, dir.file(name));
        const Scene loaded = loadGltf(dir.file(name), noGeneration());
        expectSameScene(scene, loaded);
        EXPECT_EQ(loaded.objects[0].levels[0].stats.textureBytes, (4u * 4u + 8u * 8u) * 4u);
    }
}

// Every material property survives export and reload: each of the six glTF minification
// filters and three wrap modes, texture transforms, texCoord, alpha modes, emissive strength,
// unlit, the PBR factors and maps.
TEST(GltfExport, EveryMaterialPropertyRoundTrips) {
    TempDir dir;
    Scene scene = handBuiltScene(true);
    const std::pair<FilterMode, MipmapMode> minifications[] = {
        {FilterMode::Nearest, MipmapMode::None},   {FilterMode::Linear, MipmapMode::None},
        {FilterMode::Nearest, MipmapMode::Nearest}, {FilterMode::Linear, MipmapMode::Nearest},
        {FilterMode::Nearest, MipmapMode::Linear},  {FilterMode::Linear, MipmapMode::Linear}};
    const WrapMode wraps[] = {WrapMode::Repeat, WrapMode::ClampToEdge, WrapMode::MirroredRepeat};
    scene.materials.clear();
    for (int m = 0; m < 6; ++m) {
        Material material;
        material.name = "m" + std::to_string(m);
        material.baseColorFactor = {0.5f, 0.25f, 1.0f, 0.75f};
        material.metallicFactor = 0.125f * float(m);
        material.roughnessFactor = 1.0f - 0.125f * float(m);
        material.alphaMode = AlphaMode(m % 3);
        material.alphaCutoff = 0.25f;
        material.doubleSided = m % 2 == 0;
        material.unlit = m == 5;
        material.baseColorTexture.texture = m % 2;
        material.baseColorTexture.sampler.minFilter = minifications[m].first;
        material.baseColorTexture.sampler.mipmap = minifications[m].second;
        material.baseColorTexture.sampler.magFilter = m < 3 ? FilterMode::Nearest : FilterMode::Linear;
        material.baseColorTexture.sampler.wrapS = wraps[m % 3];
        material.baseColorTexture.sampler.wrapT = wraps[(m + 1) % 3];
        material.baseColorTexture.transform = {{0.5f * float(m), -0.25f}, 0.125f * float(m), {2.0f, 0.5f}};
        material.normalTexture = {1, 1, {}, {}};
        material.normalScale = 0.5f;
        material.occlusionTexture = {0, 0, {}, {}};
        material.occlusionStrength = 0.75f;
        material.metallicRoughnessTexture = {1, 0, {}, {}};
        material.emissiveTexture = {0, 0, {}, {}};
        material.emissiveFactor = {1.0f, 0.5f, 0.0f};
        material.emissiveStrength = float(m + 1);
        scene.materials.push_back(material);
    }
    exportGltf(scene, dir.file("materials.glb"));
    const Scene loaded = loadGltf(dir.file("materials.glb"), noGeneration());
    ASSERT_EQ(loaded.materials.size(), scene.materials.size());
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
        SCOPED_TRACE(scene.materials[m].name);
        const Material &a = scene.materials[m], &b = loaded.materials[m];
        EXPECT_EQ(b.baseColorFactor, a.baseColorFactor);
        EXPECT_EQ(b.metallicFactor, a.metallicFactor);
        EXPECT_EQ(b.roughnessFactor, a.roughnessFactor);
        EXPECT_EQ(b.alphaMode, a.alphaMode);
        if (a.alphaMode == AlphaMode::Mask) EXPECT_EQ(b.alphaCutoff, a.alphaCutoff);
        EXPECT_EQ(b.doubleSided, a.doubleSided);
        EXPECT_EQ(b.unlit, a.unlit);
        EXPECT_EQ(b.baseColorTexture.texture, a.baseColorTexture.texture);
        EXPECT_TRUE(b.baseColorTexture.sampler == a.baseColorTexture.sampler);
        EXPECT_EQ(b.baseColorTexture.transform.offset, a.baseColorTexture.transform.offset);
        EXPECT_EQ(b.baseColorTexture.transform.rotation, a.baseColorTexture.transform.rotation);
        EXPECT_EQ(b.baseColorTexture.transform.scale, a.baseColorTexture.transform.scale);
        EXPECT_EQ(b.normalTexture.texture, 1);
        EXPECT_EQ(b.normalTexture.texCoord, 1);
        EXPECT_EQ(b.normalScale, a.normalScale);
        EXPECT_EQ(b.occlusionTexture.texture, 0);
        EXPECT_EQ(b.occlusionStrength, a.occlusionStrength);
        EXPECT_EQ(b.metallicRoughnessTexture.texture, 1);
        EXPECT_EQ(b.emissiveTexture.texture, 0);
        EXPECT_EQ(b.emissiveFactor, a.emissiveFactor);
        EXPECT_EQ(b.emissiveStrength, a.emissiveStrength);
    }
}

TEST(GltfExport, AuthoredLevelsAreNotRegeneratedOnReload) {
    TempDir dir;
    const Scene scene = handBuiltScene(false);
    exportGltf(scene, dir.file("levels.glb"));
    GltfLoadOptions options;  // generateLods on
    const Scene loaded = loadGltf(dir.file("levels.glb"), options);
    ASSERT_EQ(loaded.objects.size(), 2u);
    EXPECT_EQ(loaded.objects[0].levels.size(), 3u);
    for (const Level& level : loaded.objects[0].levels) EXPECT_EQ(level.simplificationError, 0.0f);
}

TEST(GltfExport, RefusesOtherExtensionsAndLeavesNothingOnFailure) {
    TempDir dir;
    Scene scene = handBuiltScene(false);
    EXPECT_THROW(exportGltf(scene, dir.file("scene.obj")), SceneError);
    scene.objects[1].levels[0].meshes[0].indices.push_back(100000);  // broken: index out of range
    scene.objects[1].levels[0].meshes[0].indices.push_back(0);
    scene.objects[1].levels[0].meshes[0].indices.push_back(1);
    EXPECT_THROW(exportGltf(scene, dir.file("broken.gltf")), SceneError);
    EXPECT_FALSE(std::filesystem::exists(dir.file("broken.gltf")));
    for (const auto& entry : std::filesystem::directory_iterator(dir.file(""))) ADD_FAILURE() << "left behind: " << entry.path();
}

// Models from /work/shared/data: load (with generated chains), export, load again.
TEST(GltfExport, SharedModelsRoundTrip) {
    const std::string data = testing::sharedDataDir() + "/gltf";
    if (!std::filesystem::exists(data)) GTEST_SKIP() << data << " is absent (shared test data)";
    TempDir dir;
    const char* models[] = {"models/FlightHelmet/FlightHelmet.gltf", "msft_lod/babylon_LevelOfDetail/LevelOfDetail.glb",
                            "models/gltf-transform/many-cubes.gltf", "models/kenney/cakeBirthday.glb",
                            "models/babylon/cannon.glb"};
    int index = 0;
    for (const char* model : models) {
        SCOPED_TRACE(model);
        const Scene scene = loadGltf(data + "/" + model);
        const std::string out = dir.file("model" + std::to_string(index) + (index % 2 ? ".glb" : ".gltf"));
        ++index;
        exportGltf(scene, out);
        expectSameScene(scene, loadGltf(out, noGeneration()));
    }
}

// Fox has no NORMAL: every level of its generated chain is drawn with flat normals, and the
// export leaves NORMAL (and TANGENT) out, so that a reader, lodopt included, draws it flat again.
TEST(GltfExport, FlatNormalsSurviveGenerationAndExport) {
    const std::string fox = testing::sharedDataDir() + "/gltf/models/Fox/Fox.glb";
    if (!std::filesystem::exists(fox)) GTEST_SKIP() << fox << " is absent (shared test data)";
    TempDir dir;
    const Scene scene = loadGltf(fox);
    ASSERT_EQ(scene.objects.size(), 1u);
    ASSERT_GE(scene.objects[0].levels.size(), 3u);
    auto everyMeshFlat = [](const Scene& s) {
        for (const Object& object : s.objects) {
            for (const Level& level : object.levels) {
                for (const Mesh& mesh : level.meshes) {
                    if (!mesh.flatNormals || mesh.normals.size() != mesh.positions.size()) return false;
                }
            }
        }
        return true;
    };
    EXPECT_TRUE(everyMeshFlat(scene));
    exportGltf(scene, dir.file("fox.gltf"));
    const std::string json = [&] {
        std::ifstream in(dir.file("fox.gltf"));
        return std::string(std::istreambuf_iterator<char>(in), {});
    }();
    EXPECT_EQ(json.find("\"NORMAL\""), std::string::npos);
    const Scene reloaded = loadGltf(dir.file("fox.gltf"), noGeneration());
    EXPECT_TRUE(everyMeshFlat(reloaded));
    expectSameScene(scene, reloaded);
    // A file with normals keeps them.
    const Scene box = loadGltf(testing::sharedDataDir() + "/gltf/render-tests/BoxTextured/glTF/BoxTextured.gltf");
    EXPECT_FALSE(box.objects.at(0).levels.at(0).meshes.at(0).flatNormals);
}

}  // namespace
}  // namespace lodopt::scenes
