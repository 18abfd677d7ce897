// Stand-ins: reduced copies of an object that SceneIndex measures instead of the object itself
// (objects near the eye, occlusion shares), and the parts of other objects that pass through it
// (what hides part of it whatever the camera). Private to the scheduler module; scene_index.hpp
// says how they are used.
#pragma once

#include <cstddef>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scheduler::detail {

// About how many triangles a stand-in keeps per level.
constexpr std::size_t kProxyTriangles = 256;

// `object` with every level's triangles thinned to an even sample of at most kProxyTriangles.
scenes::Object proxyOf(const scenes::Object& object);

// `object` with every level reduced to about kProxyTriangles triangles covering what the level
// covers (levels already that small kept as they are): simplified (scenes::simplifyMesh) where
// that keeps the surface area within 10%; otherwise (triangle soups, which simplification
// clusters away: the city's ground) its largest triangles.
scenes::Object surfaceProxyOf(const scenes::Object& object);

// What hides part of `object` from every view on the open side, whatever the camera: the
// objects drawn before it (the renderer draws in object order, and only those fail its
// fragments' depth test) whose level-0 box reaches into its own by more than 1% of its size
// along every axis, such as the sea through the ship's hull or a terrain through a trunk's
// base (a building standing on a flat ground does not). Objects merely in front of it from some
// view are not here: that occlusion depends on the camera (scene_index.hpp).
// `worldBoxes`: each object's level-0 world box (scenes::worldBounds), empty for an empty level.
std::vector<int> interpenetratingOccluders(const std::vector<scenes::Bounds>& worldBoxes, int object);

// `occluder`'s level 0 cut to the triangles whose world box overlaps `box` (world space), so
// that an occluder costs what lies in the box.
scenes::Object cutToBox(const scenes::Object& occluder, const scenes::Bounds& box);

}  // namespace lodopt::scheduler::detail
