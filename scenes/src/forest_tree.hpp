// Procedural trees with five discrete levels of detail for the built-in forest scene.
//
// A tree is grown once as a skeleton (tapered branch segments of order 0 = trunk, 1, 2, 3,
// and leaf cards) and then meshed per level:
//   level 0: every branch, every leaf card (a diamond quad standing for a cluster of leaves;
//            the renderer has no alpha test, so a card is opaque and shaped by its geometry,
//            not by a texture's alpha; it lights back faces, so one face per card);
//   level 1: branches of order <= 2, leaves pruned with lambda = 1/2;
//   level 2: branches of order <= 1, leaves pruned with lambda = 1/4;
//   level 3: crown hull (an ellipsoid, or two stacked cones for a conifer) on the trunk;
//   level 4: two crossed silhouette cards (a billboard without alpha).
//
// Leaf pruning follows Dong et al. 2015 (DONG15), eqs. (1)-(3): every leaf l gets the visual
// importance  eps(l) = 0.3 dis + 0.4 cos + 0.3 area  with, in this implementation,
//   dis  = |c_l - C| / max_k |c_k - C|: distance of the leaf centre c_l (midpoint of base and
//          tip) from the crown centre C (the centre of the bounding box of all leaf centres),
//          normalised by the largest in the tree; outer leaves make the silhouette;
//   cos  = |n_l . r_l|: n_l the card normal, r_l the horizontal unit vector from the trunk
//          axis towards the leaf centre, i.e. the reverse of the direction from which a
//          viewer standing on that side of the tree sees the leaf; a LOD is built without a
//          camera, and this reference makes the rule independent of the tree's rotation
//          (r_l = +x for a leaf on the axis); absolute value because a card is seen from
//          both sides;
//   area = A_l / max_k A_k, the card's area normalised by the largest in the tree.
// The first ceil(lambda N) leaves in descending eps (ties: lower index first) are kept and
// each is enlarged about its base so that its area grows by 1/sqrt(lambda) (edges by
// lambda^-1/4), as DONG15 writes it. DONG15 chooses lambda = 1/ln d per distance d; a
// discrete LOD fixes lambda per level instead (1/2 ~ d = 7.4 m, 1/4 ~ d = 55 m).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "procedural.hpp"
#include "scenes/scene.hpp"

namespace lodopt::scenes::forest {

enum class Species { Oak, Pine, Birch };
inline constexpr int kSpeciesCount = 3;
const char* speciesName(Species species);

// Importance weights of DONG15 eq. (1).
inline constexpr float kWeightDistance = 0.3f;
inline constexpr float kWeightCosine = 0.4f;
inline constexpr float kWeightArea = 0.3f;
// Leaf-pruning ratio lambda of levels 0, 1, 2 (levels 3 and 4 have no leaf cards).
inline constexpr float kLevelLambda[3] = {1.0f, 0.5f, 0.25f};
inline constexpr int kTreeLevels = 5;

// A diamond leaf card: base (petiole) at `base`, tip at base + axis * length, widest
// (width) at 40% of the length, in the plane spanned by `axis` and `side` (orthonormal).
struct Leaf {
    glm::vec3 base{0.0f};
    glm::vec3 axis{0.0f, 1.0f, 0.0f};
    glm::vec3 side{1.0f, 0.0f, 0.0f};
    float length = 0.0f;  // metres, > 0
    float width = 0.0f;   // metres, > 0
};
inline float leafArea(const Leaf& leaf) {
    return 0.5f * leaf.length * leaf.width;
}
inline glm::vec3 leafCenter(const Leaf& leaf) {
    return leaf.base + leaf.axis * (0.5f * leaf.length);
}
inline glm::vec3 leafNormal(const Leaf& leaf) {
    return glm::normalize(glm::cross(leaf.side, leaf.axis));
}

// DONG15 eq. (1) for every leaf of one tree (object space, trunk axis = the y axis).
// Returns one importance in [0, 1] per leaf, in order; empty input gives empty output.
std::vector<float> leafImportance(const std::vector<Leaf>& leaves);

// DONG15 eqs. (2)-(3): keeps ceil(lambda N) leaves of highest importance, enlarged by an
// area factor 1/sqrt(lambda) about their base; the result keeps the input order.
// `lambda` in (0, 1]; lambda = 1 returns the input unchanged.
std::vector<Leaf> pruneLeaves(const std::vector<Leaf>& leaves, float lambda);

// One tapered branch segment from `start` to `end`; order 0 is the trunk.
struct Branch {
    glm::vec3 start{0.0f};
    glm::vec3 end{0.0f};
    float radiusStart = 0.0f;  // metres
    float radiusEnd = 0.0f;    // metres
    int order = 0;
};

struct TreeSkeleton {
    Species species = Species::Oak;
    float height = 0.0f;  // metres above the ground (object origin)
    std::vector<Branch> branches;
    std::vector<Leaf> leaves;
};

// Grows one tree of `species` (object space: base at the origin, trunk along +y).
TreeSkeleton growTree(Species species, procedural::Rng& rng);

// Materials a tree's levels draw with (indices into Scene::materials).
struct TreeMaterials {
    int bark = -1;       // levels 0-2: trunk and branches, bark texture
    int leaves = -1;     // levels 0-2: leaf cards, leaf texture
    int hullTrunk = -1;  // level 3: trunk, small bark texture
    int crown = -1;      // levels 3-4: crown hull and billboard, small foliage texture
    int flatTrunk = -1;  // level 4: trunk card, untextured bark colour
};

// Meshes the kTreeLevels levels of a skeleton (statistics are not filled in).
std::vector<Level> buildTreeLevels(const TreeSkeleton& tree, const TreeMaterials& materials);

// Species look: bark and leaf colours (display RGB 0..1) for textures and materials.
glm::vec3 barkColor(Species species);
glm::vec3 leafColor(Species species);

}  // namespace lodopt::scenes::forest
