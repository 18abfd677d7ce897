// Private helpers shared by the glTF loader files (gltf_load.cpp, gltf_validate.cpp,
// gltf_accessors.cpp). tinygltf stays inside src/: no public header includes it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scenes/scene.hpp"

namespace lodopt::scenes::gltf_detail {

// Throws SceneError "<file>: <element>: <what>" (the element may be empty).
[[noreturn]] void fail(const std::string& file, const std::string& element, const std::string& what);

// "meshes[3].primitives[0]" style element names.
std::string element(const std::string& array, int index);

// The node graph after validation: parent of each node (-1 for roots) and the MSFT_lod
// chains (level-0 node → coarser level nodes, material → coarser materials).
struct ModelGraph {
    std::vector<int> parent;
    std::vector<std::vector<int>> nodeLods;      // per node, empty when it has no MSFT_lod
    std::vector<int> lodLevelOf;                 // per node: the level-0 node it is a level of, or -1
    std::vector<std::vector<int>> materialLods;  // per material, empty when it has no MSFT_lod
};

// Required extensions the loader implements or can safely approximate; any other one
// changes the meaning of the data (e.g. Draco-compressed accessors would read as zeros).
bool isUnderstoodExtension(const std::string& name);

// Runs every reference, range and cycle check of docs/gltf.md on a model tinygltf parsed, so
// that the conversion can index without checking. `decodedBytesAllowance`: most bytes an
// accessor without a bufferView (all zeros, maybe sparse) may decode to.
ModelGraph validateModel(const tinygltf::Model& model, const std::string& file,
                         std::uint64_t decodedBytesAllowance);

// Bytes of one element of an accessor (type × component size); 0 for an unknown type.
std::uint64_t accessorElementSize(const tinygltf::Accessor& accessor);
int accessorComponentCount(const tinygltf::Accessor& accessor);

// Reads accessor `index` as floats, `components` per element (1-4), converting any component
// type (normalized integers to [0,1] or [-1,1] as the spec says), applying sparse
// substitution. Throws SceneError naming `what` for a wrong type or a non-finite value.
std::vector<float> readFloats(const tinygltf::Model& model, int index, int components, const std::string& file,
                              const std::string& what);

// Reads an index accessor (SCALAR unsigned byte/short/int) into 32-bit indices.
std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int index, const std::string& file,
                                       const std::string& what);

// One primitive decoded in its mesh's space, as triangles (strips and fans converted).
struct DecodedPrimitive {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // empty when the file has none
    std::vector<glm::vec2> uvs;      // empty when the file has none
    std::vector<glm::vec2> uvs1;     // TEXCOORD_1, empty when the file has none
    std::vector<glm::vec4> tangents;  // TANGENT, empty when the file has none
    std::vector<glm::vec4> colors;    // COLOR_0 (alpha 1 for VEC3), empty when the file has none
    std::vector<std::uint32_t> indices;
    int material = -1;
    bool skipped = false;  // no POSITION, or a point/line primitive skipped by option
};

// Decodes meshes[mesh].primitives[primitive]. `skipNonTriangles`: point and line primitives
// become skipped (with a warning) instead of an error.
DecodedPrimitive decodePrimitive(const tinygltf::Model& model, int mesh, int primitive, const std::string& file,
                                 bool skipNonTriangles, std::vector<std::string>* warnings);

// A node's local transform (matrix, or T * R * S).
glm::mat4 localTransform(const tinygltf::Node& node);

}  // namespace lodopt::scenes::gltf_detail
