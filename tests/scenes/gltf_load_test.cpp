// glTF loading on small hand-built files: hierarchy and transforms, primitive modes,
// quantized attributes, MSFT_lod on nodes and materials, <name>_LOD<k> siblings, cameras.
#include <cmath>

#include <gtest/gtest.h>

#include "gltf_test_files.hpp"
#include "scenes/gltf_io.hpp"

namespace lodopt::scenes {
namespace {

using testing::GltfFile;
using testing::TempDir;
using nlohmann::json;

GltfLoadOptions plain() {
    GltfLoadOptions options;
    options.generateLods = false;
    return options;
}

glm::vec3 apply(const glm::mat4& m, glm::vec3 p) { return glm::vec3(m * glm::vec4(p, 1.0f)); }

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// group (translation 1,2,3) → quad (scale 2): the mesh node is the object, the group only
// moves it.
TEST(GltfLoad, MeshlessGroupIsTransformAndMeshNodeIsObject) {
    TempDir dir;
    GltfFile file;
    const int quad = file.addQuadMesh();
    file.doc["nodes"] = json::array();
    file.addNode({{"name", "group"}, {"translation", {1, 2, 3}}, {"children", {1}}}, true);
    file.addNode({{"name", "quad"}, {"mesh", quad}, {"scale", {2, 2, 2}}}, false);
    Scene scene = loadGltf(file.write(dir, "hierarchy"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    const Object& object = scene.objects[0];
    EXPECT_EQ(object.name, "quad");
    EXPECT_EQ(scene.name, "hierarchy");  // no scene name: the file stem
    ASSERT_EQ(object.levels.size(), 1u);
    EXPECT_EQ(object.levels[0].stats.triangles, 2u);
    EXPECT_EQ(object.levels[0].stats.vertices, 4u);
    expectNear(apply(object.transform, {1, 0, 0}), {3, 2, 3});
    // Normals were absent: generated, facing +Z for a counter-clockwise quad.
    for (const glm::vec3& n : object.levels[0].meshes[0].normals) expectNear(n, {0, 0, 1});
}

// A mesh node's children without LODs join its level 0, in its space; a mirroring child
// keeps its front faces (winding flipped).
TEST(GltfLoad, ChildrenJoinLevelZeroAndMirrorFlipsWinding) {
    TempDir dir;
    GltfFile file;
    const int quad = file.addQuadMesh();
    file.addNode({{"name", "parent"}, {"mesh", quad}, {"translation", {0, 0, -7}}, {"children", {1, 2}}}, true);
    file.addNode({{"name", "moved"}, {"mesh", quad}, {"translation", {5, 0, 0}}}, false);
    file.addNode({{"name", "mirrored"}, {"mesh", quad}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}}, false);
    Scene scene = loadGltf(file.write(dir, "children"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    const Level& level = scene.objects[0].levels[0];
    ASSERT_EQ(level.meshes.size(), 3u);
    EXPECT_EQ(level.stats.drawCalls, 3u);
    EXPECT_EQ(level.stats.triangles, 6u);
    expectNear(level.meshes[1].positions[1], {6, 0, 0});
    expectNear(level.meshes[2].positions[1], {-1, 0, 0});
    for (const glm::vec3& n : level.meshes[2].normals) expectNear(n, {0, 0, 1});
    expectNear(apply(scene.objects[0].transform, {0, 0, 0}), {0, 0, -7});
}

TEST(GltfLoad, StripsFansAndNonIndexedBecomeTriangleLists) {
    TempDir dir;
    GltfFile file;
    const int strip = file.addFloats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3);
    const int fan = file.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0}, "VEC3", 3);
    const int soup = file.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0, 2, 1, 0}, "VEC3", 3);
    file.addNode({{"name", "strip"}, {"mesh", file.addMesh({{"attributes", {{"POSITION", strip}}}, {"mode", 5}})}}, true);
    file.addNode({{"name", "fan"}, {"mesh", file.addMesh({{"attributes", {{"POSITION", fan}}}, {"mode", 6}})}}, true);
    file.addNode({{"name", "soup"}, {"mesh", file.addMesh({{"attributes", {{"POSITION", soup}}}})}}, true);
    Scene scene = loadGltf(file.write(dir, "modes"), plain());
    ASSERT_EQ(scene.objects.size(), 3u);
    // Strip order is the spec's (§3.7.2.1): triangle i = (v_i, v_{i+1+i%2}, v_{i+2-i%2}).
    EXPECT_EQ(scene.objects[0].levels[0].meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 1, 3, 2}));
    EXPECT_EQ(scene.objects[1].levels[0].meshes[0].indices, (std::vector<std::uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
    EXPECT_EQ(scene.objects[2].levels[0].meshes[0].indices, (std::vector<std::uint32_t>{0, 1, 2, 3, 4, 5}));
}

TEST(GltfLoad, QuantizedTexcoordsAndShortIndices) {
    TempDir dir;
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3);
    // Normalized unsigned bytes, stride 4 (vertex attributes are 4-byte aligned).
    const std::uint8_t uvBytes[12] = {0, 0, 0, 0, 255, 0, 0, 0, 255, 255, 0, 0};
    const int uv = file.addAccessor(file.addView(uvBytes, sizeof(uvBytes), 4), testing::kUnsignedByte, 3, "VEC2", true);
    const std::uint16_t normalShorts[12] = {0, 0, 32767, 0, 32767, 0, 0, 0, 0, 32767, 0, 0};
    file.doc["accessors"].push_back({{"bufferView", file.addView(normalShorts, sizeof(normalShorts), 8)},
                                     {"componentType", 5122},
                                     {"normalized", true},
                                     {"count", 3},
                                     {"type", "VEC3"}});
    const int normal = static_cast<int>(file.doc["accessors"].size()) - 1;
    const int indices = file.addIndices16({0, 1, 2});
    file.addNode({{"mesh", file.addMesh({{"attributes", {{"POSITION", position}, {"NORMAL", normal}, {"TEXCOORD_0", uv}}},
                                         {"indices", indices}})}},
                 true);
    Scene scene = loadGltf(file.write(dir, "quantized"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].name, "node0");
    const Mesh& mesh = scene.objects[0].levels[0].meshes[0];
    ASSERT_EQ(mesh.uvs.size(), 3u);
    EXPECT_FLOAT_EQ(mesh.uvs[1].x, 1.0f);
    EXPECT_FLOAT_EQ(mesh.uvs[2].y, 1.0f);
    expectNear(mesh.normals[0], {0, 0, 1});
    expectNear(mesh.normals[1], {1, 0, 0});
}

// Level 0 (quad) with MSFT_lod ids [1, 2]: a triangle, then nothing but a smaller triangle.
TEST(GltfLoad, NodeMsftLodWithScreenCoverageIsNotRegenerated) {
    TempDir dir;
    GltfFile file;
    const int quad = file.addQuadMesh();
    const int triangle = file.addMesh({{"attributes", {{"POSITION", file.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3", 3)}}}});
    file.addNode({{"name", "lod0"},
                  {"mesh", quad},
                  {"translation", {10, 0, 0}},
                  {"extensions", {{"MSFT_lod", {{"ids", {1, 2}}}}}},
                  {"extras", {{"MSFT_screencoverage", {0.5, 0.2, 0.01}}}}},
                 true);
    file.addNode({{"name", "lod1"}, {"mesh", triangle}, {"translation", {10, 0, 0}}}, false);
    file.addNode({{"name", "lod2"}, {"mesh", triangle}, {"translation", {10, 0, 0}}, {"scale", {0.5, 0.5, 0.5}}}, false);
    file.doc["extensionsUsed"] = {"MSFT_lod"};
    GltfLoadOptions options;  // generateLods on: must leave authored levels alone
    Scene scene = loadGltf(file.write(dir, "nodelod"), options);
    ASSERT_EQ(scene.objects.size(), 1u);
    const Object& object = scene.objects[0];
    EXPECT_EQ(object.name, "lod0");
    ASSERT_EQ(object.levels.size(), 3u);
    EXPECT_EQ(object.levels[0].stats.triangles, 2u);
    EXPECT_EQ(object.levels[1].stats.triangles, 1u);
    EXPECT_EQ(object.levels[2].stats.triangles, 1u);
    // Levels share level 0's placement: the coarse triangle is not moved twice.
    expectNear(object.levels[1].meshes[0].positions[1], {1, 0, 0});
    expectNear(object.levels[2].meshes[0].positions[1], {0.5f, 0, 0});
    ASSERT_TRUE(object.levels[0].screenCoverage && object.levels[2].screenCoverage);
    EXPECT_FLOAT_EQ(*object.levels[0].screenCoverage, 0.5f);
    EXPECT_FLOAT_EQ(*object.levels[2].screenCoverage, 0.01f);
    for (const Level& level : object.levels) EXPECT_EQ(level.simplificationError, 0.0f);
}

// The glTF-Toolkit layout: mesh-less LOD roots whose children hold the meshes, the coarse
// root outside the scene.
TEST(GltfLoad, MeshlessMsftLodRoots) {
    TempDir dir;
    GltfFile file;
    const int quad = file.addQuadMesh();
    file.addNode({{"name", "polygon"}, {"mesh", quad}}, false);
    file.addNode({{"name", "root"}, {"children", {0}}, {"extensions", {{"MSFT_lod", {{"ids", {3}}}}}}}, true);
    file.addNode({{"name", "polygon_lod1"}, {"mesh", quad}, {"translation", {0, 0, 1}}}, false);
    file.addNode({{"name", "root_lod1"}, {"children", {2}}}, false);
    Scene scene = loadGltf(file.write(dir, "toolkit"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].name, "root");
    ASSERT_EQ(scene.objects[0].levels.size(), 2u);
    expectNear(scene.objects[0].levels[1].meshes[0].positions[0], {0, 0, 1});
}

TEST(GltfLoad, SiblingsNamedLodKBecomeOneObject) {
    TempDir dir;
    GltfFile file;
    const int quad = file.addQuadMesh();
    const int small = file.addQuadMesh(-1, 0.5f);
    file.addNode({{"name", "Tree_LOD1"}, {"mesh", small}}, true);
    file.addNode({{"name", "Rock"}, {"mesh", quad}}, true);
    file.addNode({{"name", "Tree_LOD0"}, {"mesh", quad}, {"children", {3}}}, true);
    file.addNode({{"name", "Leaves"}, {"mesh", quad}}, false);
    file.addNode({{"name", "tree_lod2"}, {"mesh", small}}, true);
    Scene scene = loadGltf(file.write(dir, "named"), plain());
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_EQ(scene.objects[0].name, "Rock");
    EXPECT_EQ(scene.objects[1].name, "Tree");  // emitted where its finest level is
    ASSERT_EQ(scene.objects[1].levels.size(), 3u);
    EXPECT_EQ(scene.objects[1].levels[0].stats.drawCalls, 2u);  // Tree_LOD0 and its child
    EXPECT_EQ(scene.objects[1].levels[1].stats.drawCalls, 1u);
}

// Material High has MSFT_lod [Medium, Low]: same geometry, one level per material level.
TEST(GltfLoad, MaterialMsftLodGivesOneLevelPerMaterial) {
    TempDir dir;
    GltfFile file;
    file.doc["materials"] = {{{"name", "Low"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 1, 1}}}}},
                             {{"name", "Medium"}, {"pbrMetallicRoughness", {{"baseColorFactor", {0, 1, 0, 1}}}}},
                             {{"name", "High"},
                              {"pbrMetallicRoughness", {{"baseColorFactor", {1, 0, 0, 1}}}},
                              {"extensions", {{"MSFT_lod", {{"ids", {1, 0}}}}}}}};
    file.addNode({{"name", "a"}, {"mesh", file.addQuadMesh(2)}}, true);
    file.addNode({{"name", "b"}, {"mesh", file.addQuadMesh(1)}}, true);  // Medium: no chain of its own
    GltfLoadOptions options;
    Scene scene = loadGltf(file.write(dir, "matlod"), options);
    ASSERT_EQ(scene.materials.size(), 3u);
    EXPECT_EQ(scene.materials[2].name, "High");
    EXPECT_FLOAT_EQ(scene.materials[1].baseColorFactor.g, 1.0f);
    ASSERT_EQ(scene.objects.size(), 2u);
    ASSERT_EQ(scene.objects[0].levels.size(), 3u);
    EXPECT_EQ(scene.objects[0].levels[0].meshes[0].material, 2);
    EXPECT_EQ(scene.objects[0].levels[1].meshes[0].material, 1);
    EXPECT_EQ(scene.objects[0].levels[2].meshes[0].material, 0);
    // b's material has no chain: without generated LODs it keeps one level.
    EXPECT_EQ(loadGltf(dir.file("matlod.gltf"), plain()).objects[1].levels.size(), 1u);
}

TEST(GltfLoad, PerspectiveCamerasBecomeViews) {
    TempDir dir;
    GltfFile file;
    file.addNode({{"name", "quad"}, {"mesh", file.addQuadMesh()}}, true);
    file.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", M_PI / 4}, {"znear", 0.5}, {"zfar", 50}}}},
                           {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
                           {{"type", "perspective"}, {"perspective", {{"yfov", 1.0}, {"znear", 0.1}}}}};
    file.addNode({{"name", "front"}, {"camera", 0}, {"translation", {0, 0, 10}}}, true);
    file.addNode({{"name", "ortho"}, {"camera", 1}}, true);
    // Rotated 90° about +Y: looks down -X from +X.
    file.addNode({{"name", "rig"}, {"translation", {10, 0, 0}}, {"children", {4}}}, true);
    file.addNode({{"name", "side"}, {"camera", 2}, {"rotation", {0, std::sin(M_PI / 4), 0, std::cos(M_PI / 4)}}}, false);
    std::vector<std::string> warnings;
    GltfLoadOptions options = plain();
    options.warnings = &warnings;
    Scene scene = loadGltf(file.write(dir, "cameras"), options);
    ASSERT_EQ(scene.views.size(), 2u);
    const Camera& front = scene.views[0];
    EXPECT_EQ(front.name, "front");
    expectNear(front.position, {0, 0, 10});
    expectNear(glm::normalize(front.target - front.position), {0, 0, -1});
    expectNear(front.up, {0, 1, 0});
    EXPECT_NEAR(front.fovYDegrees, 45.0f, 1e-4f);
    EXPECT_FLOAT_EQ(front.nearPlane, 0.5f);
    EXPECT_FLOAT_EQ(front.farPlane, 50.0f);
    const Camera& side = scene.views[1];
    expectNear(side.position, {10, 0, 0});
    expectNear(glm::normalize(side.target - side.position), {-1, 0, 0});
    EXPECT_GT(side.farPlane, side.nearPlane);  // infinite projection: a far plane is chosen
    bool warned = false;
    for (const std::string& w : warnings) warned = warned || w.find("orthographic") != std::string::npos;
    EXPECT_TRUE(warned);
}

TEST(GltfLoad, NoCameraNoView) {
    TempDir dir;
    GltfFile file;
    file.addNode({{"name", "quad"}, {"mesh", file.addQuadMesh()}}, true);
    // Default views are loadScene()'s business (builtin.hpp), not the loader's.
    EXPECT_TRUE(loadGltf(file.write(dir, "noview"), plain()).views.empty());
}

TEST(GltfLoad, GlbAndGltfGiveTheSameScene) {
    TempDir dir;
    GltfFile file;
    file.addNode({{"name", "quad"}, {"mesh", file.addQuadMesh()}, {"translation", {1, 1, 1}}}, true);
    Scene text = loadGltf(file.write(dir, "same"), plain());
    Scene binary = loadGltf(file.writeGlb(dir, "same"), plain());
    ASSERT_EQ(binary.objects.size(), 1u);
    EXPECT_EQ(binary.objects[0].levels[0].meshes[0].positions, text.objects[0].levels[0].meshes[0].positions);
    EXPECT_EQ(binary.objects[0].transform, text.objects[0].transform);
}

TEST(GltfLoad, LinesAreSkippedWithAWarningWhenAsked) {
    TempDir dir;
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3);
    file.doc["meshes"] = {{{"primitives",
                            {{{"attributes", {{"POSITION", position}}}, {"mode", 1}},
                             {{"attributes", {{"POSITION", position}}}, {"mode", 4}}}}}};
    file.addNode({{"name", "mixed"}, {"mesh", 0}}, true);
    std::vector<std::string> warnings;
    GltfLoadOptions options = plain();
    options.skipNonTrianglePrimitives = true;
    options.warnings = &warnings;
    Scene scene = loadGltf(file.write(dir, "lines"), options);
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].levels[0].stats.triangles, 1u);
    ASSERT_FALSE(warnings.empty());
    EXPECT_NE(warnings[0].find("meshes[0].primitives[0].mode"), std::string::npos) << warnings[0];
}

TEST(GltfLoad, DenseMeshWithoutLodsGetsAGeneratedChain) {
    TempDir dir;
    GltfFile file;
    // A 24 x 24 grid with a bump: 1152 triangles, welded.
    const int n = 25;
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    for (int z = 0; z < n; ++z) {
        for (int x = 0; x < n; ++x) {
            const float fx = x / float(n - 1), fz = z / float(n - 1);
            positions.insert(positions.end(), {fx, 0.3f * std::sin(3.0f * fx) * std::cos(2.0f * fz), fz});
        }
    }
    for (int z = 0; z + 1 < n; ++z) {
        for (int x = 0; x + 1 < n; ++x) {
            const std::uint32_t a = z * n + x, b = a + 1, c = a + n, d = c + 1;
            indices.insert(indices.end(), {a, c, b, b, c, d});
        }
    }
    file.addNode({{"name", "terrain"},
                  {"mesh", file.addMesh({{"attributes", {{"POSITION", file.addFloats(positions, "VEC3", 3)}}},
                                         {"indices", file.addIndices(indices)}})}},
                 true);
    Scene scene = loadGltf(file.write(dir, "dense"));
    ASSERT_EQ(scene.objects.size(), 1u);
    const Object& object = scene.objects[0];
    ASSERT_GE(object.levels.size(), 4u);
    EXPECT_EQ(object.levels[0].stats.triangles, 1152u);
    EXPECT_EQ(object.levels[0].simplificationError, 0.0f);
    for (std::size_t k = 1; k < object.levels.size(); ++k) {
        EXPECT_LE(double(object.levels[k].stats.triangles), 0.9 * double(object.levels[k - 1].stats.triangles));
        EXPECT_LT(object.levels[k].stats.vertices, object.levels[k - 1].stats.vertices);
        EXPECT_GT(object.levels[k].simplificationError, 0.0f);
    }
}

TEST(GltfLoad, SceneRootThatHasAParentLoadsWithAWarning) {
    TempDir dir;
    GltfFile file;
    file.addNode({{"name", "tmpParent"}, {"children", {1}}, {"translation", {100, 0, 0}}}, false);
    file.addNode({{"name", "tile"}, {"mesh", file.addQuadMesh()}}, true);
    std::vector<std::string> warnings;
    GltfLoadOptions options = plain();
    options.warnings = &warnings;
    Scene scene = loadGltf(file.write(dir, "nonroot"), options);
    ASSERT_EQ(scene.objects.size(), 1u);
    expectNear(apply(scene.objects[0].transform, {0, 0, 0}), {0, 0, 0});
    EXPECT_FALSE(warnings.empty());
}

}  // namespace
}  // namespace lodopt::scenes
