// LOD chains generated with meshoptimizer for models that have none.
//
// Level k keeps about ratio[k] of level 0's triangles, each mesh simplified on its own from
// level 0 (exact duplicate vertices welded first, unused vertices dropped after): first
// meshopt_simplify with borders locked; when that stalls above twice the target, again with
// borders free; then meshopt_simplifySloppy (vertex clustering). The error bound is left
// open: the ratio is the contract. Level::simplificationError is the largest error of the
// level's meshes (meshoptimizer's relative error × that mesh's extent) divided by level 0's
// extent; a mesh that simplifies to nothing counts its whole extent. Levels with no
// triangles, or that fail to lose at least 10% of the previous level's triangles, are
// dropped, so a chain never holds two near-identical levels. Triangle soups without shared
// vertices usually reach only the clustering step.
#pragma once

#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

inline const std::vector<float> kDefaultLodRatios = {1.0f, 0.5f, 0.25f, 0.125f, 0.0625f};

// Replaces object.levels with a chain built from object.levels[0] (kept as it is).
//   object: at least one level; levels past 0 are discarded. Stats are not updated: call
//           updateStatistics() on the scene afterwards.
//   ratios: fractions of level 0's triangles, ratios[0] == 1, non-increasing, each in (0, 1].
void generateLodChain(Object& object, const std::vector<float>& ratios = kDefaultLodRatios);

// Simplifies one mesh to about `ratio` of its triangles and returns meshoptimizer's error
// relative to the mesh's extent (0 for ratio 1; >= 1 when nothing is left).
//   source: a valid mesh (normals sized like positions, uvs empty or sized like positions).
//   ratio:  in (0, 1]; the target is round(triangles × ratio) triangles.
//   out:    replaced; same material, compacted vertices, empty when the target rounds to 0.
float simplifyMesh(const Mesh& source, float ratio, Mesh& out);

}  // namespace lodopt::scenes
