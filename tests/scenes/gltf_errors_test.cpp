// Bad glTF input: each case is a small file written here that breaks one thing; loading must
// throw SceneError naming the file and the glTF element, never crash.
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "gltf_test_files.hpp"
#include "scenes/gltf_io.hpp"

namespace lodopt::scenes {
namespace {

using nlohmann::json;
using testing::GltfFile;
using testing::TempDir;

// Loads `path` and expects a SceneError whose message has every one of `parts`.
void expectError(const std::string& path, const std::vector<std::string>& parts, GltfLoadOptions options = {}) {
    options.generateLods = false;
    try {
        loadGltf(path, options);
        ADD_FAILURE() << path << ": loaded, expected an error with '" << parts.front() << "'";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
    }
}

// One quad node: the base that each case breaks.
GltfFile quadFile() {
    GltfFile file;
    file.addNode({{"name", "quad"}, {"mesh", file.addQuadMesh()}}, true);
    return file;
}

TEST(GltfErrors, MissingFileAndInvalidJson) {
    TempDir dir;
    expectError(dir.file("absent.gltf"), {"absent.gltf", "no such file"});
    const std::string broken = dir.file("broken.gltf");
    std::ofstream(broken) << "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [";
    expectError(broken, {"broken.gltf:"});
    const std::string empty = dir.file("empty.gltf");
    std::ofstream(empty) << "";
    expectError(empty, {"empty.gltf", "empty"});
}

TEST(GltfErrors, BufferViewPastItsBuffer) {
    TempDir dir;
    GltfFile file = quadFile();
    file.doc["bufferViews"][1]["byteLength"] = 4096;
    expectError(file.write(dir, "view"), {"view.gltf", "bufferViews[1]", "run past the end of buffer 0"});
}

TEST(GltfErrors, AccessorPastItsBufferView) {
    TempDir dir;
    GltfFile file = quadFile();
    file.doc["accessors"][0]["count"] = 5;
    expectError(file.write(dir, "count"), {"accessors[0]", "run past bufferView 0"});
    GltfFile strided = quadFile();
    strided.doc["bufferViews"][0]["byteStride"] = 252;
    expectError(strided.write(dir, "stride"), {"accessors[0]", "stride 252"});
}

TEST(GltfErrors, HugeCountWithoutBufferViewIsCappedByTheFileData) {
    TempDir dir;
    GltfFile file = quadFile();
    file.doc["accessors"].push_back({{"componentType", 5126}, {"count", std::numeric_limits<std::uint32_t>::max()}, {"type", "VEC3"}});
    file.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 2;
    expectError(file.write(dir, "huge"), {"accessors[2]", "without a bufferView"});
}

TEST(GltfErrors, IndexPastTheVertexCount) {
    TempDir dir;
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
    file.addNode({{"mesh", file.addMesh({{"attributes", {{"POSITION", position}}}, {"indices", file.addIndices({0, 1, 7})}})}}, true);
    expectError(file.write(dir, "model"), {"model.gltf: meshes[0].primitives[0].indices: index 7 >= vertex count 4"});
}

TEST(GltfErrors, NonTrianglePrimitive) {
    TempDir dir;
    GltfFile file = quadFile();
    file.doc["meshes"][0]["primitives"][0]["mode"] = 1;
    expectError(file.write(dir, "lines"), {"meshes[0].primitives[0].mode", "LINES"});
    file.doc["meshes"][0]["primitives"][0]["mode"] = 0;
    expectError(file.write(dir, "points"), {"meshes[0].primitives[0].mode", "POINTS"});
}

TEST(GltfErrors, NonFinitePositions) {
    TempDir dir;
    GltfFile file;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const int position = file.addFloats({0, 0, 0, nan, 0, 0, 1, 1, 0}, "VEC3", 3);
    file.addNode({{"mesh", file.addMesh({{"attributes", {{"POSITION", position}}}})}}, true);
    expectError(file.write(dir, "nan"), {"accessors[0]", "element 1 is not finite"});
    GltfFile infinite;
    const int position2 = infinite.addFloats({0, 0, 0, 1, 0, 0, 1, std::numeric_limits<float>::infinity(), 0}, "VEC3", 3);
    infinite.addNode({{"mesh", infinite.addMesh({{"attributes", {{"POSITION", position2}}}})}}, true);
    expectError(infinite.write(dir, "inf"), {"accessors[0]", "element 2 is not finite"});
}

TEST(GltfErrors, UnresolvedReferences) {
    TempDir dir;
    GltfFile child = quadFile();
    child.doc["nodes"][0]["children"] = {5};
    expectError(child.write(dir, "child"), {"nodes[0].children[0]", "node 5 does not exist"});
    GltfFile root = quadFile();
    root.doc["scenes"][0]["nodes"].push_back(9);
    expectError(root.write(dir, "root"), {"scenes[0].nodes[1]", "node 9 does not exist"});
    GltfFile positions = quadFile();
    positions.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 42;
    expectError(positions.write(dir, "positions"), {"meshes[0].primitives[0].attributes.POSITION", "accessor 42"});
    GltfFile material = quadFile();
    material.doc["meshes"][0]["primitives"][0]["material"] = 3;
    expectError(material.write(dir, "material"), {"meshes[0].primitives[0].material", "material 3"});
    GltfFile mesh = quadFile();
    mesh.doc["nodes"][0]["mesh"] = 2;
    expectError(mesh.write(dir, "mesh"), {"nodes[0].mesh", "mesh 2"});
}

TEST(GltfErrors, NodeLoopsAndSharedChildren) {
    TempDir dir;
    GltfFile loop = quadFile();
    loop.addNode({{"name", "a"}, {"children", {2}}}, false);
    loop.addNode({{"name", "b"}, {"children", {1}}}, false);
    expectError(loop.write(dir, "loop"), {"node loop"});
    GltfFile self = quadFile();
    self.doc["nodes"][0]["children"] = {0};
    expectError(self.write(dir, "self"), {"nodes[0].children", "its own child"});
    GltfFile shared = quadFile();
    shared.addNode({{"name", "leaf"}}, false);
    shared.addNode({{"name", "p1"}, {"children", {1}}}, true);
    shared.addNode({{"name", "p2"}, {"children", {1}}}, true);
    expectError(shared.write(dir, "shared"), {"nodes[3].children", "already has parent node 2"});
}

// MSFT_lod ids that do not exist, loop, or point at the node itself, an ancestor, a
// descendant, or a node another chain already uses.
TEST(GltfErrors, BadMsftLodIds) {
    TempDir dir;
    auto withLod = [](const json& ids) {
        GltfFile file = quadFile();
        file.doc["nodes"][0]["extensions"] = {{"MSFT_lod", {{"ids", ids}}}};
        file.addNode({{"name", "coarse"}, {"mesh", 0}}, false);  // node 1
        return file;
    };
    const std::string lod = "nodes[0].extensions.MSFT_lod.ids[0]";
    GltfFile missing = withLod({7});
    expectError(missing.write(dir, "missing"), {lod, "node 7 does not exist"});
    GltfFile self = withLod({0});
    expectError(self.write(dir, "self"), {lod, "level-0 node itself"});
    GltfFile notIndex = withLod({"one"});
    expectError(notIndex.write(dir, "text"), {lod, "not an index"});
    GltfFile looping = withLod({1});
    looping.doc["nodes"][1]["extensions"] = {{"MSFT_lod", {{"ids", {0}}}}};
    expectError(looping.write(dir, "looping"), {"has its own MSFT_lod"});
    GltfFile ancestor = withLod({1});
    ancestor.doc["nodes"][1]["children"] = {0};
    ancestor.doc["scenes"][0]["nodes"] = {1};
    expectError(ancestor.write(dir, "ancestor"), {lod, "is an ancestor of node 0"});
    GltfFile descendant = withLod({1});
    descendant.doc["nodes"][0]["children"] = {1};
    expectError(descendant.write(dir, "descendant"), {lod, "is a descendant of node 0"});
    GltfFile used = withLod({1});
    used.addNode({{"name", "other"}, {"mesh", 0}, {"extensions", {{"MSFT_lod", {{"ids", {1}}}}}}}, true);
    expectError(used.write(dir, "used"), {"nodes[2].extensions.MSFT_lod.ids[0]", "already a level of node 0"});
    GltfFile material = quadFile();
    material.doc["materials"] = {{{"name", "m"}, {"extensions", {{"MSFT_lod", {{"ids", {4}}}}}}}};
    expectError(material.write(dir, "material"), {"materials[0].extensions.MSFT_lod.ids[0]", "material 4 does not exist"});
}

TEST(GltfErrors, TruncatedGlb) {
    TempDir dir;
    GltfFile file = quadFile();
    const std::string path = file.writeGlb(dir, "whole");
    ASSERT_NO_THROW(loadGltf(path));
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto writeBytes = [&](const std::string& name, std::size_t size) {
        std::ofstream(dir.file(name), std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(size));
        return dir.file(name);
    };
    expectError(writeBytes("cut.glb", bytes.size() - 8), {"cut.glb", "GLB header", "truncated"});
    expectError(writeBytes("header.glb", 10), {"header.glb", "GLB header", "truncated"});
    // Fix the total length so that only the BIN chunk runs past the end.
    std::vector<char> patched(bytes.begin(), bytes.end() - 8);
    const std::uint32_t length = static_cast<std::uint32_t>(patched.size());
    std::memcpy(patched.data() + 8, &length, 4);
    std::ofstream(dir.file("chunk.glb"), std::ios::binary).write(patched.data(), static_cast<std::streamsize>(patched.size()));
    expectError(dir.file("chunk.glb"), {"chunk.glb", "GLB chunk 1", "run past the end"});
}

TEST(GltfErrors, UnsupportedRequiredExtension) {
    TempDir dir;
    GltfFile basisu = quadFile();
    basisu.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    basisu.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    expectError(basisu.write(dir, "basisu"), {"extensionsRequired", "KHR_texture_basisu is not supported"});
}

// A buffer without uri in a .gltf is valid glTF (the validator passes it: its data is the
// application's); what is drawn from it reads zeros, and a warning names the buffer.
TEST(GltfErrors, BufferWithoutUriReadsZerosWithAWarning) {
    TempDir dir;
    GltfFile bufferless = quadFile();
    const std::string path = bufferless.write(dir, "bufferless");
    bufferless.doc["buffers"][0].erase("uri");
    std::ofstream(path) << bufferless.doc.dump();
    std::vector<std::string> warnings;
    GltfLoadOptions options;
    options.generateLods = false;
    options.warnings = &warnings;
    const Scene scene = loadGltf(path, options);
    ASSERT_EQ(scene.objects.size(), 1u);
    for (const glm::vec3& p : scene.objects[0].levels[0].meshes.at(0).positions) EXPECT_EQ(p, glm::vec3(0.0f));
    ASSERT_EQ(warnings.size(), 1u) << ::testing::PrintToString(warnings);
    EXPECT_NE(warnings[0].find("bufferless.gltf: buffers[0] has no uri and the file holds no data for it"),
              std::string::npos)
        << warnings[0];
}

TEST(GltfErrors, MissingBaseColorImage) {
    TempDir dir;
    GltfFile file = quadFile();
    file.doc["images"] = {{{"uri", "missing.png"}}};
    file.doc["textures"] = {{{"source", 0}}};
    file.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    file.doc["meshes"][0]["primitives"][0]["material"] = 0;
    expectError(file.write(dir, "image"), {"images[0]", "missing.png"});
}

TEST(GltfErrors, FileOverTheByteLimit) {
    TempDir dir;
    GltfFile file = quadFile();
    GltfLoadOptions options;
    options.maxBytes = 64;
    expectError(file.write(dir, "limit"), {"limit.gltf", "over the limit"}, options);
}

TEST(GltfErrors, WrongAttributeTypes) {
    TempDir dir;
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 1, 1, 0, 0}, "VEC2", 2);
    file.addNode({{"mesh", file.addMesh({{"attributes", {{"POSITION", position}}}})}}, true);
    expectError(file.write(dir, "vec2"), {"meshes[0].primitives[0].attributes.POSITION", "must be VEC3"});
    GltfFile unequal = quadFile();
    unequal.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        unequal.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3", 3);
    expectError(unequal.write(dir, "unequal"), {"attributes.POSITION", "differs"});
}

}  // namespace
}  // namespace lodopt::scenes
