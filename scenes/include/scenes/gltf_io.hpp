// glTF 2.0 loading and export with discrete levels of detail.
//
// Objects (docs/gltf.md has the details and the error catalogue):
//  - an object is the topmost node, walking down from the default scene's roots, that has a
//    mesh or an MSFT_lod extension, or the finest of a group of sibling nodes named
//    <name>_LOD<k>; nodes without a mesh above it are only transforms (their cameras still
//    count). Its descendants join its level 0, flattened into its space, except descendants
//    that carry their own LODs, which become objects of their own. Object::transform is the
//    object node's world transform.
//  - levels come from, in order of preference:
//     1. the MSFT_lod node extension: {"extensions": {"MSFT_lod": {"ids": [n1, n2, ...]}}} on
//        a node makes that node level 0 and nodes n1, n2, ... (subtrees, placed like the
//        level-0 node under its parent) levels 1, 2, ...; the node's
//        extras.MSFT_screencoverage array gives one screen-coverage threshold per level;
//     2. MSFT_lod on materials (same geometry, coarser textures): an object with one
//        geometric level whose meshes use such materials gets one level per material level;
//     3. sibling nodes named <name>_LOD<k> (k = 0, 1, ..., any case), object named <name>;
//     4. otherwise one level, and GltfLoadOptions::generateLods adds a meshoptimizer chain.
//  - perspective cameras of the scene become Scene::views (none added when the file has
//    none: loadScene() in builtin.hpp adds default views); scenes[s].extras
//    .lodopt_camera_paths becomes Scene::paths. Skins, animations, morph targets, lights
//    and material properties other than the base color are ignored.
//
// Extensions: EXT_meshopt_compression, KHR_draco_mesh_compression and EXT_texture_webp are
// decoded; any other required extension the loader cannot honour (KHR_texture_basisu, ...) is
// refused by name; an optional one that changes the look and is not implemented gets one
// warning (docs/gltf.md, "Extensions").
//
// Every reference, range and cycle is checked after tinygltf parses the file: bad data
// throws SceneError naming the file and the element (e.g. "meshes[3].primitives[0].indices").

#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

struct GltfLoadOptions {
    // Add a meshoptimizer LOD chain (lod_generation.hpp defaults) to objects with one level.
    bool generateLods = true;
    // Refuse files whose buffers and images, with the bytes their compressed views and
    // primitives decode to, exceed this many bytes.
    std::uint64_t maxBytes = std::uint64_t(1) << 31;
    // POINTS / LINES primitives: false → SceneError naming meshes[i].primitives[j].mode;
    // true → the primitive is skipped with a warning.
    bool skipNonTrianglePrimitives = false;
    // When not null, receives one line per thing ignored or approximated (skipped
    // primitives, orthographic cameras, material LODs under node LODs, unimplemented
    // optional extensions, ...).
    std::vector<std::string>* warnings = nullptr;
};

Scene loadGltf(const std::string& path, const GltfLoadOptions& options = {});

// What the values of extras.MSFT_screencoverage measure (the extension leaves it open). Inside
// lodopt Level::screenCoverage is always a screen size (scenes::screenSize: bounding-sphere
// diameter over the view height). A file may say otherwise in asset.extras
// .lodopt_screencoverage: "unity_relative_height" (the bounds' largest extent over the view
// height, what UnityGLTF reads as LOD.screenRelativeTransitionHeight); the loader converts
// such values to screen sizes with each object's level-0 world bounds (engine_lod.hpp).
// Files without the mark are read as screen sizes.
enum class CoverageConvention { ScreenSize, UnityRelativeHeight };

struct GltfExportOptions {
    CoverageConvention coverage = CoverageConvention::ScreenSize;
};

// Writes .gltf (JSON + embedded base64 buffer and PNG images) or .glb (by extension, any
// case) with one scene root node per object: its level 0, carrying MSFT_lod (levels 1.. as
// nodes outside the scene, with the same transform) and MSFT_screencoverage in its extras
// when every level has one (in options.coverage's convention, marked in asset.extras). Views become camera nodes (their targets kept in the node's
// extras.lodopt_target), Scene::paths the scene's extras.lodopt_camera_paths, Scene::name
// the scene's name. loadGltf() of the result gives back the same objects, levels, materials,
// textures, views and paths. Written to a temporary file and renamed, so a failure leaves
// no partial output. Throws SceneError for another extension or an invalid scene.
void exportGltf(const Scene& scene, const std::string& path, const GltfExportOptions& options = {});

}  // namespace lodopt::scenes
