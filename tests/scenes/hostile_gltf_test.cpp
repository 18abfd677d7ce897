// Hostile glTF input (issue #9): each case is a clear SceneError naming the file and element,
// or a documented, sane handling — never a crash, a hang or an allocation the file does not
// back. gltf_errors_test.cpp has the basic catalogue; this file adds the attacks around it
// (docs/robustness.md lists every case and what it does), replays the fuzz corpus and the
// crash regressions, and truncates and corrupts a GLB at every byte.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>
#include <sys/stat.h>

#include "../fuzz/fuzz_inputs.hpp"
#include "gltf_test_files.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "lodopt_test_paths.hpp"

namespace lodopt::scenes {
namespace {

using nlohmann::json;
using testing::GltfFile;
using testing::kFloat;
using testing::kUnsignedByte;
using testing::kUnsignedInt;
using testing::kUnsignedShort;
using testing::TempDir;

GltfLoadOptions plain(std::vector<std::string>* warnings = nullptr) {
    GltfLoadOptions options;
    options.generateLods = false;
    options.warnings = warnings;
    return options;
}

// Loads `path` and expects a SceneError whose message contains every one of `parts`.
void expectError(const std::string& path, const std::vector<std::string>& parts, GltfLoadOptions options = plain()) {
    try {
        loadGltf(path, options);
        ADD_FAILURE() << path << ": loaded, expected an error with '" << parts.front() << "'";
    } catch (const SceneError& e) {
        const std::string message = e.what();
        for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
    }
}

std::vector<char> readBytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string writeBytes(const TempDir& dir, const std::string& name, const std::vector<char>& bytes) {
    const std::string path = dir.file(name);
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
}

void putU32(std::vector<char>& bytes, std::size_t at, std::uint32_t value) {
    std::memcpy(bytes.data() + at, &value, 4);
}

GltfFile quadFile() {
    GltfFile file;
    file.addNode({{"name", "quad"}, {"mesh", file.addQuadMesh()}}, true);
    return file;
}

// ---- GLB container ---------------------------------------------------------------------

TEST(HostileGltf, GlbChunkLengthsPastTheEndOrWrapping) {
    TempDir dir;
    GltfFile file = quadFile();
    const std::vector<char> whole = readBytes(file.writeGlb(dir, "whole"));
    ASSERT_NO_THROW(loadGltf(dir.file("whole.glb"), plain()));
    // JSON chunk length 0xFFFFFFFC: 12 + 8 + length wraps a 32-bit sum.
    std::vector<char> huge = whole;
    putU32(huge, 12, 0xFFFFFFFCu);
    expectError(writeBytes(dir, "huge.glb", huge), {"huge.glb", "GLB chunk 0", "run past the end"});
    // Header length shorter than the chunks: the JSON chunk no longer fits.
    std::vector<char> shortHeader = whole;
    putU32(shortHeader, 8, 24);
    expectError(writeBytes(dir, "short.glb", shortHeader), {"short.glb", "GLB chunk 0"});
    // Only the 12-byte header.
    std::vector<char> headerOnly(whole.begin(), whole.begin() + 12);
    putU32(headerOnly, 8, 12);
    expectError(writeBytes(dir, "header.glb", headerOnly), {"header.glb", "no JSON chunk"});
    // Version 1, and an empty JSON chunk.
    std::vector<char> version = whole;
    putU32(version, 4, 1);
    expectError(writeBytes(dir, "version.glb", version), {"version.glb", "version 1"});
    std::vector<char> emptyJson(whole.begin(), whole.begin() + 20);
    putU32(emptyJson, 8, 20);
    putU32(emptyJson, 12, 0);
    expectError(writeBytes(dir, "empty_json.glb", emptyJson), {"empty_json.glb"});
}

// Every prefix of a valid GLB, and the GLB with each byte set to 0xFF in turn: each loads or
// throws SceneError (the sanitizer build checks that nothing reads out of bounds meanwhile).
TEST(HostileGltf, GlbTruncatedOrCorruptedAtEveryByte) {
    TempDir dir;
    GltfFile file = quadFile();
    const std::vector<char> whole = readBytes(file.writeGlb(dir, "whole"));
    ASSERT_GT(whole.size(), 100u);
    // A fresh name per variant: rewriting one file in place makes ext4 flush it on every close.
    int refused = 0;
    for (std::size_t size = 0; size < whole.size(); ++size) {
        const std::vector<char> prefix(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(size));
        try {
            loadGltf(writeBytes(dir, "cut" + std::to_string(size) + ".glb", prefix), plain());
        } catch (const SceneError&) {
            ++refused;
        }
    }
    EXPECT_EQ(refused, static_cast<int>(whole.size())) << "every strict prefix of a GLB is truncated";
    int loaded = 0;
    for (std::size_t at = 0; at < whole.size(); ++at) {
        std::vector<char> corrupt = whole;
        corrupt[at] = static_cast<char>(0xFF);
        try {
            const Scene scene = loadGltf(writeBytes(dir, "corrupt" + std::to_string(at) + ".glb", corrupt), plain());
            validateScene(scene);
            ++loaded;
        } catch (const SceneError&) {
        }
    }
    EXPECT_GT(loaded, 0) << "bytes inside the vertex data change values, not validity";
}

// ---- Accessors -------------------------------------------------------------------------

TEST(HostileGltf, AccessorsWithHugeCountsOffsetsOrStrides) {
    TempDir dir;
    GltfFile count = quadFile();
    count.doc["accessors"][0]["count"] = std::numeric_limits<std::uint32_t>::max();
    expectError(count.write(dir, "count"), {"accessors[0]", "run past bufferView 0"});
    GltfFile offset = quadFile();
    offset.doc["accessors"][0]["byteOffset"] = std::uint64_t(1) << 31;
    expectError(offset.write(dir, "offset"), {"accessors[0]"});
    GltfFile stride = quadFile();
    stride.doc["bufferViews"][0]["byteStride"] = 256;
    expectError(stride.write(dir, "stride"), {"stride.gltf", "byteStride", "256"});
    GltfFile tiny = quadFile();
    tiny.doc["bufferViews"][0]["byteStride"] = 4;
    expectError(tiny.write(dir, "tiny"), {"accessors[0]", "smaller than an element"});
    GltfFile negative = quadFile();
    negative.doc["accessors"][0]["count"] = -3;
    expectError(negative.write(dir, "negative"), {"negative.gltf"});
    GltfFile enormous = quadFile();
    enormous.doc["accessors"][0]["count"] = 1e300;
    expectError(enormous.write(dir, "enormous"), {"enormous.gltf"});
    GltfFile buffer = quadFile();
    const std::string path = buffer.write(dir, "buffer");
    buffer.doc["buffers"][0]["byteLength"] = std::uint64_t(1) << 40;
    std::ofstream(path) << buffer.doc.dump();
    expectError(path, {"buffer.gltf"});
}

// POSITION without a bufferView (zeros), three vertices replaced by a sparse accessor.
TEST(HostileGltf, SparseAccessorsSubstituteAndAreRangeChecked) {
    TempDir dir;
    auto sparseFile = [](std::vector<std::uint16_t> targets, std::vector<float> values, std::size_t count) {
        GltfFile file;
        const int indices = file.addView(targets.data(), targets.size() * 2);
        const int replacements = file.addView(values.data(), values.size() * 4);
        file.doc["accessors"].push_back(
            {{"componentType", kFloat},
             {"count", count},
             {"type", "VEC3"},
             {"sparse",
              {{"count", targets.size()},
               {"indices", {{"bufferView", indices}, {"componentType", kUnsignedShort}}},
               {"values", {{"bufferView", replacements}}}}}});
        const int position = static_cast<int>(file.doc["accessors"].size()) - 1;
        file.addNode({{"name", "sparse"},
                      {"mesh", file.addMesh({{"attributes", {{"POSITION", position}}},
                                             {"indices", file.addIndices({0, 1, 2, 0, 2, 3})}})}},
                     true);
        return file;
    };
    GltfFile valid = sparseFile({1, 2, 3}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, 4);
    const Scene scene = loadGltf(valid.write(dir, "valid"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    const std::vector<glm::vec3>& p = scene.objects[0].levels[0].meshes[0].positions;
    ASSERT_EQ(p.size(), 4u);
    EXPECT_EQ(p[0], glm::vec3(0, 0, 0));
    EXPECT_EQ(p[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(p[2], glm::vec3(1, 1, 0));
    EXPECT_EQ(p[3], glm::vec3(0, 1, 0));

    GltfFile past = sparseFile({1, 9, 3}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, 4);
    expectError(past.write(dir, "past"), {"past.gltf", "sparse.indices", "index 9 >= count 4"});
    GltfFile tooMany = sparseFile({0, 1, 2, 3}, std::vector<float>(12, 0.5f), 3);
    expectError(tooMany.write(dir, "too_many"), {"accessors[", "sparse.count", "4 is not in 1..3"});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    GltfFile notFinite = sparseFile({1, 2, 3}, {1, 0, 0, nan, 1, 0, 0, 1, 0}, 4);
    expectError(notFinite.write(dir, "nan"), {"attributes.POSITION", "element 2 is not finite"});
    GltfFile viewPast = sparseFile({1, 2, 3}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, 4);
    viewPast.doc["accessors"][0]["sparse"]["values"]["byteOffset"] = 32;
    expectError(viewPast.write(dir, "view_past"), {"sparse.values", "run past bufferView"});
    // A huge sparse count without a bufferView is capped by the file's data like a dense one.
    GltfFile huge = sparseFile({1, 2, 3}, {1, 0, 0, 1, 1, 0, 0, 1, 0}, 4);
    huge.doc["accessors"][0]["count"] = std::uint64_t(1) << 31;
    expectError(huge.write(dir, "huge"), {"without a bufferView"});
}

// Sparse index accessors are substituted as integers: an index past 2^24 must not be rounded
// to a float on the way (regression: it was read through the float path).
TEST(HostileGltf, SparseIndicesKeepEveryBitOfTheIndex) {
    TempDir dir;
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3);
    const std::vector<std::uint32_t> base = {0, 1, 2};
    const int dense = file.addView(base.data(), 12);
    const std::uint8_t target = 2;
    const std::uint32_t value = 16777217u;  // 2^24 + 1: not a float
    const int targets = file.addView(&target, 1);
    const int values = file.addView(&value, 4);
    file.doc["accessors"].push_back(
        {{"bufferView", dense},
         {"componentType", kUnsignedInt},
         {"count", 3},
         {"type", "SCALAR"},
         {"sparse",
          {{"count", 1},
           {"indices", {{"bufferView", targets}, {"componentType", kUnsignedByte}}},
           {"values", {{"bufferView", values}}}}}});
    const int indices = static_cast<int>(file.doc["accessors"].size()) - 1;
    file.addNode({{"mesh", file.addMesh({{"attributes", {{"POSITION", position}}}, {"indices", indices}})}}, true);
    expectError(file.write(dir, "sparse_index"), {"indices", "index 16777217 >= vertex count 3"});
}

TEST(HostileGltf, IndexValuesPastTheVertexCountInEveryFormatAndMode) {
    TempDir dir;
    GltfFile bytes;
    const int position = bytes.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0}, "VEC3", 3);
    const std::vector<std::uint8_t> small = {0, 1, 200};
    const int byteIndices = bytes.addAccessor(bytes.addView(small.data(), 3), kUnsignedByte, 3, "SCALAR");
    bytes.addNode({{"mesh", bytes.addMesh({{"attributes", {{"POSITION", position}}}, {"indices", byteIndices}})}}, true);
    expectError(bytes.write(dir, "bytes"), {"indices", "index 200 >= vertex count 3"});
    GltfFile strip;
    const int stripPosition = strip.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
    strip.addNode({{"mesh", strip.addMesh({{"attributes", {{"POSITION", stripPosition}}},
                                           {"indices", strip.addIndices16({0, 1, 2, 3, 4000})},
                                           {"mode", 5}})}},
                  true);
    expectError(strip.write(dir, "strip"), {"indices", "index 4000 >= vertex count 4"});
    GltfFile ragged = quadFile();
    ragged.doc["accessors"][1]["count"] = 5;  // 5 indices is not whole triangles
    expectError(ragged.write(dir, "ragged"), {"indices", "not a multiple of 3"});
    GltfFile vectorIndices = quadFile();
    vectorIndices.doc["accessors"][1]["type"] = "VEC2";
    vectorIndices.doc["accessors"][1]["count"] = 3;
    expectError(vectorIndices.write(dir, "vector"), {"indices", "SCALAR"});
}

// ---- Values ----------------------------------------------------------------------------

TEST(HostileGltf, NonFiniteValuesAnywhereAndTransformsThatOverflow) {
    TempDir dir;
    const float inf = std::numeric_limits<float>::infinity();
    GltfFile normal = quadFile();
    normal.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
        normal.addFloats({0, 0, 1, 0, 0, 1, 0, inf, 1, 0, 0, 1}, "VEC3", 3);
    expectError(normal.write(dir, "normal"), {"accessors[2]", "element 2 is not finite"});
    GltfFile uv = quadFile();
    uv.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
        uv.addFloats({0, 0, 1, 0, -inf, 1, 0, 1}, "VEC2", 2);
    expectError(uv.write(dir, "uv"), {"accessors[2]", "element 2 is not finite"});
    // Finite numbers whose product is not: a child scaled by 1e30 of a vertex at 1e30.
    GltfFile overflow;
    const int big = overflow.addMesh(
        {{"attributes", {{"POSITION", overflow.addFloats({0, 0, 0, 1e30f, 0, 0, 0, 1e30f, 0}, "VEC3", 3)}}}});
    overflow.addNode({{"name", "parent"}, {"mesh", big}, {"children", {1}}}, true);
    overflow.addNode({{"name", "child"}, {"mesh", big}, {"scale", {1e30, 1e30, 1e30}}}, false);
    expectError(overflow.write(dir, "overflow"), {"overflow", "position", "not finite"});
    // The object's own transform overflowing its vertices: refused the same way (world bounds
    // and default views would be infinite).
    GltfFile scaled;
    scaled.addNode({{"name", "scaled"},
                    {"mesh", scaled.addMesh({{"attributes",
                                              {{"POSITION", scaled.addFloats({0, 0, 0, 1e30f, 0, 0, 0, 1e30f, 0},
                                                                             "VEC3", 3)}}}})},
                    {"scale", {1e30, 1e30, 1e30}}},
                   true);
    expectError(scaled.write(dir, "scaled"), {"scaled", "not finite"});
}

// Degenerate (repeated index) and zero-area (collinear) triangles load as they are: they
// draw nothing, their normals fall back to +Y, and LOD generation copes with them.
TEST(HostileGltf, DegenerateAndZeroAreaTrianglesLoadWithFiniteNormals) {
    TempDir dir;
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0}, "VEC3", 3);  // collinear
    file.addNode({{"name", "flat"},
                  {"mesh", file.addMesh({{"attributes", {{"POSITION", position}}},
                                         {"indices", file.addIndices({0, 1, 2, 1, 1, 1, 3, 3, 0, 0, 2, 3})}})}},
                 true);
    const std::string path = file.write(dir, "degenerate");
    for (bool generate : {false, true}) {
        GltfLoadOptions options = plain();
        options.generateLods = generate;
        const Scene scene = loadGltf(path, options);
        ASSERT_EQ(scene.objects.size(), 1u);
        EXPECT_EQ(scene.objects[0].levels[0].stats.triangles, 4u);
        for (const Level& level : scene.objects[0].levels) {
            for (const Mesh& mesh : level.meshes) {
                for (const glm::vec3& n : mesh.normals) {
                    EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
                    EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
                }
            }
        }
        EXPECT_NO_THROW(validateScene(scene));
    }
    // Every vertex at one point: zero-size bounds still get default views with finite planes.
    GltfFile point;
    const int same = point.addFloats({5, 5, 5, 5, 5, 5, 5, 5, 5}, "VEC3", 3);
    point.addNode({{"name", "point"}, {"mesh", point.addMesh({{"attributes", {{"POSITION", same}}}})}}, true);
    const Scene scene = loadScene(point.write(dir, "point"));
    ASSERT_EQ(scene.views.size(), 3u);
    for (const Camera& camera : scene.views) {
        EXPECT_TRUE(std::isfinite(camera.position.x) && camera.nearPlane > 0.0f && camera.farPlane > camera.nearPlane);
    }
}

// ---- Node graph ------------------------------------------------------------------------

// 100,000 nested nodes: refused with a message instead of overflowing the stack of the
// recursive walks (a real model nests a few dozen levels).
TEST(HostileGltf, DeepNodeHierarchyIsRefusedNotAStackOverflow) {
    TempDir dir;
    GltfFile file;
    const int mesh = file.addQuadMesh();
    const int depth = 100000;
    file.doc["nodes"] = json::array();
    for (int n = 0; n < depth; ++n) {
        json node = {{"name", "n"}};
        if (n + 1 < depth) node["children"] = {n + 1};
        if (n + 1 == depth) node["mesh"] = mesh;
        file.doc["nodes"].push_back(node);
    }
    file.doc["scenes"][0]["nodes"] = {0};
    expectError(file.write(dir, "deep"), {"deep.gltf", "nodes[", "deeper than"});
    // A merely deep one (200 levels) still loads: one object, the mesh node.
    GltfFile fine;
    const int fineMesh = fine.addQuadMesh();
    fine.doc["nodes"] = json::array();
    for (int n = 0; n < 200; ++n) {
        json node = {{"name", std::to_string(n)}, {"translation", {0.0, 0.01, 0.0}}};
        if (n + 1 < 200) node["children"] = {n + 1};
        if (n + 1 == 200) node["mesh"] = fineMesh;
        fine.doc["nodes"].push_back(node);
    }
    fine.doc["scenes"][0]["nodes"] = {0};
    const Scene scene = loadGltf(fine.write(dir, "fine"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_NEAR(scene.objects[0].transform[3][1], 2.0f, 1e-3f);
}

// Deeply nested JSON (extras are free-form) would overflow the stack of tinygltf's recursive
// value conversion: refused before parsing.
TEST(HostileGltf, DeeplyNestedJsonIsRefusedBeforeParsing) {
    TempDir dir;
    GltfFile file = quadFile();
    const std::string path = file.write(dir, "nested");
    std::string text = file.doc.dump();
    const std::string extras = "\"extras\":" + std::string(200000, '[') + std::string(200000, ']') + ",";
    text.insert(1, extras);
    std::ofstream(path) << text;
    expectError(path, {"nested.gltf", "nested deeper than"});
    // Brackets inside strings do not count.
    file.doc["nodes"][0]["name"] = std::string(5000, '[');
    EXPECT_NO_THROW(loadGltf(file.write(dir, "brackets"), plain()));
}

// A buffer uri naming a FIFO would block the load forever (no writer ever comes), a device
// would be read as data: only regular files are read.
TEST(HostileGltf, BuffersThatNameFifosDevicesOrFoldersAreRefused) {
    TempDir dir;
    GltfFile file = quadFile();
    const std::string path = file.write(dir, "device");
    ASSERT_EQ(::mkfifo(dir.file("pipe.bin").c_str(), 0600), 0);
    for (const std::string uri : {"pipe.bin", "../../../../../../../../dev/zero", "."}) {
        file.doc["buffers"][0]["uri"] = uri;
        std::ofstream(path) << file.doc.dump();
        expectError(path, {"device.gltf"});
    }
}

// ---- Textures --------------------------------------------------------------------------

// A PNG or JPEG whose header promises more pixels than the byte limit is refused before a
// decoder allocates anything; a corrupt one is a clear error.
TEST(HostileGltf, OversizedOrCorruptTexturesAreRefused) {
    TempDir dir;
    auto textured = [](const std::vector<std::uint8_t>& image) {
        GltfFile file = quadFile();
        file.doc["meshes"][0]["primitives"][0]["material"] = 0;
        file.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
        file.doc["textures"] = {{{"source", 0}}};
        file.doc["images"] = {{{"bufferView", file.addView(image.data(), image.size())}, {"mimeType", "image/png"}}};
        return file;
    };
    // PNG signature + IHDR of 60000 x 60000 RGBA (14.4 GB decoded), no pixel data.
    std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0, 0, 13, 'I', 'H', 'D', 'R',
                                     0, 0, 0xEA, 0x60, 0, 0, 0xEA, 0x60, 8, 6, 0, 0, 0, 0, 0, 0, 0};
    GltfFile bigPng = textured(png);
    expectError(bigPng.write(dir, "big_png"), {"images[0]", "60000x60000", "over the byte limit"});
    // A baseline JPEG frame header (SOF0) of 60000 x 60000, three components, then nothing.
    std::vector<std::uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xC0, 0x00, 0x11, 0x08, 0xEA, 0x60, 0xEA, 0x60, 0x03,
                                      0x01, 0x22, 0x00, 0x02, 0x11, 0x01, 0x03, 0x11, 0x01, 0xFF, 0xD9};
    GltfFile bigJpeg = textured(jpeg);
    expectError(bigJpeg.write(dir, "big_jpeg"), {"images[0]", "60000x60000", "over the byte limit"});
    // A small PNG header whose pixel data is garbage.
    std::vector<std::uint8_t> corrupt = png;
    corrupt[18] = corrupt[22] = 0;
    corrupt[19] = corrupt[23] = 4;
    corrupt.insert(corrupt.end(), {0, 0, 0, 8, 'I', 'D', 'A', 'T', 1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 0, 0});
    GltfFile garbage = textured(corrupt);
    expectError(garbage.write(dir, "garbage"), {"images[0]", "cannot be decoded"});
}

// ---- Empty scenes and objects ----------------------------------------------------------

TEST(HostileGltf, NoObjectsOrObjectsWithoutTrianglesAreLeftOutWithAWarning) {
    TempDir dir;
    GltfFile empty;
    const Scene none = loadGltf(empty.write(dir, "empty"), plain());
    EXPECT_TRUE(none.objects.empty());
    const Scene withViews = loadScene(dir.file("empty.gltf"));
    EXPECT_EQ(withViews.views.size(), 3u) << "default views frame a unit box when there is nothing to frame";

    // "line" has a two-vertex strip (no triangle), "quad" is fine.
    GltfFile mixed = quadFile();
    const int two = mixed.addFloats({0, 0, 0, 1, 0, 0}, "VEC3", 3);
    mixed.addNode({{"name", "line"}, {"mesh", mixed.addMesh({{"attributes", {{"POSITION", two}}}, {"mode", 5}})}}, true);
    std::vector<std::string> warnings;
    const Scene scene = loadGltf(mixed.write(dir, "mixed"), plain(&warnings));
    ASSERT_EQ(scene.objects.size(), 1u);
    EXPECT_EQ(scene.objects[0].name, "quad");
    ASSERT_FALSE(warnings.empty());
    EXPECT_NE(warnings.back().find("'line' has no triangles"), std::string::npos) << warnings.back();
}

// ---- The fuzz corpus and crash regressions ---------------------------------------------

// Every seed and every input that once crashed the fuzz_gltf target goes through the same
// function the fuzzer calls (tests/fuzz/fuzz_inputs.hpp), in every build.
TEST(HostileGltf, FuzzCorpusAndRegressionsLoadOrFailCleanly) {
    const std::filesystem::path root = std::filesystem::path(LODOPT_SOURCE_DIR) / "tests" / "fuzz";
    int inputs = 0;
    for (const char* folder : {"corpus/gltf", "regressions/gltf"}) {
        if (!std::filesystem::exists(root / folder)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(root / folder)) {
            const std::vector<char> bytes = readBytes(entry.path().string());
            SCOPED_TRACE(entry.path().string());
            EXPECT_NO_THROW(fuzz::loadGltfBytes(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
            ++inputs;
        }
    }
    EXPECT_GE(inputs, 10) << "the seed corpus is checked in under tests/fuzz/corpus/gltf";
}

// Found by fuzzing in CI (2026-12-01): an image's bufferView of 728 bytes inside a 188-byte
// GLB buffer. tinygltf passes it to the image loader unchecked, which read past the buffer.
TEST(HostileGltf, ImageBufferViewPastItsBufferIsRefusedBeforeAnyRead) {
    const std::filesystem::path file =
        std::filesystem::path(LODOPT_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / "gltf" / "image-view-past-buffer.glb";
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    try {
        loadGltf(file.string());
        ADD_FAILURE() << "loaded";
    } catch (const SceneError& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find("bufferViews[0] (an image) runs past the end of buffers[0]"), std::string::npos)
            << message;
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace lodopt::scenes
