// Small glTF files written by the tests themselves: a JSON document plus one external .bin,
// built element by element so that each test can break exactly one thing.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>
#include "lodopt_test_paths.hpp"

namespace lodopt::scenes::testing {

inline constexpr int kFloat = 5126;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;

// A fresh folder per test, removed afterwards.
class TempDir {
public:
    TempDir() {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        mPath = std::filesystem::temp_directory_path() /
                ("lodopt_gltf_" + std::to_string(::getpid()) + "_" +
                 (info ? std::string(info->test_suite_name()) + "_" + info->name() : std::string("x")));
        std::filesystem::remove_all(mPath);
        std::filesystem::create_directories(mPath);
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(mPath, ignored);
    }
    std::string file(const std::string& name) const { return (mPath / name).string(); }

private:
    std::filesystem::path mPath;
};

class GltfFile {
public:
    GltfFile() {
        doc["asset"] = {{"version", "2.0"}};
        doc["scene"] = 0;
        doc["scenes"] = nlohmann::json::array({{{"nodes", nlohmann::json::array()}}});
    }

    // Appends bytes (4-aligned) as a new bufferView; returns its index.
    int addView(const void* data, std::size_t bytes, int stride = 0) {
        while (mBin.size() % 4 != 0) mBin.push_back(0);
        nlohmann::json view = {{"buffer", 0}, {"byteOffset", mBin.size()}, {"byteLength", bytes}};
        if (stride) view["byteStride"] = stride;
        const auto* begin = static_cast<const std::uint8_t*>(data);
        mBin.insert(mBin.end(), begin, begin + bytes);
        doc["bufferViews"].push_back(view);
        return static_cast<int>(doc["bufferViews"].size()) - 1;
    }
    int addAccessor(int view, int componentType, std::size_t count, const std::string& type, bool normalized = false) {
        nlohmann::json accessor = {{"bufferView", view}, {"componentType", componentType}, {"count", count}, {"type", type}};
        if (normalized) accessor["normalized"] = true;
        doc["accessors"].push_back(accessor);
        return static_cast<int>(doc["accessors"].size()) - 1;
    }
    int addFloats(const std::vector<float>& values, const std::string& type, int components) {
        return addAccessor(addView(values.data(), values.size() * 4), kFloat, values.size() / components, type);
    }
    int addIndices(const std::vector<std::uint32_t>& indices) {
        return addAccessor(addView(indices.data(), indices.size() * 4), kUnsignedInt, indices.size(), "SCALAR");
    }
    int addIndices16(const std::vector<std::uint16_t>& indices) {
        return addAccessor(addView(indices.data(), indices.size() * 2), kUnsignedShort, indices.size(), "SCALAR");
    }
    // A mesh with one primitive; returns the mesh index.
    int addMesh(const nlohmann::json& primitive, const std::string& name = "") {
        nlohmann::json mesh = {{"primitives", nlohmann::json::array({primitive})}};
        if (!name.empty()) mesh["name"] = name;
        doc["meshes"].push_back(mesh);
        return static_cast<int>(doc["meshes"].size()) - 1;
    }
    // A unit quad in the XY plane (2 triangles, 4 vertices), indexed; returns the mesh index.
    int addQuadMesh(int material = -1, float size = 1.0f) {
        const int position = addFloats({0, 0, 0, size, 0, 0, size, size, 0, 0, size, 0}, "VEC3", 3);
        const int indices = addIndices({0, 1, 2, 0, 2, 3});
        nlohmann::json primitive = {{"attributes", {{"POSITION", position}}}, {"indices", indices}};
        if (material >= 0) primitive["material"] = material;
        return addMesh(primitive);
    }
    int addNode(const nlohmann::json& node, bool root) {
        doc["nodes"].push_back(node);
        const int index = static_cast<int>(doc["nodes"].size()) - 1;
        if (root) doc["scenes"][0]["nodes"].push_back(index);
        return index;
    }

    // Writes <name>.gltf and <name>.bin into `dir`; returns the .gltf path.
    std::string write(const TempDir& dir, const std::string& name) {
        if (!mBin.empty()) {
            while (mBin.size() % 4 != 0) mBin.push_back(0);
            doc["buffers"] = nlohmann::json::array({{{"uri", name + ".bin"}, {"byteLength", mBin.size()}}});
            std::ofstream bin(dir.file(name + ".bin"), std::ios::binary);
            bin.write(reinterpret_cast<const char*>(mBin.data()), static_cast<std::streamsize>(mBin.size()));
        }
        const std::string path = dir.file(name + ".gltf");
        std::ofstream(path) << doc.dump(1);
        return path;
    }
    // Writes the same content as a .glb (JSON chunk + BIN chunk).
    std::string writeGlb(const TempDir& dir, const std::string& name) {
        nlohmann::json copy = doc;
        std::vector<std::uint8_t> bin = mBin;
        while (bin.size() % 4 != 0) bin.push_back(0);
        if (!bin.empty()) copy["buffers"] = nlohmann::json::array({{{"byteLength", bin.size()}}});
        std::string json = copy.dump();
        while (json.size() % 4 != 0) json.push_back(' ');
        std::vector<std::uint8_t> out;
        auto u32 = [&](std::uint32_t v) {
            for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
        };
        u32(0x46546C67u);
        u32(2);
        u32(static_cast<std::uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
        u32(static_cast<std::uint32_t>(json.size()));
        u32(0x4E4F534Au);
        out.insert(out.end(), json.begin(), json.end());
        if (!bin.empty()) {
            u32(static_cast<std::uint32_t>(bin.size()));
            u32(0x004E4942u);
            out.insert(out.end(), bin.begin(), bin.end());
        }
        const std::string path = dir.file(name + ".glb");
        std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(out.data()),
                                                    static_cast<std::streamsize>(out.size()));
        return path;
    }

    nlohmann::json doc;

private:
    std::vector<std::uint8_t> mBin;
};

inline std::string sharedDataDir() { return LODOPT_SHARED_DATA_DIR; }

}  // namespace lodopt::scenes::testing
