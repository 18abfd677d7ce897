// A screen-size switch threshold (scenes::screenSize: bounding-sphere diameter over the view
// height, for a perspective camera with vertical field of view fovY) in each engine's own
// convention, and back. For an object with world bounds B (sphere radius r = half the box
// diagonal, largest box extent e) seen from distance d:
//
//   Unreal    screen size = 2 r / (2 d tan(fovY/2)) = s: ComputeBoundsScreenSize takes the larger
//             of the two projection scales, which is the vertical one for a view at least as wide
//             as it is high (aspect >= 1, assumed here).
//   Unity     LOD.screenRelativeTransitionHeight = e / (2 d tan(fovY/2)) = s e / (2 r): a
//             LODGroup's size is its bounds' largest extent (UnityGLTF reads MSFT_screencoverage
//             as this height).
//   three.js  THREE.LOD switches by the camera's distance to the LOD's position: level k from
//             distance d_k = r / (s_k tan(fovY/2)) on, with the LOD placed at the bounds' centre.
//   Babylon   addLODLevel(distance): the same d_k, measured to the bounding sphere's centre; with
//             useLODScreenCoverage, coverage = pi (r minZ / d)^2 / screenArea where screenArea is
//             the near plane's, (2 minZ tan(fovY/2))^2 aspect: coverage = pi s^2 / (4 aspect).
//
// docs/thresholds.md has the sources.
#pragma once

#include "scenes/scene.hpp"

namespace lodopt::scenes {

double unrealScreenSize(double screenSize);
double unityRelativeHeight(double screenSize, const Bounds& bounds);
double screenSizeFromUnityRelativeHeight(double relativeHeight, const Bounds& bounds);
// Distances grow as screen size shrinks; screenSize > 0.
double switchDistance(double screenSize, const Bounds& bounds, double fovYDegrees);
double babylonScreenCoverage(double screenSize, double aspect);

}  // namespace lodopt::scenes
