// Viewpoints over a scene for batch work (`lodopt sweep`): a grid of camera positions over the
// scene's footprint, and an object's size on screen from a camera.
//
// A grid "CxRxD@H[/P]" places C x R positions evenly over a box in the ground plane (x, z):
// cell centres, so no camera stands on the box's edge. At each position D cameras look in
// directions evenly spaced around the vertical (the first toward +x, turning toward +z),
// pitched P degrees (negative: down; default -10), from height H above the scene's lowest
// point. The box is the scene's footprint (the union of every object's level-0 world bounds)
// unless one is given. Built-in scenes have no walkable-area mark-up, so the footprint stands in
// for it; a user who knows better passes the box.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

struct GroundBox {
    float minX = 0.0f, minZ = 0.0f, maxX = 0.0f, maxZ = 0.0f;
};

struct CameraGrid {
    int columns = 1;              // along x, >= 1
    int rows = 1;                 // along z, >= 1
    int directions = 1;           // look directions per position, >= 1
    float height = 2.0f;          // above the scene's lowest point, world units, finite
    float pitchDegrees = -10.0f;  // (-90, 90)
    std::optional<GroundBox> box;  // default: the scene's footprint
    float fovYDegrees = 45.0f;
};

// Parses "CxRxD@H" or "CxRxD@H/P" (for example "10x10x8@2" or "5x5x4@60/-35"). Throws
// std::invalid_argument saying which part is wrong.
CameraGrid parseCameraGrid(std::string_view text);

// columns * rows * directions cameras, position-major (row, then column, then direction),
// named "grid_R_C_D". Throws SceneError when the scene has no geometry and no box is given, or
// when the grid's values are out of range.
std::vector<Camera> gridCameras(const Scene& scene, const CameraGrid& grid);

// The union of every object's level-0 world bounds (empty Bounds for an empty scene).
Bounds sceneBounds(const Scene& scene);

// Engines' "screen size": the bounding sphere's diameter over the viewport height, for a
// perspective camera (Unreal's screen size; 2 r cot(fov/2) / d). Distance clamped to 1e-6.
double screenSize(const Bounds& bounds, const Camera& camera);

}  // namespace lodopt::scenes
