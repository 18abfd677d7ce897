// What the scheduler knows of a scene, precomputed once, and what it learns per frame without
// rendering: view-frustum culling, the importance inputs and each level's time-model features.
//
// Features per (object, level) for a frame come in two modes:
//   Exact   a timemodel::FeatureTable for the frame's camera: every feature exactly as the time
//           model was calibrated, but building it walks every level's geometry
//           (O(vertices + triangles) per frame: milliseconds for a forest);
//   Bounds  (default) O(levels) per visible object, no geometry. At construction each level is
//           measured with the exact features from a camera that does not see it (u), and with
//           its bounding sphere filling the viewport from 14 canonical directions (6 axes,
//           8 diagonals; v), the 6 axis directions also at a quarter of that size. Per frame,
//           with v taken in the canonical direction nearest to the eye, A the level's bounding
//           box area on screen before viewport clipping, A_c after it, A_near the canonical one:
//               f = u + (v − u) · (A_c / A) · (A / A_near)^e,
//           e ∈ {0, ½, 1} per feature: the power that the two canonical sizes show (pixel areas
//           scale with 1, edge lengths with ½, triangle counts with 0). So projected pixels are
//           exact (a level whose box lies within 2% of the previous level's reuses its
//           projection), visible triangles scale with the visible share of the box, raster
//           areas with the screen area, and a feature added to the time model later is handled
//           alike. An object whose centre is within 1.5 bounding radii of the eye (a terrain
//           under it, a tree brushed past) is measured through two stand-ins instead, each the
//           object alone with about 256 triangles per level and each feature scaled by the
//           object / stand-in ratio seen from the axis directions (this allocates); there a
//           box's screen rectangle says little about what is in view. Counts of triangles,
//           edges and blocks come from an even sample of the level's triangles; the pixels it
//           covers (raster, shaded, textured) from the level reduced to the same surface:
//           simplified where that keeps its area within 10%, otherwise (a soup of separate
//           quads) its largest triangles: a sample covers a large surface in a few large
//           triangles, in or out of it, and its depth pass sees through the gaps. Features that
//           depend on the other objects (the time model's shaded pixels, decided by a depth pass
//           over the whole frame) see the object alone, except for what objects drawn before
//           it and passing through its box hide (the sea a hull's lower half, a terrain a
//           trunk's base, a neighbour's crown part of a crown): that share is measured at
//           set-up from 64 directions at two distances, with stand-ins of both, and
//           interpolated for the eye's direction. Occlusion by objects merely in front of it
//           is not seen, so Bounds over-counts those fragments; the measured-time feedback
//           absorbs such a bias. tests/scheduler/scene_index_test.cpp bounds the error against
//           Exact; docs/scheduler.md reports it on the scenes' paths.
#pragma once

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "scenes/scene.hpp"
#include "scheduler/importance.hpp"
#include "timemodel/features.hpp"

namespace lodopt::scheduler {

enum class FeatureMode { Bounds, Exact };
// "bounds", "exact".
const char* toString(FeatureMode mode);

// The six clip planes of a view-projection matrix (Gribb & Hartmann), normalised, inside >= 0.
struct Frustum {
    std::array<glm::vec4, 6> planes{};
    static Frustum fromViewProjection(const glm::mat4& viewProjection);
    // False only when the sphere lies entirely outside one plane (conservative).
    bool intersectsSphere(glm::vec3 center, float radius) const;
    // False only when the box lies entirely outside one plane (conservative).
    bool intersectsBox(glm::vec3 low, glm::vec3 high) const;
};

// Screen rectangle of an object-space box: its 12 edges clipped to the near and far planes,
// projected; `area` before viewport clipping, `visibleArea` after (both pixels). The latter is
// exactly timemodel::projectedPixels.
struct ProjectedBox {
    double area = 0.0;
    double visibleArea = 0.0;
};
ProjectedBox projectBox(const scenes::Bounds& box, const glm::mat4& modelViewProjection, int width, int height);

// One frame's camera and results, reused from frame to frame so that a warmed-up frame does
// not allocate (except the Exact mode's table).
struct FrameObjects {
    scenes::Camera camera;
    glm::mat4 viewProjection{1.0f};
    Frustum frustum;
    std::shared_ptr<const timemodel::FeatureTable> table;  // Exact mode
    std::vector<std::uint8_t> visible;                     // per object: 1 when observed and in the frustum
    std::vector<ObjectView> views;                         // per object, valid when visible
    std::vector<timemodel::FrameFeatures> contributions;   // per (object, level), valid when visible
};

class SceneIndex {
public:
    // `scene` must outlive the index (Exact mode reads its geometry every frame). `width`,
    // `height` > 0: the render size in pixels, as calibrated for the time model. Bounds mode
    // measures every object from canonical cameras here, on `threads` threads (0: one per
    // core); the result does not depend on the count. `needed`: the features the time model
    // reads (TimeModel::readFeatures; the others may be left 0, their work skipped).
    SceneIndex(const scenes::Scene& scene, int width, int height, FeatureMode mode, int threads = 0,
               const timemodel::FeatureSet& needed = timemodel::everyFeature());
    ~SceneIndex();
    SceneIndex(const SceneIndex&) = delete;
    SceneIndex& operator=(const SceneIndex&) = delete;

    const scenes::Scene& scene() const { return mScene; }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    FeatureMode mode() const { return mMode; }
    const timemodel::FeatureSet& neededFeatures() const { return mNeeded; }
    int objectCount() const { return int(mShapes.size()); }
    int levelCount(int object) const { return mFirstLevel[object + 1] - mFirstLevel[object]; }
    int maxLevelCount() const { return mMaxLevels; }
    // Index of (object, level 0) in FrameObjects::contributions.
    int firstLevel(int object) const { return mFirstLevel[object]; }
    int totalLevels() const { return mFirstLevel.back(); }
    const ObjectShape& shape(int object) const { return mShapes[object]; }
    // Simplification rates per level (switch control, pixel-loss estimates).
    const std::vector<double>& rates(int object) const { return mRates[object]; }
    // Per-frame features independent of the combination (bounding boxes tested).
    const timemodel::FrameFeatures& frameConstant() const { return mFrameConstant; }

    // Starts a frame in `out`: camera matrices and frustum; clears `out.visible`; Exact mode
    // builds the frame's FeatureTable here. The index itself is never modified, so one index
    // serves any number of schedulers.
    void beginFrame(const scenes::Camera& camera, FrameObjects& out) const;
    // Culls `object` against the frame's frustum; when it may be seen, fills its view and its
    // levels' contributions and returns true. Call after beginFrame.
    bool observe(int object, FrameObjects& out) const;

private:
    struct Canonical;
    void measureCanonical();
    // Bounds mode: the share of `object`'s shaded fragments its interpenetrating occluders
    // leave visible from `eyeDirection` (unit, from the object), for an eye near the object
    // (its stand-ins measured) or not; 1 without such occluders.
    double unoccludedShare(int object, glm::vec3 eyeDirection, bool nearEye) const;

    const scenes::Scene& mScene;
    int mWidth;
    int mHeight;
    FeatureMode mMode;
    timemodel::FeatureSet mNeeded;
    int mThreads = 0;
    int mMaxLevels = 1;
    std::vector<ObjectShape> mShapes;
    std::vector<int> mFirstLevel;  // per object + end sentinel
    std::vector<std::vector<double>> mRates;
    std::vector<std::uint8_t> mSameBoundsAsPrevious;  // per (object, level)
    timemodel::FrameFeatures mFrameConstant;
    std::unique_ptr<Canonical> mCanonical;  // Bounds mode
};

}  // namespace lodopt::scheduler
