// Compressed and extended glTF on tiny hand-made files: EXT_meshopt_compression (filters,
// index modes, fallback buffers), EXT_texture_webp, KHR_draco_mesh_compression refusals,
// percent-encoded and data uris, and how required and optional extensions are treated
// (docs/gltf.md, "Extensions"). The packed shared models are checked in
// tests/evaluation/packed_gltf_render_test.cpp.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/gtc/type_ptr.hpp>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

#include "gltf_test_files.hpp"
#include "scenes/gltf_io.hpp"

namespace lodopt::scenes {
namespace {

using namespace testing;
using json = nlohmann::json;

constexpr int kByte = 5120;

GltfLoadOptions plain(std::vector<std::string>* warnings = nullptr) {
    GltfLoadOptions options;
    options.generateLods = false;
    options.warnings = warnings;
    return options;
}

std::string errorOf(const std::string& path) {
    try {
        loadGltf(path, plain());
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(loaded)";
}

void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                static_cast<std::streamsize>(bytes.size()));
}

// A .glb with `doc` as JSON and `bin` as the BIN chunk (buffer 0).
std::string writeGlb(const TempDir& dir, const std::string& name, const json& doc, std::vector<std::uint8_t> bin) {
    std::string text = doc.dump();
    while (text.size() % 4 != 0) text += ' ';
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::vector<std::uint8_t> out;
    auto u32 = [&](std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    };
    u32(0x46546C67u);
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    u32(static_cast<std::uint32_t>(text.size()));
    u32(0x4E4F534Au);
    out.insert(out.end(), text.begin(), text.end());
    u32(static_cast<std::uint32_t>(bin.size()));
    u32(0x004E4942u);
    out.insert(out.end(), bin.begin(), bin.end());
    const std::string path = dir.file(name + ".glb");
    writeBytes(path, out);
    return path;
}

// A quad whose positions (EXPONENTIAL filter), normals (OCTAHEDRAL filter, 8-bit) and indices
// (TRIANGLES or INDICES mode, 16-bit) are meshopt-compressed in buffer 0; the views lie in
// buffer 1, a fallback buffer without data. Drawn:
//   3 ---- 2     positions (0,0,0) (2,0,0) (2,1,0) (0,1,0)
//   |  \   |     normals tilted: (0.6, 0, 0.8) at every vertex
//   0 ---- 1     triangles 0 1 2, 0 2 3
struct MeshoptQuad {
    json doc;
    std::vector<std::uint8_t> bin;
};

const std::vector<float> kQuadPositions = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
const std::vector<std::uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

MeshoptQuad meshoptQuad(const std::string& indexMode) {
    MeshoptQuad quad;
    std::uint32_t fallbackOffset = 0;
    auto addStream = [&](const std::vector<std::uint8_t>& compressed, std::size_t count, std::size_t stride,
                         const std::string& mode, const std::string& filter) {
        while (quad.bin.size() % 4 != 0) quad.bin.push_back(0);
        json meshopt = {{"buffer", 0},     {"byteOffset", quad.bin.size()}, {"byteLength", compressed.size()},
                        {"byteStride", stride}, {"count", count},          {"mode", mode}};
        if (!filter.empty()) meshopt["filter"] = filter;
        quad.bin.insert(quad.bin.end(), compressed.begin(), compressed.end());
        json view = {{"buffer", 1}, {"byteOffset", fallbackOffset}, {"byteLength", count * stride},
                     {"extensions", {{"EXT_meshopt_compression", meshopt}}}};
        if (mode == "ATTRIBUTES") view["byteStride"] = stride;
        fallbackOffset += static_cast<std::uint32_t>((count * stride + 3) / 4 * 4);
        quad.doc["bufferViews"].push_back(view);
        return static_cast<int>(quad.doc["bufferViews"].size()) - 1;
    };
    auto encodeVertices = [](const void* vertices, std::size_t count, std::size_t stride) {
        std::vector<std::uint8_t> out(meshopt_encodeVertexBufferBound(count, stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), vertices, count, stride));
        return out;
    };

    std::vector<std::uint32_t> positions(12);
    meshopt_encodeFilterExp(positions.data(), 4, 12, 15, kQuadPositions.data());
    const int positionView = addStream(encodeVertices(positions.data(), 4, 12), 4, 12, "ATTRIBUTES", "EXPONENTIAL");

    const std::vector<float> normals = {0.6f, 0, 0.8f, 0, 0.6f, 0, 0.8f, 0, 0.6f, 0, 0.8f, 0, 0.6f, 0, 0.8f, 0};
    std::vector<std::int8_t> octahedral(16);
    meshopt_encodeFilterOct(octahedral.data(), 4, 4, 8, normals.data());
    const int normalView = addStream(encodeVertices(octahedral.data(), 4, 4), 4, 4, "ATTRIBUTES", "OCTAHEDRAL");

    std::vector<std::uint8_t> indices(64);
    indices.resize(indexMode == "TRIANGLES"
                       ? meshopt_encodeIndexBuffer(indices.data(), indices.size(), kQuadIndices.data(), 6)
                       : meshopt_encodeIndexSequence(indices.data(), indices.size(), kQuadIndices.data(), 6));
    const int indexView = addStream(indices, 6, 2, indexMode, "");

    quad.doc["asset"] = {{"version", "2.0"}};
    quad.doc["extensionsUsed"] = {"EXT_meshopt_compression"};
    quad.doc["extensionsRequired"] = {"EXT_meshopt_compression"};
    quad.doc["buffers"] = {{{"byteLength", (quad.bin.size() + 3) / 4 * 4}},
                           {{"byteLength", fallbackOffset},
                            {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
    quad.doc["accessors"] = {
        {{"bufferView", positionView}, {"componentType", kFloat}, {"count", 4}, {"type", "VEC3"},
         {"min", {0, 0, 0}}, {"max", {2, 1, 0}}},
        {{"bufferView", normalView}, {"componentType", kByte}, {"normalized", true}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", indexView}, {"componentType", kUnsignedShort}, {"count", 6}, {"type", "SCALAR"}}};
    const json primitive = {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}};
    quad.doc["meshes"] = json::array({{{"primitives", json::array({primitive})}}});
    quad.doc["nodes"] = {{{"mesh", 0}, {"name", "quad"}}};
    quad.doc["scenes"] = {{{"nodes", {0}}}};
    quad.doc["scene"] = 0;
    return quad;
}

void expectQuad(const Scene& scene) {
    ASSERT_EQ(scene.objects.size(), 1u);
    const Mesh& mesh = scene.objects[0].levels[0].meshes.at(0);
    ASSERT_EQ(mesh.positions.size(), 4u);
    for (int v = 0; v < 4; ++v) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(mesh.positions[v][c], kQuadPositions[3 * v + c], 1e-3f) << v;
        // 8-bit octahedral: about 1/127 per component.
        EXPECT_NEAR(mesh.normals[v].x, 0.6f, 0.02f) << v;
        EXPECT_NEAR(mesh.normals[v].y, 0.0f, 0.02f) << v;
        EXPECT_NEAR(mesh.normals[v].z, 0.8f, 0.02f) << v;
    }
    EXPECT_EQ(mesh.indices, kQuadIndices);
}

TEST(GltfCompressed, MeshoptFiltersAndTriangleIndicesWithAFallbackBufferInAGlb) {
    TempDir dir;
    MeshoptQuad quad = meshoptQuad("TRIANGLES");
    expectQuad(loadGltf(writeGlb(dir, "quad", quad.doc, quad.bin), plain()));
}

TEST(GltfCompressed, MeshoptIndexSequenceWithAFallbackBufferWithoutUriInAGltf) {
    TempDir dir;
    MeshoptQuad quad = meshoptQuad("INDICES");
    writeBytes(dir.file("quad.bin"), quad.bin);
    quad.doc["buffers"][0]["uri"] = "quad.bin";
    quad.doc["buffers"][0]["byteLength"] = quad.bin.size();
    std::ofstream(dir.file("quad.gltf")) << quad.doc.dump();
    expectQuad(loadGltf(dir.file("quad.gltf"), plain()));
}

TEST(GltfCompressed, HostileMeshoptStreamsAreRefusedByElement) {
    TempDir dir;
    MeshoptQuad truncated = meshoptQuad("TRIANGLES");
    truncated.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"]["byteLength"] = 5;
    std::string message = errorOf(writeGlb(dir, "truncated", truncated.doc, truncated.bin));
    EXPECT_NE(message.find("truncated.glb: bufferViews[1].extensions.EXT_meshopt_compression"), std::string::npos) << message;
    EXPECT_NE(message.find("cannot be decoded"), std::string::npos) << message;

    MeshoptQuad past = meshoptQuad("TRIANGLES");
    past.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"] = 4000;
    message = errorOf(writeGlb(dir, "past", past.doc, past.bin));
    EXPECT_NE(message.find("bufferViews[0].extensions.EXT_meshopt_compression: bytes 4000.."), std::string::npos)
        << message;

    MeshoptQuad stride = meshoptQuad("TRIANGLES");
    stride.doc["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 3;
    message = errorOf(writeGlb(dir, "stride", stride.doc, stride.bin));
    EXPECT_NE(message.find("bufferViews[2].extensions.EXT_meshopt_compression.byteStride: 3 must be 2 or 4"),
              std::string::npos)
        << message;

    MeshoptQuad huge = meshoptQuad("TRIANGLES");
    huge.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["count"] = 1e12;
    message = errorOf(writeGlb(dir, "huge", huge.doc, huge.bin));
    EXPECT_NE(message.find("bufferViews[0].extensions.EXT_meshopt_compression: decodes to"), std::string::npos)
        << message;

    // A plain view in a fallback buffer has no data to read.
    MeshoptQuad plainView = meshoptQuad("TRIANGLES");
    plainView.doc["bufferViews"][2].erase("extensions");
    message = errorOf(writeGlb(dir, "plain", plainView.doc, plainView.bin));
    EXPECT_NE(message.find("plain.glb: bufferViews[2]: lies in buffers[1]"), std::string::npos) << message;
}

// A 2x2 lossless WebP: red, green / blue, white (half transparent).
std::vector<std::uint8_t> webpImage() {
    const std::uint8_t rgba[16] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
    std::uint8_t* encoded = nullptr;
    const std::size_t size = WebPEncodeLosslessRGBA(rgba, 2, 2, 8, &encoded);
    std::vector<std::uint8_t> bytes(encoded, encoded + size);
    WebPFree(encoded);
    return bytes;
}

// A textured quad whose texture names its image through EXT_texture_webp only; the image and
// the buffer are found through percent-encoded uris (a folder, a space and a '+').
GltfFile webpQuad(const std::string& imageUri) {
    GltfFile file;
    const int position = file.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3", 3);
    const int uv = file.addFloats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2", 2);
    const int indices = file.addIndices({0, 1, 2, 0, 2, 3});
    file.addMesh({{"attributes", {{"POSITION", position}, {"TEXCOORD_0", uv}}}, {"indices", indices}, {"material", 0}});
    file.addNode({{"mesh", 0}}, true);
    file.doc["images"] = {{{"uri", imageUri}}};
    file.doc["textures"] = {{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}};
    file.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    file.doc["extensionsUsed"] = {"EXT_texture_webp"};
    file.doc["extensionsRequired"] = {"EXT_texture_webp"};
    return file;
}

TEST(GltfCompressed, WebpTextureThroughPercentEncodedUris) {
    TempDir dir;
    std::filesystem::create_directories(dir.file("textures"));
    writeBytes(dir.file("textures/grass one+1.webp"), webpImage());
    GltfFile file = webpQuad("textures%2Fgrass%20one+1.webp");
    const std::string path = file.write(dir, "my model");  // writes "my model.bin", uri "my model.bin"
    json doc = json::parse(std::ifstream(path));
    doc["buffers"][0]["uri"] = "my%20model.bin";
    std::ofstream(path) << doc.dump();

    const Scene scene = loadGltf(path, plain());
    ASSERT_EQ(scene.textures.size(), 1u);
    const Texture& texture = scene.textures[0];
    ASSERT_EQ(texture.width, 2);
    ASSERT_EQ(texture.height, 2);
    const std::vector<std::uint8_t> expected = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
    EXPECT_EQ(texture.rgba, expected);  // lossless
    EXPECT_EQ(scene.materials.at(0).baseColorTexture.texture, 0);
}

TEST(GltfCompressed, WebpDataUriAndBadWebpHeaders) {
    TempDir dir;
    // data:image/webp (tinygltf 2.7 reads it as a file name on its own).
    const std::vector<std::uint8_t> webp = webpImage();
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string base64;
    for (std::size_t i = 0; i < webp.size(); i += 3) {
        const std::uint32_t group = (std::uint32_t(webp[i]) << 16) | (i + 1 < webp.size() ? webp[i + 1] << 8 : 0) |
                                    (i + 2 < webp.size() ? webp[i + 2] : 0);
        base64 += kAlphabet[(group >> 18) & 63];
        base64 += kAlphabet[(group >> 12) & 63];
        base64 += i + 1 < webp.size() ? kAlphabet[(group >> 6) & 63] : '=';
        base64 += i + 2 < webp.size() ? kAlphabet[group & 63] : '=';
    }
    GltfFile embedded = webpQuad("data:image/webp;base64," + base64);
    EXPECT_EQ(loadGltf(embedded.write(dir, "embedded"), plain()).textures.at(0).width, 2);

    std::vector<std::uint8_t> badHeader = webp;
    badHeader[12] = 'X';  // "VP8L" chunk tag broken
    writeBytes(dir.file("bad.webp"), badHeader);
    GltfFile bad = webpQuad("bad.webp");
    std::string message = errorOf(bad.write(dir, "bad"));
    EXPECT_NE(message.find("bad.gltf: images[0]: cannot be decoded as PNG, JPEG or WebP"), std::string::npos) << message;

    std::vector<std::uint8_t> cut(webp.begin(), webp.begin() + 30);
    writeBytes(dir.file("cut.webp"), cut);
    GltfFile truncated = webpQuad("cut.webp");
    message = errorOf(truncated.write(dir, "cut"));
    EXPECT_NE(message.find("cut.gltf: images[0]"), std::string::npos) << message;

    GltfFile missing = webpQuad("cut.webp");
    missing.doc["textures"][0]["extensions"]["EXT_texture_webp"]["source"] = 3;
    message = errorOf(missing.write(dir, "missing"));
    EXPECT_NE(message.find("textures[0].extensions.EXT_texture_webp.source: image 3 does not exist"), std::string::npos)
        << message;
}

// One quad, the buffer given as a data uri.
std::string dataUriQuad(const TempDir& dir, const std::string& name, const std::string& uriPrefix, bool base64) {
    GltfFile file;
    file.addQuadMesh();
    file.addNode({{"mesh", 0}}, true);
    const std::string path = file.write(dir, name);
    std::ifstream in(dir.file(name + ".bin"), std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::string data;
    if (base64) {
        static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        for (std::size_t i = 0; i < bytes.size(); i += 3) {  // sizes are multiples of 4; pad anyway
            const std::uint32_t group = (std::uint32_t(bytes[i]) << 16) |
                                        (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                                        (i + 2 < bytes.size() ? bytes[i + 2] : 0);
            data += kAlphabet[(group >> 18) & 63];
            data += kAlphabet[(group >> 12) & 63];
            data += i + 1 < bytes.size() ? kAlphabet[(group >> 6) & 63] : '=';
            data += i + 2 < bytes.size() ? kAlphabet[group & 63] : '=';
        }
    } else {
        static const char kHex[] = "0123456789ABCDEF";
        for (std::uint8_t byte : bytes) {
            data += '%';
            data += kHex[byte >> 4];
            data += kHex[byte & 15];
        }
    }
    json doc = json::parse(std::ifstream(path));
    doc["buffers"][0]["uri"] = uriPrefix + data;
    std::filesystem::remove(dir.file(name + ".bin"));
    std::ofstream(path) << doc.dump();
    return path;
}

TEST(GltfCompressed, BufferDataUrisOfGltfBufferAndOctetStream) {
    TempDir dir;
    for (const auto& [name, prefix, base64] :
         std::vector<std::tuple<std::string, std::string, bool>>{
             {"buffer64", "data:application/gltf-buffer;base64,", true},
             {"octets64", "data:application/octet-stream;base64,", true},
             {"bufferPercent", "data:application/gltf-buffer,", false},
             {"octetsPercent", "data:application/octet-stream,", false}}) {
        const Scene scene = loadGltf(dataUriQuad(dir, name, prefix, base64), plain());
        ASSERT_EQ(scene.objects.size(), 1u) << name;
        EXPECT_EQ(scene.objects[0].levels[0].stats.triangles, 2u) << name;
        EXPECT_FLOAT_EQ(scene.objects[0].levels[0].stats.bounds.max.x, 1.0f) << name;
    }
    // Another media type is not a buffer.
    const std::string message = errorOf(dataUriQuad(dir, "text", "data:text/html,", false));
    EXPECT_NE(message.find("text.gltf"), std::string::npos) << message;
}

TEST(GltfCompressed, RequiredExtensionsThatCannotBeDecodedAreRefusedByName) {
    TempDir dir;
    GltfFile file = webpQuad("a.png");
    file.doc["extensionsUsed"] = {"KHR_texture_basisu"};
    file.doc["extensionsRequired"] = {"KHR_texture_basisu"};
    file.doc["textures"] = {{{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}};
    const std::string message = errorOf(file.write(dir, "basisu"));
    EXPECT_NE(message.find("basisu.gltf: extensionsRequired: KHR_texture_basisu is not supported"), std::string::npos)
        << message;
}

TEST(GltfCompressed, OptionalVisualExtensionsWarnOnceByName) {
    TempDir dir;
    GltfFile file;
    file.addQuadMesh(0);
    file.addNode({{"mesh", 0}}, true);
    file.doc["materials"] = {{{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}}}},
                             {{"extensions", {{"KHR_materials_clearcoat", {{"clearcoatFactor", 0.5}}}}}}};
    // Implemented (or drawn by the renderer) and non-visual extensions do not warn.
    file.doc["extensionsUsed"] = {"KHR_materials_clearcoat", "KHR_texture_transform", "KHR_materials_emissive_strength",
                                  "KHR_xmp_json_ld", "KHR_materials_clearcoat", "KHR_lights_punctual",
                                  "KHR_texture_basisu"};
    std::vector<std::string> warnings;
    const Scene scene = loadGltf(file.write(dir, "coat"), plain(&warnings));
    EXPECT_EQ(scene.objects.size(), 1u);
    ASSERT_EQ(warnings.size(), 3u) << ::testing::PrintToString(warnings);
    EXPECT_NE(warnings[0].find("coat.gltf: extensionsUsed: KHR_materials_clearcoat is not implemented"),
              std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[1].find("KHR_lights_punctual"), std::string::npos) << warnings[1];
    EXPECT_NE(warnings[2].find("KHR_texture_basisu"), std::string::npos) << warnings[2];  // a fallback source is drawn
}

// Two triangles as a Draco mesh with positions, normals (+Z) and 8-bit normalized colors,
// without quantization (so the values come back exactly). The glTF primitive maps the
// attributes by their Draco unique ids, in another order than they were added:
//   3 ---- 2     triangle 0: 0 1 2, red
//   |  /   |     triangle 1: 0 2 3, green
//   0 ---- 1
TEST(GltfCompressed, DracoAttributesFollowTheExtensionsIds) {
    const float corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const float up[3] = {0, 0, 1};
    const std::uint8_t colors[2][4] = {{255, 0, 0, 255}, {0, 255, 0, 255}};
    const int faces[2][3] = {{0, 1, 2}, {0, 2, 3}};
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int color = builder.AddAttribute(draco::GeometryAttribute::COLOR, 4, draco::DT_UINT8, true);
    const int position = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    const int normal = builder.AddAttribute(draco::GeometryAttribute::NORMAL, 3, draco::DT_FLOAT32);
    for (int f = 0; f < 2; ++f) {
        const draco::FaceIndex face(f);
        builder.SetAttributeValuesForFace(position, face, corners[faces[f][0]], corners[faces[f][1]], corners[faces[f][2]]);
        builder.SetAttributeValuesForFace(normal, face, up, up, up);
        builder.SetAttributeValuesForFace(color, face, colors[f], colors[f], colors[f]);
    }
    const std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    ASSERT_TRUE(mesh);
    draco::Encoder encoder;
    draco::EncoderBuffer encoded;
    ASSERT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &encoded).ok());

    TempDir dir;
    GltfFile file;
    const int view = file.addView(encoded.data(), encoded.size());
    file.doc["accessors"] = {{{"componentType", kFloat}, {"count", 1}, {"type", "VEC3"}},
                             {{"componentType", kFloat}, {"count", 1}, {"type", "VEC3"}},
                             {{"componentType", kUnsignedByte}, {"normalized", true}, {"count", 1}, {"type", "VEC4"}},
                             {{"componentType", kUnsignedShort}, {"count", 6}, {"type", "SCALAR"}}};
    const json ids = {{"POSITION", mesh->attribute(position)->unique_id()},
                      {"NORMAL", mesh->attribute(normal)->unique_id()},
                      {"COLOR_0", mesh->attribute(color)->unique_id()}};
    file.addMesh({{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"COLOR_0", 2}}},
                  {"indices", 3},
                  {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", ids}}}}}});
    file.addNode({{"mesh", 0}}, true);
    file.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    file.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const Scene scene = loadGltf(file.write(dir, "draco"), plain());
    ASSERT_EQ(scene.objects.size(), 1u);
    const Mesh& decoded = scene.objects[0].levels[0].meshes.at(0);
    ASSERT_EQ(decoded.indices.size(), 6u);
    // Draco may reorder points and faces: compare each decoded triangle's corners with one of
    // the two drawn above (the same corners in the same winding, from any start).
    std::vector<std::vector<glm::vec3>> expected;
    for (const auto& face : faces) expected.push_back({glm::make_vec3(corners[face[0]]), glm::make_vec3(corners[face[1]]),
                                                       glm::make_vec3(corners[face[2]])});
    int matched = 0;
    for (int t = 0; t < 2; ++t) {
        std::vector<glm::vec3> triangle;
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t index = decoded.indices[3 * t + c];
            triangle.push_back(decoded.positions.at(index));
            EXPECT_EQ(decoded.normals.at(index), glm::vec3(0, 0, 1));
        }
        for (const auto& candidate : expected) {
            for (int start = 0; start < 3; ++start) {
                matched += triangle[0] == candidate[start] && triangle[1] == candidate[(start + 1) % 3] &&
                           triangle[2] == candidate[(start + 2) % 3];
            }
        }
    }
    EXPECT_EQ(matched, 2);
}

TEST(GltfCompressed, HostileDracoPrimitivesAreRefusedByElement) {
    TempDir dir;
    auto dracoFile = [&](const std::string& name, int view, const std::vector<std::uint8_t>& blob) {
        GltfFile file;
        file.addView(blob.data(), blob.size());
        file.doc["accessors"] = {{{"componentType", kFloat}, {"count", 3}, {"type", "VEC3"}},
                                 {{"componentType", kUnsignedShort}, {"count", 3}, {"type", "SCALAR"}}};
        file.addMesh({{"attributes", {{"POSITION", 0}}},
                      {"indices", 1},
                      {"extensions", {{"KHR_draco_mesh_compression", {{"bufferView", view}, {"attributes", {{"POSITION", 0}}}}}}}});
        file.addNode({{"mesh", 0}}, true);
        file.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
        file.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        return file.write(dir, name);
    };
    const std::string where = "meshes[0].primitives[0].extensions.KHR_draco_mesh_compression";
    std::string message = errorOf(dracoFile("noview", 7, {1, 2, 3, 4}));
    EXPECT_NE(message.find("noview.gltf: " + where + ".bufferView: bufferView 7 does not exist"), std::string::npos)
        << message;
    message = errorOf(dracoFile("garbage", 0, {'D', 'R', 'A', 'C', 'O', 2, 2, 1, 1, 0, 0, 0}));
    EXPECT_NE(message.find("garbage.gltf: " + where + ": Draco data cannot be decoded"), std::string::npos) << message;

    // A view that runs past its buffer (tinygltf does not check; validation runs after the
    // pre-pass, so the pre-pass checks it itself).
    const std::string path = dracoFile("past", 0, {1, 2, 3, 4});
    json doc = json::parse(std::ifstream(path));
    doc["bufferViews"][0]["byteLength"] = 4000;
    std::ofstream(path) << doc.dump();
    message = errorOf(path);
    EXPECT_NE(message.find("past.gltf: " + where + ".bufferView: bufferView 0 (bytes 0..4000) runs past the end"),
              std::string::npos)
        << message;
}

}  // namespace
}  // namespace lodopt::scenes
