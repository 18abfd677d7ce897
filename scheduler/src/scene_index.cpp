// The scheduler's per-frame knowledge of a scene without rendering: frustum culling (planes
// after Gribb & Hartmann 2001), importance inputs, and time-model features per level, exact
// or from canonical measurements scaled by the projected bounding box (see scene_index.hpp).
#include "scheduler/scene_index.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>

#include "scheduler/switch_control.hpp"
#include "stand_ins.hpp"

namespace lodopt::scheduler {

using detail::cutToBox;
using detail::interpenetratingOccluders;
using detail::proxyOf;
using detail::surfaceProxyOf;
using timemodel::FrameFeatures;
using timemodel::kFeatureCount;

const char* toString(FeatureMode mode) {
    return mode == FeatureMode::Exact ? "exact" : "bounds";
}

Frustum Frustum::fromViewProjection(const glm::mat4& m) {
    // Rows of the matrix (glm is column-major: m[column][row]).
    auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    Frustum f;
    f.planes[0] = row(3) + row(0);  // left
    f.planes[1] = row(3) - row(0);  // right
    f.planes[2] = row(3) + row(1);  // bottom
    f.planes[3] = row(3) - row(1);  // top
    f.planes[4] = row(3) + row(2);  // near
    f.planes[5] = row(3) - row(2);  // far
    for (glm::vec4& p : f.planes) {
        const float length = glm::length(glm::vec3(p));
        if (length > 0.0f) p /= length;
    }
    return f;
}

bool Frustum::intersectsSphere(glm::vec3 center, float radius) const {
    for (const glm::vec4& p : planes) {
        if (glm::dot(glm::vec3(p), center) + p.w < -radius) return false;
    }
    return true;
}

bool Frustum::intersectsBox(glm::vec3 low, glm::vec3 high) const {
    for (const glm::vec4& p : planes) {
        // The corner furthest along the plane normal: if it is outside, the whole box is.
        const glm::vec3 corner(p.x >= 0.0f ? high.x : low.x, p.y >= 0.0f ? high.y : low.y,
                               p.z >= 0.0f ? high.z : low.z);
        if (glm::dot(glm::vec3(p), corner) + p.w < 0.0f) return false;
    }
    return true;
}

ProjectedBox projectBox(const scenes::Bounds& box, const glm::mat4& mvp, int width, int height) {
    assert(width > 0 && height > 0);
    ProjectedBox result;
    // The time model's outline, so that visibleArea is its projected pixels exactly.
    const timemodel::ProjectedOutline outline = timemodel::projectedOutline(box, mvp);
    if (outline.empty) return result;
    const double scale = 0.25 * double(width) * double(height);
    result.area = double(outline.maxX - outline.minX) * double(outline.maxY - outline.minY) * scale;
    result.visibleArea = timemodel::viewportPixels(outline, width, height);
    return result;
}

// Canonical measurements of every level (Bounds mode).
struct SceneIndex::Canonical {
    static constexpr int kDirections = 14;
    std::array<glm::vec3, kDirections> directions{};
    std::vector<FrameFeatures> unseen;  // per (object, level)
    // Per (object, level, direction): seen − unseen at the near size and its box area.
    std::vector<FrameFeatures> seen;
    std::vector<double> nearArea;
    // Per (object, level): the exponent code per feature (0 → e = 0, 1 → ½, 2 → 1).
    std::vector<std::array<std::uint8_t, kFeatureCount>> exponent;
    // For objects near the eye, two stand-ins per object, each the object alone with at most
    // about kProxyTriangles triangles per level, and per (object, level) each one's unseen
    // features and the factor per feature from it to the object:
    //   sampled  an even sample of the level's triangles, for the counts of triangles, edges
    //            and blocks (shaded or not), which scale with the sample whatever the view;
    //   surface  the level reduced to the same surface (surfaceProxyOf), for the pixels it
    //            covers (kSurfaceFeatures). A sample's area seen from near a large surface is
    //            a few large triangles in or out of it, and its depth pass sees through the
    //            gaps: on the harbor's approach what a step between the sea's levels saves
    //            came out 113% off the exact saving on average (bench/scheduler_bench).
    // Each computes only the features taken from it.
    struct Proxy {
        std::vector<scenes::Scene> scenes;  // per object
        std::vector<FrameFeatures> unseen;  // per (object, level)
        std::vector<FrameFeatures> scale;   // per (object, level)
        timemodel::FeatureSet needed;       // what its tables compute
        int depthPassCells = 0;
    };
    Proxy sampled;
    Proxy surface;
    // The share of an object's shaded fragments that objects drawn before it and passing
    // through its box leave visible (interpenetratingOccluders), per object with such
    // occluders (occlusionRow: its first slot, −1 without), per distance (the canonical near
    // one; kOcclusionNearRadii, for an eye near the object) and per occlusion direction. The
    // share follows the eye's elevation over a sea or a terrain closely, so it is measured from
    // more directions than the 14 and interpolated between them (unoccludedShare).
    std::vector<glm::vec3> occlusionDirections;
    std::vector<int> occlusionRow;
    std::vector<float> unoccluded;
};

namespace {

// Closer than this many bounding radii, a box's screen rectangle says little about which part
// of the object is in view (a terrain under the eye), so the object's proxy is measured.
constexpr float kProxyWithinRadii = 1.5f;
// Taken from the surface proxy (Canonical::Proxy): the pixels the level covers.
constexpr std::array kSurfaceFeatures = {timemodel::Feature::kRasterPixels, timemodel::Feature::kShadedPixels,
                                         timemodel::Feature::kTexturedPixels};
// Of what the model reads (`needed`), what the surface proxy's tables compute, and the rest.
timemodel::FeatureSet surfaceFeatures(const timemodel::FeatureSet& needed) {
    timemodel::FeatureSet set;
    for (const timemodel::Feature feature : kSurfaceFeatures)
        set.set(static_cast<std::size_t>(feature), timemodel::contains(needed, feature));
    return set;
}
timemodel::FeatureSet sampledFeatures(const timemodel::FeatureSet& needed) {
    return needed & ~surfaceFeatures(needed);
}
// The proxy's depth pass, measured at set-up and again every frame the object is near the eye,
// on a coarser grid than the time model's: a proxy fills the view there, and at 128 cells its
// pass cost about as much as the rest of a city decision.
constexpr int kProxyDepthPassCells = 32;
// The surface proxy's, coarser still: bench/scheduler_bench's errors are the same to 1% at 16
// cells as at 32, and a frame is observed 2-30% faster.
constexpr int kSurfaceDepthPassCells = 16;
constexpr int kDepthPassCells = timemodel::FeatureTable::kDepthPassCells;
// The depth passes that measure how much of an object its interpenetrating occluders hide,
// from this many directions spread evenly over the sphere (a Fibonacci lattice, about 25°
// apart); a frame weighs those within 28° of the eye's direction. bench/scheduler_bench: 48
// directions within 30° and 96 within 25° gave the forest 6.0% and 4.4% all-finest frame
// error (64: 5.0%), at 2.9 and 3.8 s of set-up (64: 3.2 s).
constexpr int kOcclusionDepthPassCells = 32;
constexpr int kOcclusionDirections = 64;
constexpr float kOcclusionReachCos = 0.883f;  // cos 28°
// The near-eye shares are measured this many bounding radii from the object's centre: from
// close by, the water in front of a hull hides more of it than from afar in the same direction.
constexpr float kOcclusionNearRadii = 1.25f;

bool readsDepthTestedFeature(const timemodel::FeatureSet& needed) {
    return std::any_of(timemodel::kDepthTestedFeatures.begin(), timemodel::kDepthTestedFeatures.end(),
                       [&](timemodel::Feature f) { return timemodel::contains(needed, f); });
}

// Scales what `f` adds over `unseen` in the depth-tested features by `unoccluded`, the share of
// the object's fragments its interpenetrating occluders leave visible.
void hideOccluded(FrameFeatures& f, const FrameFeatures& unseen, double unoccluded) {
    if (unoccluded >= 1.0) return;
    for (const timemodel::Feature feature : timemodel::kDepthTestedFeatures)
        f[feature] = unseen[feature] + (f[feature] - unseen[feature]) * unoccluded;
}

// The share of the last object's depth-tested fragments in `occluded` that pass, over that in
// `alone` (the same object by itself): what the objects before it hide seen from `camera`.
double unoccludedShareOf(const scenes::Scene& alone, const scenes::Scene& occluded, const scenes::Camera& camera,
                         int width, int height) {
    const double share = timemodel::depthTestedShares(alone, camera, width, height, kOcclusionDepthPassCells)[0];
    const double behind =
        timemodel::depthTestedShares(occluded, camera, width, height, kOcclusionDepthPassCells).back();
    return share > 0.0 ? std::clamp(behind / share, 0.0, 1.0) : 1.0;
}

}  // namespace

SceneIndex::SceneIndex(const scenes::Scene& scene, int width, int height, FeatureMode mode, int threads,
                       const timemodel::FeatureSet& needed)
    : mScene(scene), mWidth(width), mHeight(height), mMode(mode), mNeeded(needed), mThreads(threads) {
    assert(width > 0 && height > 0);
    const int objects = int(scene.objects.size());
    mShapes.reserve(objects);
    mFirstLevel.reserve(objects + 1);
    mRates.reserve(objects);
    for (const scenes::Object& object : scene.objects) {
        mFirstLevel.push_back(int(mSameBoundsAsPrevious.size()));
        mShapes.push_back(objectShape(object));
        std::vector<double> triangles;
        for (std::size_t l = 0; l < object.levels.size(); ++l) {
            triangles.push_back(double(object.levels[l].stats.triangles));
            // Boxes within 2% of the object's size of the previous level's share its projection.
            const scenes::Bounds& box = object.levels[l].stats.bounds;
            const scenes::Bounds& previous = object.levels[l > 0 ? l - 1 : 0].stats.bounds;
            const float tolerance = 0.02f * glm::length(previous.max - previous.min);
            const bool same = l > 0 && !box.empty() && !previous.empty() &&
                              glm::all(glm::lessThanEqual(glm::abs(box.min - previous.min), glm::vec3(tolerance))) &&
                              glm::all(glm::lessThanEqual(glm::abs(box.max - previous.max), glm::vec3(tolerance)));
            mSameBoundsAsPrevious.push_back(same ? 1 : 0);
        }
        mRates.push_back(simplificationRates(triangles));
        mMaxLevels = std::max(mMaxLevels, int(object.levels.size()));
    }
    mFirstLevel.push_back(int(mSameBoundsAsPrevious.size()));
    // The combination-independent part, taken from the time model's own table so that it
    // stays right whatever the model counts there.
    scenes::Camera any;
    if (!scene.views.empty()) any = scene.views.front();
    mFrameConstant = timemodel::FeatureTable(scene, any, width, height, kDepthPassCells, mNeeded).frameConstant();
    if (mMode == FeatureMode::Bounds) measureCanonical();
}

SceneIndex::~SceneIndex() = default;

void SceneIndex::measureCanonical() {
    mCanonical = std::make_unique<Canonical>();
    Canonical& c = *mCanonical;
    int d = 0;
    for (int axis = 0; axis < 3; ++axis) {
        for (float sign : {1.0f, -1.0f}) {
            glm::vec3 v(0.0f);
            v[axis] = sign;
            c.directions[d++] = v;
        }
    }
    for (int corner = 0; corner < 8; ++corner) {
        c.directions[d++] =
            glm::normalize(glm::vec3(corner & 1 ? 1.0f : -1.0f, corner & 2 ? 1.0f : -1.0f, corner & 4 ? 1.0f : -1.0f));
    }
    const int levels = totalLevels();
    c.unseen.resize(levels);
    c.seen.resize(std::size_t(levels) * Canonical::kDirections);
    c.nearArea.resize(c.seen.size());
    c.exponent.resize(std::size_t(levels));
    // The sphere fills the smaller viewport dimension at the near size; a quarter of the
    // diameter (1/16 of the area) at the far size.
    const double aspect = double(mWidth) / double(mHeight);
    const double fovY = 40.0;
    const double halfAngle = std::atan(std::min(1.0, aspect) * std::tan(glm::radians(fovY / 2.0)));
    constexpr float kFarFactor = 4.0f;
    // One object at a time, with the scene's materials and its textures' names and sizes (not
    // their pixels, which would be copied once per object: the time model reads stats only).
    std::vector<scenes::Texture> textureSizes;
    for (const scenes::Texture& texture : mScene.textures)
        textureSizes.push_back({texture.name, texture.width, texture.height, {}});
    c.sampled.needed = sampledFeatures(mNeeded);
    c.sampled.depthPassCells = kProxyDepthPassCells;
    c.surface.needed = surfaceFeatures(mNeeded);
    c.surface.depthPassCells = kSurfaceDepthPassCells;
    for (Canonical::Proxy* proxy : {&c.sampled, &c.surface}) {
        proxy->scenes.resize(std::size_t(objectCount()));
        proxy->unseen.resize(std::size_t(levels));
        proxy->scale.resize(std::size_t(levels));
    }
    const bool measureOcclusion = readsDepthTestedFeature(mNeeded);
    for (int i = 0; i < kOcclusionDirections; ++i) {
        const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(kOcclusionDirections);
        const float ring = std::sqrt(std::max(0.0f, 1.0f - y * y));
        const float angle = float(i) * 2.39996323f;  // the golden angle
        c.occlusionDirections.push_back({ring * std::cos(angle), y, ring * std::sin(angle)});
    }
    c.occlusionRow.assign(std::size_t(objectCount()), -1);
    std::vector<scenes::Bounds> worldBoxes;
    for (const scenes::Object& object : mScene.objects) worldBoxes.push_back(scenes::worldBounds(object, 0));
    std::vector<std::vector<int>> occluders(static_cast<std::size_t>(objectCount()));
    for (int o = 0; measureOcclusion && o < objectCount(); ++o) {
        occluders[std::size_t(o)] = interpenetratingOccluders(worldBoxes, o);
        if (occluders[std::size_t(o)].empty()) continue;
        c.occlusionRow[std::size_t(o)] = int(c.unoccluded.size());
        c.unoccluded.resize(c.unoccluded.size() + 2 * kOcclusionDirections, 1.0f);
    }
    // Objects are measured independently, each into its own slots: spread over threads.
    auto measureObject = [&](int o, scenes::Scene& single) {
        single.objects.assign(1, mScene.objects[o]);
        for (Canonical::Proxy* proxy : {&c.sampled, &c.surface}) {
            scenes::Scene& stand = proxy->scenes[std::size_t(o)];
            stand.materials = mScene.materials;
            stand.textures = textureSizes;
            stand.objects.assign(1,
                                 proxy == &c.sampled ? proxyOf(mScene.objects[o]) : surfaceProxyOf(mScene.objects[o]));
        }
        const ObjectShape& shape = mShapes[o];
        const float radius = std::max(shape.radius, 1e-4f);
        const float nearDistance = float(radius / std::sin(halfAngle));
        auto cameraAt = [&](glm::vec3 direction, float distance) {
            scenes::Camera camera;
            camera.position = shape.center + direction * distance;
            camera.target = shape.center;
            camera.fovYDegrees = float(fovY);
            camera.nearPlane = std::max(distance - 1.5f * radius, distance * 1e-3f);
            camera.farPlane = distance + 1.5f * radius;
            return camera;
        };
        scenes::Camera away = cameraAt(glm::vec3(0.0f, 0.0f, 1.0f), nearDistance);
        away.target = away.position + glm::vec3(0.0f, 0.0f, nearDistance);  // looking away
        const timemodel::FeatureTable unseen(single, away, mWidth, mHeight, kDepthPassCells, mNeeded);
        const int count = levelCount(o);
        Canonical::Proxy* const proxies[2] = {&c.sampled, &c.surface};
        if (c.occlusionRow[std::size_t(o)] >= 0) {
            // The finest level of the object's surface stand-in alone, and after the stand-ins
            // of what passes through its box (the depth passes' reference is level 0). What
            // hides the object's lower part from a low eye lies outside its box (the water in
            // front of a hull): the occluders are cut to the box widened by a radius.
            scenes::Bounds box = worldBoxes[std::size_t(o)];
            box.min -= glm::vec3(shape.radius);
            box.max += glm::vec3(shape.radius);
            scenes::Scene alone, occluded;
            for (int p : occluders[std::size_t(o)])
                occluded.objects.push_back(surfaceProxyOf(cutToBox(mScene.objects[p], box)));
            scenes::Object surface = c.surface.scenes[std::size_t(o)].objects.front();
            surface.levels.resize(1);
            for (scenes::Scene* scene : {&alone, &occluded}) {
                scene->materials = mScene.materials;
                scene->textures = textureSizes;
                scene->objects.push_back(surface);
                scenes::updateStatistics(*scene);
            }
            const float distances[2] = {nearDistance, kOcclusionNearRadii * radius};
            for (int d = 0; d < 2; ++d) {
                for (int k = 0; k < kOcclusionDirections; ++k) {
                    const scenes::Camera camera = cameraAt(c.occlusionDirections[std::size_t(k)], distances[d]);
                    c.unoccluded[std::size_t(c.occlusionRow[std::size_t(o)] + d * kOcclusionDirections + k)] =
                        float(unoccludedShareOf(alone, occluded, camera, mWidth, mHeight));
                }
            }
        }
        for (int l = 0; l < count; ++l) c.unseen[mFirstLevel[o] + l] = unseen.contribution(0, l);
        for (Canonical::Proxy* proxy : proxies) {
            const timemodel::FeatureTable proxyUnseen(proxy->scenes[std::size_t(o)], away, mWidth, mHeight,
                                                      proxy->depthPassCells, proxy->needed);
            for (int l = 0; l < count; ++l) proxy->unseen[mFirstLevel[o] + l] = proxyUnseen.contribution(0, l);
        }
        // Exponents from the six axis directions together (a far table per direction would
        // double the set-up time for little: the power a feature scales with is a property of
        // the feature, not of the direction).
        std::vector<FrameFeatures> nearSum(static_cast<std::size_t>(count)), farSum(static_cast<std::size_t>(count));
        std::vector<double> nearAreaSum(static_cast<std::size_t>(count), 0.0),
            farAreaSum(static_cast<std::size_t>(count), 0.0);
        std::vector<FrameFeatures> proxySum[2] = {std::vector<FrameFeatures>(static_cast<std::size_t>(count)),
                                                  std::vector<FrameFeatures>(static_cast<std::size_t>(count))};
        for (int k = 0; k < Canonical::kDirections; ++k) {
            const scenes::Camera nearCamera = cameraAt(c.directions[k], nearDistance);
            const timemodel::FeatureTable nearTable(single, nearCamera, mWidth, mHeight, kDepthPassCells, mNeeded);
            const glm::mat4 nearVp =
                scenes::projectionMatrix(nearCamera, float(aspect)) * scenes::viewMatrix(nearCamera);
            const bool axis = k < 6;
            std::unique_ptr<timemodel::FeatureTable> farTable, proxyTable[2];
            glm::mat4 farVp(1.0f);
            if (axis) {
                for (int p = 0; p < 2; ++p) {
                    proxyTable[p] = std::make_unique<timemodel::FeatureTable>(
                        proxies[p]->scenes[std::size_t(o)], nearCamera, mWidth, mHeight, proxies[p]->depthPassCells,
                        proxies[p]->needed);
                }
                const scenes::Camera farCamera = cameraAt(c.directions[k], nearDistance * kFarFactor);
                farTable = std::make_unique<timemodel::FeatureTable>(single, farCamera, mWidth, mHeight,
                                                                     kDepthPassCells, mNeeded);
                farVp = scenes::projectionMatrix(farCamera, float(aspect)) * scenes::viewMatrix(farCamera);
            }
            for (int l = 0; l < count; ++l) {
                const int index = mFirstLevel[o] + l;
                const std::size_t slot = std::size_t(index) * Canonical::kDirections + k;
                const scenes::Bounds& box = mScene.objects[o].levels[l].stats.bounds;
                const double nearArea = projectBox(box, nearVp * shape.transform, mWidth, mHeight).area;
                c.seen[slot] = nearTable.contribution(0, l) - c.unseen[index];
                c.nearArea[slot] = nearArea;
                if (axis) {
                    nearSum[l] += c.seen[slot];
                    farSum[l] += farTable->contribution(0, l) - c.unseen[index];
                    nearAreaSum[l] += nearArea;
                    farAreaSum[l] += projectBox(box, farVp * shape.transform, mWidth, mHeight).area;
                    for (int p = 0; p < 2; ++p)
                        proxySum[p][l] += proxyTable[p]->contribution(0, l) - proxies[p]->unseen[index];
                }
            }
        }
        for (int p = 0; p < 2; ++p) {
            for (int l = 0; l < count; ++l) {
                FrameFeatures& scale = proxies[p]->scale[std::size_t(mFirstLevel[o] + l)];
                for (std::size_t f = 0; f < kFeatureCount; ++f) {
                    const double sum = proxySum[p][l].values[f];
                    scale.values[f] = sum > 0.0 ? nearSum[l].values[f] / sum : 1.0;
                }
            }
        }
        for (int l = 0; l < count; ++l) {
            auto& exponent = c.exponent[std::size_t(mFirstLevel[o] + l)];
            const double nearArea = nearAreaSum[l], farArea = farAreaSum[l];
            for (std::size_t f = 0; f < kFeatureCount; ++f) {
                std::uint8_t code = 0;
                const double a = nearSum[l].values[f], b = farSum[l].values[f];
                if (a > 0.0 && nearArea > 0.0 && farArea > 0.0 && nearArea > farArea) {
                    // Power of the change with the box area between the two sizes, rounded to
                    // 0, ½ or 1; a feature that vanishes at the far size scales fully.
                    const double e = b > 0.0 ? std::log(a / b) / std::log(nearArea / farArea) : 1.0;
                    code = e < 0.25 ? 0 : (e < 0.75 ? 1 : 2);
                }
                exponent[f] = code;
            }
        }
    };
    const int threads =
        std::clamp(mThreads > 0 ? mThreads : int(std::thread::hardware_concurrency()), 1, std::max(1, objectCount()));
    std::atomic<int> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    auto worker = [&] {
        scenes::Scene single;  // the object alone, with the scene's materials and texture sizes
        single.materials = mScene.materials;
        single.textures = textureSizes;
        for (int o = next++; o < objectCount(); o = next++) {
            try {
                measureObject(o, single);
            } catch (...) {
                const std::lock_guard lock(failureMutex);
                if (!failure) failure = std::current_exception();
                next = objectCount();
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) {
        try {
            pool.emplace_back(worker);
        } catch (const std::system_error&) {
            break;  // no more threads to be had: the ones running (and this one) do the rest
        }
    }
    worker();
    for (std::thread& thread : pool) thread.join();
    if (failure) std::rethrow_exception(failure);
}

double SceneIndex::unoccludedShare(int object, glm::vec3 eyeDirection, bool nearEye) const {
    const Canonical& c = *mCanonical;
    const int first = c.occlusionRow[std::size_t(object)];
    if (first < 0) return 1.0;
    const int row = first + (nearEye ? kOcclusionDirections : 0);
    // Weights falling to 0 at kOcclusionReachCos from the eye's direction; the nearest direction
    // alone where none is that near (the lattice leaves no such gap, but rounding might).
    double sum = 0.0, weights = 0.0, nearestDot = -2.0, nearest = 1.0;
    for (int k = 0; k < kOcclusionDirections; ++k) {
        const float dot = glm::dot(c.occlusionDirections[std::size_t(k)], eyeDirection);
        const double share = c.unoccluded[std::size_t(row + k)];
        if (dot > nearestDot) {
            nearestDot = dot;
            nearest = share;
        }
        if (dot <= kOcclusionReachCos) continue;
        const double w = double(dot - kOcclusionReachCos) * double(dot - kOcclusionReachCos);
        sum += w * share;
        weights += w;
    }
    return weights > 0.0 ? sum / weights : nearest;
}

void SceneIndex::beginFrame(const scenes::Camera& camera, FrameObjects& out) const {
    out.camera = camera;
    out.viewProjection = scenes::projectionMatrix(camera, float(mWidth) / float(mHeight)) * scenes::viewMatrix(camera);
    out.frustum = Frustum::fromViewProjection(out.viewProjection);
    out.visible.assign(mShapes.size(), 0);
    out.views.resize(mShapes.size());
    out.contributions.resize(std::size_t(totalLevels()));
    if (mMode == FeatureMode::Exact) {
        out.table =
            std::make_shared<timemodel::FeatureTable>(mScene, camera, mWidth, mHeight, kDepthPassCells, mNeeded);
    }
}

bool SceneIndex::observe(int object, FrameObjects& out) const {
    assert(object >= 0 && object < objectCount());
    const ObjectShape& shape = mShapes[object];
    if (shape.radius <= 0.0f || !out.frustum.intersectsSphere(shape.center, shape.radius)) return false;
    out.visible[object] = 1;
    const glm::mat4 mvp = out.viewProjection * shape.transform;
    const scenes::Object& sceneObject = mScene.objects[object];
    ProjectedBox box = projectBox(sceneObject.levels[0].stats.bounds, mvp, mWidth, mHeight);
    out.views[object] = scheduler::observe(shape, out.camera, out.viewProjection, box.visibleArea);
    const int first = mFirstLevel[object];
    const int count = levelCount(object);
    if (mMode == FeatureMode::Exact) {
        for (int l = 0; l < count; ++l) out.contributions[first + l] = out.table->contribution(object, l);
        return true;
    }
    const Canonical& c = *mCanonical;
    const glm::vec3 toEye = out.camera.position - shape.center;
    const float length = glm::length(toEye);
    const glm::vec3 eyeDirection = length > 0.0f ? toEye / length : glm::vec3(0.0f, 0.0f, 1.0f);
    if (length < kProxyWithinRadii * shape.radius) {
        const double unoccluded = unoccludedShare(object, eyeDirection, true);
        const timemodel::FeatureTable sampled(c.sampled.scenes[std::size_t(object)], out.camera, mWidth, mHeight,
                                              c.sampled.depthPassCells, c.sampled.needed);
        const timemodel::FeatureTable surface(c.surface.scenes[std::size_t(object)], out.camera, mWidth, mHeight,
                                              c.surface.depthPassCells, c.surface.needed);
        for (int l = 0; l < count; ++l) {
            const int index = first + l;
            FrameFeatures& f = out.contributions[index];
            const FrameFeatures seen = sampled.contribution(0, l) - c.sampled.unseen[index];
            f = c.unseen[index];
            for (std::size_t k = 0; k < kFeatureCount; ++k)
                f.values[k] += seen.values[k] * c.sampled.scale[index].values[k];
            const FrameFeatures covered = surface.contribution(0, l) - c.surface.unseen[index];
            for (const timemodel::Feature feature : kSurfaceFeatures) {
                f[feature] = c.unseen[index][feature] + covered[feature] * c.surface.scale[index][feature];
            }
            hideOccluded(f, c.unseen[index], unoccluded);
        }
        return true;
    }
    // The canonical direction nearest to the eye as seen from the object.
    int best = 0;
    float bestDot = -2.0f;
    for (int k = 0; k < Canonical::kDirections; ++k) {
        const float dot = glm::dot(c.directions[k], eyeDirection);
        if (dot > bestDot) {
            bestDot = dot;
            best = k;
        }
    }
    const double unoccluded = unoccludedShare(object, eyeDirection, false);
    for (int l = 0; l < count; ++l) {
        const int index = first + l;
        if (l > 0 && !mSameBoundsAsPrevious[index]) {
            box = projectBox(sceneObject.levels[l].stats.bounds, mvp, mWidth, mHeight);
        }
        FrameFeatures& f = out.contributions[index];
        f = c.unseen[index];
        const std::size_t slot = std::size_t(index) * Canonical::kDirections + best;
        if (box.area <= 0.0 || box.visibleArea <= 0.0 || c.nearArea[slot] <= 0.0) continue;
        const double share = box.visibleArea / box.area;
        const double ratio = box.area / c.nearArea[slot];
        const double scale[3] = {share, share * std::sqrt(ratio), share * ratio};
        const FrameFeatures& w = c.seen[slot];
        const auto& exponent = c.exponent[std::size_t(index)];
        for (std::size_t k = 0; k < kFeatureCount; ++k) f.values[k] += w.values[k] * scale[exponent[k]];
        hideOccluded(f, c.unseen[index], unoccluded);
    }
    return true;
}

}  // namespace lodopt::scheduler
