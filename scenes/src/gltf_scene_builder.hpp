// Turns a validated tinygltf model into a Scene: object discovery, levels (MSFT_lod on nodes
// and materials, <name>_LOD<k> siblings, generated chains), materials, textures, views and
// camera paths. Private to the scenes module; the rules are in gltf_io.hpp and docs/gltf.md.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gltf_detail.hpp"
#include "scenes/gltf_io.hpp"

namespace lodopt::scenes::gltf_detail {

class SceneBuilder {
public:
    SceneBuilder(const tinygltf::Model& model, const ModelGraph& graph, const std::string& file,
                 const GltfLoadOptions& options, std::vector<std::vector<unsigned char>> encodedImages);
    Scene build();

private:
    // A run of sibling nodes named <base>_LOD<k>, finest first.
    struct NameGroup {
        std::string base;
        std::vector<int> members;
    };
    // What a node is among its siblings.
    enum class Role { kLodLevel, kGroupMember, kGroupFinest, kLodRoot, kMeshNode, kPlain };
    struct Classified {
        std::vector<Role> roles;
        std::vector<int> group;  // index into `groups` for kGroupFinest / kGroupMember
        std::vector<NameGroup> groups;
    };
    // An object found inside another object's subtree, emitted after it.
    struct Pending {
        int node = -1;                      // a node with MSFT_lod, or -1 for a name group
        std::optional<NameGroup> group;
        glm::mat4 parentWorld{1.0f};
    };

    Classified classify(const std::vector<int>& siblings) const;
    void visitGroupLevel(const std::vector<int>& siblings, const glm::mat4& parentWorld);
    void emitNodeObject(int node, const glm::mat4& parentWorld);
    void emitNameGroupObject(const NameGroup& group, const glm::mat4& parentWorld);
    void emitPending(std::vector<Pending>& pending);
    // Appends node's subtree to `level`; `relative` maps the node into object space.
    // `split`: children with their own LODs go to `pending` instead of into the level.
    void flatten(int node, const glm::mat4& relative, const glm::mat4& world, Level& level, bool split,
                 std::vector<Pending>* pending);
    void appendMesh(int mesh, const glm::mat4& relative, Level& level);
    void applyMaterialLods(Object& object, int rootNode);
    void finishObject(Object object);
    void generateMissingTangents();
    void convertScreenCoverage();

    void buildMaterials();
    Material buildMaterial(int index);
    TextureRef textureRef(int gltfTexture, int texCoord, const tinygltf::ExtensionMap& extensions,
                          const std::string& where);
    int sceneTexture(int gltfTexture, const std::string& where);
    Texture decodeImage(int image);
    void buildViews();
    void buildPaths(int sceneIndex);
    void warn(const std::string& message) const;

    std::string nodeName(int node) const;

    const tinygltf::Model& mModel;
    const ModelGraph& mGraph;
    const std::string& mFile;
    const GltfLoadOptions& mOptions;
    std::vector<std::vector<unsigned char>> mEncodedImages;
    std::vector<int> mImageToTexture;
    std::vector<int> mMeshUses;  // how many nodes draw each mesh: only shared meshes are cached
    std::map<std::pair<int, int>, std::shared_ptr<const DecodedPrimitive>> mPrimitiveCache;
    std::vector<std::pair<int, glm::mat4>> mCameraNodes;  // node, world transform
    Scene mScene;
};

}  // namespace lodopt::scenes::gltf_detail
