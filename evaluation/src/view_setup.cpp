// Per-view preparation: reference, layers, skipped objects and merged levels.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "evaluation/evaluation.hpp"
#include "visibility.hpp"

namespace lodopt::evaluation {

const char* toString(SkipReason reason) {
    switch (reason) {
        case SkipReason::None: return "searched";
        case SkipReason::OutsideFrustum: return "outside_frustum";
        case SkipReason::BelowOnePixel: return "below_one_pixel";
        case SkipReason::Hidden: return "hidden";
    }
    return "unknown";
}

namespace {

bool sameLayer(const renderer::Layer& a, const renderer::Layer& b) {
    const bool sameRect = a.rect.x0 == b.rect.x0 && a.rect.y0 == b.rect.y0 && a.rect.x1 == b.rect.x1 &&
                          a.rect.y1 == b.rect.y1;
    return sameRect && a.depth == b.depth && a.rgba == b.rgba && a.blendRgba == b.blendRgba &&
           a.opaqueDepth == b.opaqueDepth && a.blendDistance == b.blendDistance && a.blendFarthest == b.blendFarthest &&
           a.stackPixels == b.stackPixels && a.stackStarts == b.stackStarts && a.stackFragments == b.stackFragments;
}

// True when the object's level-0 bounding box lies entirely outside one clip plane.
bool outsideFrustum(const scenes::Object& object, const glm::mat4& viewProjection) {
    const scenes::Bounds& bounds = object.levels[0].stats.bounds;
    if (bounds.empty()) return true;
    const glm::mat4 mvp = viewProjection * object.transform;
    scenes::ClipPlaneCounts counts;
    for (int corner = 0; corner < 8; ++corner) {
        glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                    (corner & 4) ? bounds.max.z : bounds.min.z);
        counts.add(mvp * glm::vec4(p, 1.0f));
    }
    return counts.allOutsideOnePlane();
}

}  // namespace

ViewSetup::ViewSetup(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer)
    : mScene(scene), mCamera(camera), mClearColor(renderer.settings().clearColor) {
    const auto start = std::chrono::steady_clock::now();
    mReference = renderer.render(scenes::referenceCombination(scene), camera);
    const int width = mReference.width, height = mReference.height;
    const std::size_t pixels = std::size_t(width) * height;

    mLayers.resize(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        for (std::size_t l = 0; l < scene.objects[o].levels.size(); ++l) {
            mLayers[o].push_back(renderer.renderLayer(int(o), int(l), camera));
        }
    }

    // Level-0 depths per pixel: "the other objects' depth" at a pixel is one lookup. Blended
    // surfaces hide nothing (they write no depth), so only opaque ones take part.
    detail::NearestTwo levelZero(pixels);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const renderer::Layer& layer = mLayers[o][0];
        const std::vector<float>& occluder = layer.occluderDepth();
        for (int y = layer.rect.y0; y < layer.rect.y1; ++y) {
            for (int x = layer.rect.x0; x < layer.rect.x1; ++x) {
                const float depth = occluder[std::size_t(y - layer.rect.y0) * layer.rect.width() + (x - layer.rect.x0)];
                levelZero.offer(std::size_t(y) * width + x, depth, int(o));
            }
        }
    }

    const glm::mat4 viewProjection =
        scenes::projectionMatrix(camera, float(width) / float(height)) * scenes::viewMatrix(camera);
    mObjects.resize(scene.objects.size());
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const std::vector<renderer::Layer>& layers = mLayers[o];
        ObjectSetup& setup = mObjects[o];
        setup.fixedLevel = int(layers.size()) - 1;
        setup.referencePixels = layers[0].coveredPixels;
        const bool anyCoverage =
            std::any_of(layers.begin(), layers.end(), [](const renderer::Layer& l) { return l.coveredPixels > 0; });
        if (!anyCoverage) {
            setup.skip = outsideFrustum(scene.objects[o], viewProjection) ? SkipReason::OutsideFrustum
                                                                          : SkipReason::BelowOnePixel;
        } else {
            // Hidden: no level has a pixel at least as near as the other objects' level 0.
            bool visible = false;
            for (const renderer::Layer& layer : layers) {
                for (int y = layer.rect.y0; y < layer.rect.y1 && !visible; ++y) {
                    for (int x = layer.rect.x0; x < layer.rect.x1; ++x) {
                        float depth =
                            layer.depth[std::size_t(y - layer.rect.y0) * layer.rect.width() + (x - layer.rect.x0)];
                        if (depth >= 1.0f) continue;
                        if (depth <= levelZero.nearestOtherThan(std::size_t(y) * width + x, int(o))) {
                            visible = true;
                            break;
                        }
                    }
                }
                if (visible) break;
            }
            if (!visible) setup.skip = SkipReason::Hidden;
        }
        if (setup.skip != SkipReason::None) continue;
        // Runs of identical consecutive levels collapse into their coarsest (cheapest) member.
        for (std::size_t l = 0; l < layers.size(); ++l) {
            if (l + 1 < layers.size() && sameLayer(layers[l], layers[l + 1])) {
                ++setup.mergedLevels;
                continue;
            }
            setup.optionLevels.push_back(int(l));
        }
        mVariableObjects.push_back(int(o));
    }

    for (const ObjectSetup& setup : mObjects) {
        mSkip.searchedObjects += setup.skip == SkipReason::None;
        mSkip.outsideFrustum += setup.skip == SkipReason::OutsideFrustum;
        mSkip.belowOnePixel += setup.skip == SkipReason::BelowOnePixel;
        mSkip.hidden += setup.skip == SkipReason::Hidden;
        mSkip.mergedLevels += setup.mergedLevels;
    }
    mSetupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::vector<int> ViewSetup::levelCounts() const {
    std::vector<int> counts;
    for (int object : mVariableObjects) counts.push_back(int(mObjects[object].optionLevels.size()));
    return counts;
}

scenes::Combination ViewSetup::toScene(const optimizer::Combination& combination) const {
    scenes::Combination result(mObjects.size());
    for (std::size_t o = 0; o < mObjects.size(); ++o) result[o] = mObjects[o].fixedLevel;
    for (std::size_t v = 0; v < mVariableObjects.size(); ++v) {
        const int object = mVariableObjects[v];
        result[object] = mObjects[object].optionLevels[combination[v]];
    }
    return result;
}

optimizer::Combination ViewSetup::fromScene(const scenes::Combination& combination) const {
    optimizer::Combination result;
    for (int object : mVariableObjects) {
        const std::vector<int>& options = mObjects[object].optionLevels;
        int level = combination[object] == scenes::kNotDrawn ? options.back() : combination[object];
        auto it = std::lower_bound(options.begin(), options.end(), level);
        result.push_back(it == options.end() ? int(options.size()) - 1 : int(it - options.begin()));
    }
    return result;
}

}  // namespace lodopt::evaluation
