// A coarse software depth pass (private to the module): which share of each object's
// rasterized fragments survives the depth test when the reference frame (every object at
// level 0) is drawn in object order, as the renderer draws it. Early depth testing lets
// llvmpipe skip shading hidden fragments, so hidden and visible fragments cost differently;
// this share turns an object's rasterized area into an estimate of its shaded area.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::timemodel::detail {

// Per object: passed / rasterized fragments on a grid whose longer side is `resolution`
// cells (1 when the object rasterizes no fragment). `viewProjection` maps world to clip
// space; `aspect` = width / height of the real viewport. Each triangle is sampled only on the
// cells of each row it can reach; `everyCell` samples its whole bounding box instead (the
// slower reference: the same shares).
// FeatureTable::kDepthPassCells is the time model's `resolution`.
std::vector<double> depthPassShares(const scenes::Scene& scene, const glm::mat4& viewProjection, float aspect,
                                    int resolution, bool everyCell = false);

}  // namespace lodopt::timemodel::detail
