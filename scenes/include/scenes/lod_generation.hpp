// LOD chains generated with meshoptimizer for models that have none.
//
// Level k keeps about ratio[k] of level 0's triangles (meshopt_simplify, borders locked,
// falling back to meshopt_simplifySloppy when the topology-preserving simplifier stalls
// above twice the target). The relative error meshoptimizer reports is kept in
// Level::simplificationError. Levels that fail to lose at least 10% of the previous
// level's triangles are dropped, so a chain never holds two near-identical levels.
#pragma once

#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

inline const std::vector<float> kDefaultLodRatios = {1.0f, 0.5f, 0.25f, 0.125f, 0.0625f};

// Replaces object.levels with a chain built from object.levels[0]. `ratios` starts at 1.
void generateLodChain(Object& object, const std::vector<float>& ratios = kDefaultLodRatios);

// Simplifies one mesh to about `ratio` of its triangles; returns meshoptimizer's relative error.
float simplifyMesh(const Mesh& source, float ratio, Mesh& out);

}  // namespace lodopt::scenes
