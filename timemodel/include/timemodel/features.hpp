// Frame features: what a render-time model is allowed to see of a frame.
//
// Following DONG15 (polygons, texture amount) and CITY17 after Wimmer & Wonka 2003
// (transformed vertices, pixels, matrices, bounding boxes, textures), a frame is described by
// sums over its drawn objects:
//   vertices, triangles, texture bytes, draw calls  — from scenes::LevelStats of the drawn level;
//   projected pixels — the screen area of the level's bounding box for the viewpoint, clipped
//                      to the near/far planes and the viewport (CITY17's "#pixels");
//   drawn objects, matrices — one model-view-projection (+ normal) matrix per drawn object;
//   bounding boxes tested — every object of the scene, drawn or not: a culling pass tests
//                      them all (our renderer does no culling, so this is constant per scene).
// and four that the papers' engines got implicitly from view-frustum culling and hardware
// rasterizers, and that llvmpipe's cost follows (measured here: the same 270k-triangle forest
// frame costs 14 ms of CPU from a view that sees a few trees and 73 ms from one that sees them
// all; a street view and an aerial view of the city with equal raster area differ by 30%):
//   visible triangles — triangles not trivially outside the view frustum (not all three
//                      vertices beyond the same clip plane): those the rasterizer sets up;
//   raster pixels    — their screen area summed (clipped to the near plane and the viewport):
//                      fragments rasterized, overdraw included;
//   edge pixels      — the length of their clipped edges inside the viewport: partial blocks;
//   shaded pixels    — raster pixels times the share of the object's fragments that pass the
//                      depth test in the reference frame drawn in object order (a 128-cell
//                      software depth pass): early depth testing skips the hidden ones;
//   textured pixels  — the part of the shaded pixels drawn with a base-color texture: the
//                      trilinear fetch makes such a fragment cost 2–2.7 times an untextured
//                      one, and a depth-failed fragment costs a fifth to a tenth of either
//                      (bench/renderer_bench, docs/timemodel.md "Overdraw probe");
//   shaded edge pixels — edge pixels times the same depth-pass share: the partial blocks along
//                      edges are cheap too where the depth test fails;
//   partial blocks   — the 4x4 pixel blocks their clipped outlines cover only partly: llvmpipe
//                      rasterizes in 4x4 blocks and tests pixel coverage only in partial ones.
//                      Edge length counts a sliver's blocks twice (both long edges cross
//                      them); the sea seen from half a metre is all slivers (docs/timemodel.md
//                      "Partial blocks");
//   shaded partial blocks — partial blocks times the depth-pass share.
// These walk the geometry once per (object, level) when a table is built.
//
// A FeatureTable precomputes each (object, level) contribution for one viewpoint and render
// size, so the features of a combination cost O(objects) and a one-object change O(1).
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::timemodel {

// Feature indices; the order is the order of FrameFeatures::values and of profile files.
enum class Feature : int {
    kVertices = 0,
    kTriangles,
    kTextureBytes,
    kDrawCalls,
    kPixels,
    kDrawnObjects,
    kMatrices,
    kBoundingBoxes,
    kVisibleTriangles,
    kRasterPixels,
    kEdgePixels,
    kShadedPixels,
    // Added after the first profiles: older files lack them (read as 0).
    kTexturedPixels,
    kShadedEdgePixels,
    kPartialBlocks,
    kShadedPartialBlocks,
};
inline constexpr std::size_t kFeatureCount = 16;

// Stable snake_case name ("vertices", "texture_bytes", ...), used in profiles and tables.
const char* featureName(Feature feature);
// All features in index order.
const std::array<Feature, kFeatureCount>& allFeatures();

// The features the depth pass scales: each is a raster count times the object's share of
// fragments passing the depth test (depthTestedShares).
inline constexpr std::array<Feature, 4> kDepthTestedFeatures = {
    Feature::kShadedPixels, Feature::kTexturedPixels, Feature::kShadedEdgePixels, Feature::kShadedPartialBlocks};

// A set of features, indexed like Feature: what a reader (a time model, TimeModel::readFeatures)
// needs. A FeatureTable built for a set skips the work of the features outside it where that
// saves time (the 4x4 block walk for the two partial-block features, the depth pass for the
// four shaded ones) and holds 0 for those; every feature in the set is exact.
using FeatureSet = std::bitset<kFeatureCount>;
inline FeatureSet everyFeature() {
    return FeatureSet().set();
}
inline bool contains(const FeatureSet& set, Feature feature) {
    return set.test(static_cast<std::size_t>(feature));
}

// Sums over a frame's drawn objects (see the file comment); every value >= 0, in its own
// unit (count, bytes, pixels). Additive: the features of a frame are the sum of its parts.
struct FrameFeatures {
    std::array<double, kFeatureCount> values{};

    double& operator[](Feature feature) { return values[static_cast<std::size_t>(feature)]; }
    double operator[](Feature feature) const { return values[static_cast<std::size_t>(feature)]; }
    FrameFeatures& operator+=(const FrameFeatures& other);
    FrameFeatures& operator-=(const FrameFeatures& other);
};
FrameFeatures operator+(FrameFeatures a, const FrameFeatures& b);
FrameFeatures operator-(FrameFeatures a, const FrameFeatures& b);

// A box's screen outline after clipping to the near and far planes, in normalized device
// coordinates (not clipped to the viewport); `empty` when nothing of it lies in front of the
// camera between the planes.
struct ProjectedOutline {
    float minX = 0.0f, minY = 0.0f, maxX = 0.0f, maxY = 0.0f;
    bool empty = true;
};
ProjectedOutline projectedOutline(const scenes::Bounds& box, const glm::mat4& modelViewProjection);
// The pixels of `outline` inside the viewport of a `width` x `height` render (> 0 each); 0
// when it is empty or lies outside.
double viewportPixels(const ProjectedOutline& outline, int width, int height);

// Screen area in pixels of an object-space box seen through `modelViewProjection` (OpenGL
// clip space): the box's 12 edges are clipped to the near and far planes, the remaining
// points projected, and their bounding rectangle clipped to the viewport. 0 when the box is
// empty, behind the camera or outside the view.
// `width`, `height` > 0: viewport size in pixels.
double projectedPixels(const scenes::Bounds& objectBounds, const glm::mat4& modelViewProjection, int width, int height);

// Visible triangles, raster pixels, edge pixels and partial blocks (see the file comment) of
// `meshes` seen through `modelViewProjection` at `width` x `height` pixels; O(vertices +
// triangles + the 4-pixel rows they span).
struct RasterFeatures {
    double visibleTriangles = 0.0;
    double rasterPixels = 0.0;
    double edgePixels = 0.0;
    double partialBlocks = 0.0;
};
RasterFeatures rasterFeatures(const std::vector<scenes::Mesh>& meshes, const glm::mat4& modelViewProjection, int width,
                              int height);
// Adds one mesh's raster features to `sum` (the vector form is this over its meshes, in order);
// without `countPartialBlocks` its partialBlocks stays as it was (the block walk skipped).
void addRasterFeatures(const scenes::Mesh& mesh, const glm::mat4& modelViewProjection, int width, int height,
                       RasterFeatures& sum, bool countPartialBlocks = true);

// Per-viewpoint table of feature contributions: build once per (scene, camera, size), then
// query combinations. Holds no reference to the scene after construction. Building walks
// every level's geometry once (O(total vertices + triangles), a few ms per million).
class FeatureTable {
public:
    // `width`, `height` > 0: the render size in pixels. `depthPassCells`: the longer side of
    // the software depth pass's grid that gives the shaded-fragment shares (kDepthPassCells; a
    // caller that only needs rough shares of small objects may take fewer). `needed`: the
    // features to compute (FeatureSet: the others may be left 0), e.g. a model's readFeatures().
    static constexpr int kDepthPassCells = 128;
    FeatureTable(const scenes::Scene& scene, const scenes::Camera& camera, int width, int height,
                 int depthPassCells = kDepthPassCells, const FeatureSet& needed = everyFeature());

    int objectCount() const { return static_cast<int>(mFirstLevel.size()) - 1; }
    int levelCount(int object) const;

    // What object `object` adds to a frame when drawn at `level`; zeros for kNotDrawn.
    // `object` in [0, objectCount()), `level` a valid level or scenes::kNotDrawn.
    const FrameFeatures& contribution(int object, int level) const;
    // Per-frame part independent of the combination (the bounding boxes tested).
    const FrameFeatures& frameConstant() const { return mFrameConstant; }

    // Features of a whole frame, O(objects). `combination` must be valid for the scene the
    // table was built from (caller's duty: validate outside input with scenes::validateCombination).
    FrameFeatures features(const scenes::Combination& combination) const;
    void features(const scenes::Combination& combination, FrameFeatures& out) const;
    // Change of the frame's features when `object` goes from `oldLevel` to `newLevel`, O(1).
    FrameFeatures delta(int object, int oldLevel, int newLevel) const;

private:
    std::vector<int> mFirstLevel;  // per object: index of its level 0 in mContributions; + end sentinel
    std::vector<FrameFeatures> mContributions;
    FrameFeatures mFrameConstant;
    FrameFeatures mZero;
};

// Per object, the share of its level 0's fragments that pass the depth test when every object
// is drawn at level 0 in object order: what the shaded features scale raster counts by, on a
// grid whose longer side is `depthPassCells` (FeatureTable's). 1 for an object that rasterizes
// no fragment. O(level-0 vertices + triangles), without the raster features' work.
std::vector<double> depthTestedShares(const scenes::Scene& scene, const scenes::Camera& camera, int width, int height,
                                      int depthPassCells);

// Features of one frame without a table: walks only the drawn levels' geometry.
// Same result as FeatureTable(scene, camera, width, height).features(combination).
FrameFeatures computeFrameFeatures(const scenes::Scene& scene, const scenes::Combination& combination,
                                   const scenes::Camera& camera, int width, int height);

}  // namespace lodopt::timemodel
