// libFuzzer target: the glTF 2.0 / GLB loader (scenes::loadGltf, LOD generation included).
// Run by scripts/fuzz.sh with the seed corpus in tests/fuzz/corpus/gltf/.
#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lodopt::fuzz::loadGltfBytes(data, size);
    return 0;
}
