// Geometric error of a level of detail: the two-sided surface deviation between two triangle
// surfaces, measured the way Metro does (Cignoni, Rocchini, Scopigno 1998, "Metro: measuring
// error on simplified surfaces").
//
// Each surface is sampled and every sample is measured to the nearest point of the other
// surface: the one-sided distance d(A, B) is the largest such distance of A's samples, and the
// Hausdorff distance max(d(A, B), d(B, A)) is what a level may be off by, wherever the camera
// looks (one side alone misses what a level adds or cuts away). A surface's samples are
// area-weighted points, the same set every run and on every platform (systematic sampling along
// the cumulative triangle areas, the position inside a triangle from the van der Corput
// sequence: no random numbers), plus its vertices, where a simplification's error concentrates.
// Around the largest area samples (on up to 32 triangles per side) a compass search over the
// triangle climbs to the peak itself, so that a peak narrower than the sample spacing (over a
// gap or a spike the simplification removed) is found rather than stepped over. The nearest
// point on a triangle is Ericson's closest point (Real-Time Collision Detection, §5.1.5); a
// bounding-volume hierarchy over the other surface's triangles finds the nearest triangle
// without visiting every one. Every value measured is a true distance of a point of the
// surface, so the maximum bounds the Hausdorff distance from below and rises towards it as the
// samples grow denser.
//
// A surface is the union of a level's meshes, all their triangles at once (materials are not
// told apart). Degenerate triangles (zero area) get no area samples but are still measured to,
// as their edges. A surface without triangles cannot be measured to: against one, the deviation
// is the diagonal of the other surface's bounding box (the whole of it is missing), and two such
// surfaces deviate by 0. The result is finite for finite positions.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scenes {

// Distances in the units of the positions after the transform (world units for an object's
// transform, object units for the identity).
struct SurfaceDeviation {
    // The larger one-sided maximum: the Hausdorff distance as far as the samples see it.
    double maximum = 0.0;
    // The mean distance of both sides' area samples (an estimate of the mean of the two
    // one-sided area-weighted mean distances, Metro's mean; vertices are left out, since they
    // would weigh a finely tessellated region more); a side without area counts its vertices.
    double mean = 0.0;
};

struct GeometricErrorParameters {
    // Area-weighted samples on each surface with area: samplesPerTriangle per triangle of the
    // one with more triangles (Metro's default, 10), within [minSamplesPerSide,
    // maxSamplesPerSide]; 0 <= samplesPerTriangle, 1 <= minSamplesPerSide <= maxSamplesPerSide.
    // The floor keeps a box's mean meaningful; the cap bounds a level's time on a huge mesh,
    // where the vertex samples and the peak search keep the maximum close.
    int samplesPerTriangle = 10;
    int minSamplesPerSide = 1024;
    int maxSamplesPerSide = 8192;
    // Each surface's distinct vertex positions (those its triangles use) are measured too, at
    // most this many, >= 0: beyond it an evenly strided subset, so that a huge mesh costs a
    // bounded time.
    int maxVertexSamples = 32768;
    // Worker threads of computeGeometricErrors, >= 0; 0 for std::thread::hardware_concurrency().
    // Results do not depend on it.
    int threads = 0;
};

// The two-sided surface deviation between surfaces `a` and `b`, after both are transformed.
//   a, b:       meshes with indices in range (a valid level's meshes); either may have no
//               triangles (see above). Only positions and indices are read.
//   transform:  affine (last row 0 0 0 1), applied to both; the identity measures in object units.
//   parameters: the sample counts; threads is not used (one thread).
SurfaceDeviation surfaceDeviation(const std::vector<Mesh>& a, const std::vector<Mesh>& b, const glm::mat4& transform,
                                  const GeometricErrorParameters& parameters = {});

// Fills every unset Level::geometricError of the scene: level 0 gets 0, level k the maximum of
// surfaceDeviation(level k, level 0) under the object's transform, in world units. Levels
// already set are left as they are. Objects with the same geometry in every level (same
// positions and indices) and transforms that differ only by rotation, reflection, translation
// and uniform scale are measured once, in object space, and scaled by each one's scale; a
// level with level 0's exact geometry (a material-only level) gets 0 without sampling.
// Objects and levels are measured in parallel; the results are the same for any thread count.
//   scene:      a valid scene (validateScene); its geometry is not changed.
//   parameters: as above.
void computeGeometricErrors(Scene& scene, const GeometricErrorParameters& parameters = {});

}  // namespace lodopt::scenes
