// What the fuzz targets do with one input, shared by the libFuzzer programs (tests/fuzz/
// fuzz_*.cpp, clang only) and by the GoogleTest suites that replay the checked-in corpora and
// crash regressions in every build (tests/scenes/hostile_gltf_test.cpp, tests/cli/
// robustness_test.cpp). Each function returns normally when the input was handled as the docs
// say (loaded, or refused with the documented exception); anything else — another exception,
// a crash, a sanitizer report — is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scenes/gltf_io.hpp"

namespace lodopt::fuzz {

// A private scratch folder (RAM-backed when /dev/shm exists: rewriting a file on ext4 flushes
// it to disk each time), removed at exit. The loaders take paths, not bytes.
inline const std::filesystem::path& scratchDir() {
    struct Scratch {
        std::filesystem::path path;
        Scratch() {
            const std::filesystem::path base = std::filesystem::exists("/dev/shm")
                                                   ? std::filesystem::path("/dev/shm")
                                                   : std::filesystem::temp_directory_path();
            path = base / ("lodopt-fuzz-" + std::to_string(::getpid()));
            std::filesystem::create_directories(path);
        }
        ~Scratch() {
            std::error_code ignored;
            std::filesystem::remove_all(path, ignored);
        }
    };
    static const Scratch scratch;
    return scratch.path;
}

inline std::string writeScratch(const std::string& name, const std::uint8_t* data, std::size_t size) {
    const std::string path = (scratchDir() / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    return path;
}

// The glTF/GLB loader: `data` is the whole file (GLB when it starts with "glTF"). The limit
// on declared buffers and images is lowered to 64 MiB so that a finding is a real bug, not a
// legitimately large allocation; LOD generation runs too (meshoptimizer on hostile meshes).
inline void loadGltfBytes(const std::uint8_t* data, std::size_t size, bool generateLods = true) {
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = writeScratch(binary ? "input.glb" : "input.gltf", data, size);
    scenes::GltfLoadOptions options;
    options.maxBytes = std::uint64_t(64) << 20;
    options.generateLods = generateLods;
    options.skipNonTrianglePrimitives = size > 0 && (data[size - 1] & 1);
    std::vector<std::string> warnings;
    options.warnings = &warnings;
    try {
        scenes::Scene scene = scenes::loadGltf(path, options);
        scenes::validateScene(scene);  // what the loader returns must satisfy the model's invariants
    } catch (const scenes::SceneError&) {
        // the documented refusal
    }
}

}  // namespace lodopt::fuzz
