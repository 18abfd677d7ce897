// glTF 2.0 loading and export with discrete levels of detail.
//
// Levels come from, in order of preference:
//  1. the MSFT_lod node extension: {"extensions": {"MSFT_lod": {"ids": [n1, n2, ...]}}} on a
//     node makes that node level 0 and nodes n1, n2, ... levels 1, 2, ...; the node's
//     extras.MSFT_screencoverage array gives one screen-coverage threshold per level;
//  2. MSFT_lod on materials (same geometry, coarser textures): an object that uses such a
//     material gets one level per material level;
//  3. sibling nodes named <name>_LOD<k> (k = 0, 1, ...);
//  4. otherwise one level, and loadScene(..., generateLods = true) adds a meshoptimizer chain.
// Each top-level object is one node subtree of the default scene (a node that is a root of
// the scene, or a node carrying MSFT_lod); its meshes are flattened into object space.
//
// Every reference, range and cycle is checked after tinygltf parses the file: bad data
// throws SceneError naming the file and the element (e.g. "meshes[3].primitives[0].indices").
#pragma once

#include <string>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

struct GltfLoadOptions {
    // Add a meshoptimizer LOD chain (lod_generation.hpp defaults) to objects with one level.
    bool generateLods = true;
    // Refuse files whose declared buffers or images exceed this many bytes.
    std::uint64_t maxBytes = std::uint64_t(1) << 31;
};

Scene loadGltf(const std::string& path, const GltfLoadOptions& options = {});

// Writes .gltf (JSON + embedded base64 buffer) or .glb (by extension) with MSFT_lod on each
// object's level-0 node and MSFT_screencoverage in its extras when every level has one.
// Written to a temporary file and renamed, so a failure leaves no partial output.
void exportGltf(const Scene& scene, const std::string& path);

}  // namespace lodopt::scenes
