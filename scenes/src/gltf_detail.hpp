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

// Extensions the loader decodes, implements or can safely approximate (accepted when
// required, no warning when used); any other required one changes the meaning of the data
// (e.g. KHR_texture_basisu images lodopt cannot decode).
bool isUnderstoodExtension(const std::string& name);

// --- Extensions (gltf_extensions.cpp, gltf_meshopt.cpp, gltf_draco.cpp) --------------------
// Each runs on the parsed model before validateModel(), so that everything after sees plain
// glTF 2.0: decoded bufferViews and accessors in new buffers, textures pointing at the image
// the loader decodes. They check every index and range they read themselves.

// Rewrites the JSON (of a .gltf, or the JSON chunk of a .glb, returned as a whole file) where
// tinygltf 2.7 would misread it: an EXT_meshopt_compression fallback buffer without uri
// becomes a 4-byte data uri (tinygltf would otherwise fail on the missing uri, or copy
// unrelated bytes of the BIN chunk); a KHR_draco_mesh_compression primitive loses its
// `indices` (an accessor without bufferView, which tinygltf refuses; the Draco pre-pass writes
// new ones); a buffer's percent-encoded data uri (application/gltf-buffer or octet-stream
// without ;base64) and an image's data:image/webp uri become base64 octet-stream, which
// tinygltf decodes; a relative uri with '+' keeps its '+' (tinygltf's percent-decoding turns it
// into a space). Returns the input unchanged when none occurs. `fallbackBuffers` receives the
// indices of the fallback buffers.
std::vector<unsigned char> rewriteForTinygltf(std::vector<unsigned char> bytes, bool binary,
                                              std::vector<int>& fallbackBuffers);

// Valid glTF that tinygltf 2.7 refuses, rewritten so that it reads it: integral numbers written
// as floats become integers; a buffer without uri (other than a .glb's own; the validator
// accepts it, its data is the application's) reads as zeros of its byteLength, with a note in
// `notes` when something drawn reads it (a node's mesh primitives or skin, an animation, an
// image); an accessor of a type glTF does not define that nothing drawn reads becomes a scalar;
// an accessor without bufferView or sparse holds zeros by the spec (one zero-filled buffer).
// Zeros up to 16 MiB in all. The rewritten file, or empty when nothing changed. Called only
// after tinygltf has refused the file, so files it reads pay nothing.
std::vector<unsigned char> standInsForUnreadableObjects(const std::vector<unsigned char>& bytes, bool binary,
                                                    std::vector<std::string>& notes);

// The refusal of docs/gltf.md: a required extension lodopt neither decodes nor can draw
// faithfully without, named ("extensionsRequired: KHR_texture_basisu is not supported").
void checkRequiredExtensions(const tinygltf::Model& model, const std::string& file);

// One warning per used-but-not-required extension that changes how the model looks and that
// lodopt does not implement (docs/gltf.md lists them), "<file>: extensionsUsed: <name> ...".
void warnUnimplementedExtensions(const tinygltf::Model& model, const std::string& file,
                                 std::vector<std::string>* warnings);

// The image a texture shows: EXT_texture_webp's source when present, else `source`; -1 for
// none. Throws SceneError for an extension source that is not an image index.
int textureImageSource(const tinygltf::Model& model, int texture, const std::string& file);

// Points each texture's `source` at textureImageSource(), so that code reading `source`
// decodes the WebP image.
void resolveTextureSources(tinygltf::Model& model, const std::string& file);

// EXT_meshopt_compression: decodes every compressed bufferView (ATTRIBUTES with the NONE,
// OCTAHEDRAL, QUATERNION or EXPONENTIAL filter, TRIANGLES, INDICES) into one new buffer and
// points the view at it. `fallbackBuffers`: buffers without data (rewriteForTinygltf). Every
// decoded byte is taken from `byteBudget`, which may not go below 0.
void decodeMeshoptViews(tinygltf::Model& model, const std::string& file, const std::vector<int>& fallbackBuffers,
                        std::uint64_t& byteBudget);

// KHR_draco_mesh_compression: decodes each compressed triangle primitive into new accessors
// (the extension's attributes, in the types their accessors declare, and 32-bit indices) in
// one new buffer, and points the primitive at them. Decoded bytes come from `byteBudget`.
void decodeDracoPrimitives(tinygltf::Model& model, const std::string& file, std::uint64_t& byteBudget);

// Reads an optional non-negative integer property of an extension object: `fallback` when
// absent, SceneError naming `where`.<key> when not an integer in 0..`max`.
std::uint64_t extensionInteger(const tinygltf::Value& object, const char* key, std::uint64_t fallback,
                               std::uint64_t max, const std::string& file, const std::string& where);
// Same, required.
std::uint64_t requiredExtensionInteger(const tinygltf::Value& object, const char* key, std::uint64_t max,
                                       const std::string& file, const std::string& where);

// Runs every reference, range and cycle check of docs/gltf.md on a model tinygltf parsed, so
// that the conversion can index without checking. `decodedBytesAllowance`: most bytes an
// accessor without a bufferView (all zeros, maybe sparse) may decode to.
ModelGraph validateModel(const tinygltf::Model& model, const std::string& file,
                         std::uint64_t decodedBytesAllowance);

// Bytes of one component of a glTF component type (5120..5126); 0 for any other.
std::uint64_t componentSize(int componentType);
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
