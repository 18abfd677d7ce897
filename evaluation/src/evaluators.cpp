// The fast (layers + incremental metrics) and full (render + metrics) evaluation paths.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <thread>

#include "evaluation/evaluation.hpp"
#include "dirty_regions.hpp"
#include "visibility.hpp"
#include "window_groups.hpp"
#include "metrics/incremental_evaluator.hpp"
#include "scenes/viewpoints.hpp"

namespace lodopt::evaluation {

metrics::MetricParameters searchParameters(metrics::MetricParameters parameters) {
    parameters.computePrecisionRecall = false;
    return parameters;
}

std::vector<std::string> componentNames(bool precisionRecall) {
    std::vector<std::string> names = {"ssim", "boundary_entropy", "information_entropy"};
    if (precisionRecall) names.insert(names.end(), {"precision", "recall"});
    return names;
}

optimizer::Score toScore(const metrics::MetricResult& result) {
    optimizer::Score score;
    score.fitness = result.fitness;
    score.components[0] = result.ssimFidelity;
    score.components[1] = result.boundaryEntropy.fidelity;
    score.components[2] = result.informationEntropy.fidelity;
    score.componentCount = 3;
    if (result.precisionRecallComputed) {
        score.components[3] = result.precision;
        score.components[4] = result.recall;
        score.componentCount = 5;
    }
    return score;
}

namespace {

metrics::ImageView viewOf(const renderer::Frame& frame) {
    return metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4);
}

// How finely the composite reports changed pixels. Finer bands and splits fit a ragged
// silhouette more tightly, but every update grows by the SSIM window and has a fixed cost, so
// small pieces get merged back (mergeCheaper). Measured on forest at 512² (docs/optimizer.md).
const renderer::ChangeGrid kChangeGrid{8, 32};

std::uint64_t updateCost(const std::vector<renderer::PixelRect>& rects, const detail::UpdateCostModel& model) {
    std::uint64_t cost = 0;
    for (const renderer::PixelRect& rect : rects) cost += model.cost(rect);
    return cost;
}

}  // namespace

// One evaluation state: the last candidate's composite and incremental metrics.
struct LayerEvaluator::State {
    DirtyRegions regions;
    renderer::Frame frame;
    std::vector<const renderer::Layer*> layers;  // per scene object, the current layer
    optimizer::Combination current;
    metrics::IncrementalEvaluator metrics;
    detail::UpdateCostModel costModel;
    std::vector<renderer::PixelRect> dirty;  // ObjectBounds: the changed objects' rectangles
    // ChangedPixels: per frame row, the columns a changed object covered before or covers now,
    // in use over rows [dirtyTop, dirtyBottom) and empty elsewhere.
    std::vector<renderer::RowSpan> dirtyRows;
    int dirtyTop = 0, dirtyBottom = 0;
    std::vector<renderer::PixelRect> changed;  // tight rectangles of the changed pixels
    renderer::CompositeScratch compositeScratch;
    std::vector<metrics::PartMove> moves;        // with parts: the variables that moved
    std::vector<metrics::UpdateRect> updateRects;

    State(const ViewSetup& setup, const metrics::MetricParameters& parameters, DirtyRegions regions,
          const std::shared_ptr<metrics::PartCache>& parts)
        : regions(regions), metrics(viewOf(setup.reference()), parameters) {
        current.assign(setup.variableObjects().size(), 0);
        const scenes::Combination levels = setup.toScene(current);
        for (std::size_t o = 0; o < levels.size(); ++o) layers.push_back(&setup.layer(int(o), levels[o]));
        renderer::composite(layers, setup.width(), setup.height(), setup.clearColor(), frame);
        if (parts) {
            metrics.setParts(parts, viewOf(frame), current);
        } else {
            metrics.setCandidate(viewOf(frame));
        }
        moves.reserve(current.size());
        updateRects.reserve(64);
        // ObjectBounds keeps the earlier threshold too: plain area, no window or call cost.
        if (regions == DirtyRegions::ObjectBounds) {
            costModel = {0, 0};
        } else {
            costModel.ssimReach = metrics.ssimMapSize().window - 1;
        }
        dirty.reserve(current.size());
        dirtyRows.resize(std::size_t(setup.height()));
    }

    void moveTo(const ViewSetup& setup, const optimizer::Combination& combination) {
        if (regions == DirtyRegions::ObjectBounds) {
            moveWithinBounds(setup, combination);
            return;
        }
        dirtyTop = frame.height;
        dirtyBottom = 0;
        moves.clear();
        const std::vector<int>& objects = setup.variableObjects();
        for (std::size_t v = 0; v < combination.size(); ++v) {
            if (combination[v] == current[v]) continue;
            const int object = objects[v];
            const std::vector<int>& levels = setup.objects()[object].optionLevels;
            markDirty(*layers[object], setup.coverage(object, levels[current[v]]));
            layers[object] = &setup.layer(object, levels[combination[v]]);
            markDirty(*layers[object], setup.coverage(object, levels[combination[v]]));
            current[v] = combination[v];
            moves.push_back({int(v), combination[v]});
        }
        changed.clear();
        if (dirtyTop < dirtyBottom) {
            const std::span<renderer::RowSpan> rows(dirtyRows.data() + dirtyTop, std::size_t(dirtyBottom - dirtyTop));
            renderer::compositeSpansChanges(layers, dirtyTop, rows, setup.clearColor(), kChangeGrid, frame, changed,
                                            compositeScratch);
            std::fill(rows.begin(), rows.end(), renderer::RowSpan{});
        }
        // A pixel-identical composite leaves the scores as they are; with parts the moved parts'
        // states must still be recorded (their owned windows come from the cache).
        if (metrics.hasParts() ? moves.empty() : changed.empty()) return;
        detail::mergeCheaper(changed, costModel);
        score(changed);
    }

private:
    // Widens the dirty rows by the columns `layer` covers.
    void markDirty(const renderer::Layer& layer, const std::vector<renderer::RowSpan>& coverage) {
        for (std::size_t i = 0; i < coverage.size(); ++i) {
            const renderer::RowSpan& span = coverage[i];
            if (span.empty()) continue;
            const int y = layer.rect.y0 + int(i);
            renderer::RowSpan& row = dirtyRows[std::size_t(y)];
            row = row.empty() ? span : renderer::RowSpan{std::min(row.x0, span.x0), std::max(row.x1, span.x1)};
            dirtyTop = std::min(dirtyTop, y);
            dirtyBottom = std::max(dirtyBottom, y + 1);
        }
    }

    // The earlier fast path: recomposite and re-score the changed objects' whole rectangles.
    void moveWithinBounds(const ViewSetup& setup, const optimizer::Combination& combination) {
        dirty.clear();
        const std::vector<int>& objects = setup.variableObjects();
        for (std::size_t v = 0; v < combination.size(); ++v) {
            if (combination[v] == current[v]) continue;
            const int object = objects[v];
            const renderer::Layer* next = &setup.layer(object, setup.objects()[object].optionLevels[combination[v]]);
            const renderer::PixelRect rect = detail::unite(layers[object]->rect, next->rect);
            layers[object] = next;
            current[v] = combination[v];
            if (!rect.empty()) dirty.push_back(rect);
        }
        if (dirty.empty()) return;
        detail::mergeOverlapping(dirty);
        for (const renderer::PixelRect& rect : dirty) renderer::compositeRect(layers, rect, setup.clearColor(), frame);
        score(dirty);
    }

    // Updates the metrics for a frame that changed only inside `rects` (and, with parts, whose
    // variables in `moves` moved).
    void score(const std::vector<renderer::PixelRect>& rects) {
        // Past half the image by the cost model, one full metric pass is cheaper: per pixel it
        // costs about half of an update's (metrics_bench: 1.16 ms at 512² against 44 µs for a
        // 64² rectangle, 74² windows with the margin).
        const bool whole = 2 * updateCost(rects, costModel) > std::uint64_t(frame.width) * frame.height;
        if (metrics.hasParts()) {
            updateRects.clear();
            if (whole) {
                updateRects.push_back({0, 0, frame.width, frame.height});
            } else {
                for (const renderer::PixelRect& r : rects) updateRects.push_back({r.x0, r.y0, r.x1, r.y1});
            }
            metrics.update(viewOf(frame), updateRects, moves);
            return;
        }
        if (whole) {
            metrics.setCandidate(viewOf(frame));
            return;
        }
        for (const renderer::PixelRect& rect : rects) {
            metrics.updateRect(viewOf(frame), rect.x0, rect.y0, rect.x1, rect.y1);
        }
    }
};

namespace {

// Per pixel, the one variable whose option layers can show there, kSharedPixel where several
// can and kConstantPixel where none can (skipped objects never change; detail::VisibilityBounds
// says which covering layers are always hidden).
std::vector<std::int32_t> pixelParts(const ViewSetup& setup, const detail::VisibilityBounds& visibility) {
    const int width = setup.width(), height = setup.height();
    std::vector<std::int32_t> parts(std::size_t(width) * height, metrics::kConstantPixel);
    const std::vector<int>& objects = setup.variableObjects();
    for (std::size_t v = 0; v < objects.size(); ++v) {
        for (int level : setup.objects()[objects[v]].optionLevels) {
            const renderer::Layer& layer = setup.layer(objects[v], level);
            const renderer::PixelRect& r = layer.rect;
            for (int y = std::max(r.y0, 0); y < std::min(r.y1, height); ++y) {
                const float* depth = layer.depth.data() + std::size_t(y - r.y0) * r.width();
                std::int32_t* row = parts.data() + std::size_t(y) * width;
                for (int x = std::max(r.x0, 0); x < std::min(r.x1, width); ++x) {
                    if (!visibility.canShow(std::size_t(y) * width + x, objects[v], depth[x - r.x0])) continue;
                    std::int32_t& owner = row[x];
                    if (owner == metrics::kConstantPixel) {
                        owner = std::int32_t(v);
                    } else if (owner != std::int32_t(v)) {
                        owner = metrics::kSharedPixel;
                    }
                }
            }
        }
    }
    return parts;
}

// Pixels where `a` and `b` differ: one covers and the other not, or both cover in other colors
// (opaque or blended).
std::uint64_t differingPixels(const renderer::Layer& a, const renderer::Layer& b) {
    const renderer::PixelRect& ra = a.rect;
    const renderer::PixelRect& rb = b.rect;
    // The covered pixel (x, y) of `layer`, its opaque and blended colors in `color` and
    // `blend`; false when not covered.
    auto covered = [](const renderer::Layer& layer, int x, int y, std::uint32_t& color, std::uint32_t& blend) {
        const renderer::PixelRect& r = layer.rect;
        if (x < r.x0 || x >= r.x1 || y < r.y0 || y >= r.y1) return false;
        const std::size_t at = std::size_t(y - r.y0) * r.width() + std::size_t(x - r.x0);
        if (!(layer.depth[at] < 1.0f)) return false;
        std::memcpy(&color, &layer.rgba[at * 4], 4);
        if (layer.blends()) std::memcpy(&blend, &layer.blendRgba[at * 4], 4);
        return true;
    };
    std::uint64_t count = 0;
    for (int y = std::min(ra.y0, rb.y0); y < std::max(ra.y1, rb.y1); ++y) {
        for (int x = std::min(ra.x0, rb.x0); x < std::max(ra.x1, rb.x1); ++x) {
            std::uint32_t colorA = 0, colorB = 0, blendA = 0, blendB = 0;
            const bool inA = covered(a, x, y, colorA, blendA), inB = covered(b, x, y, colorB, blendB);
            count += inA != inB || (inA && (colorA != colorB || blendA != blendB));
        }
    }
    return count;
}

}  // namespace

double meanLevelStepPixels(const ViewSetup& setup) {
    double pixels = 0.0;
    int steps = 0;
    for (int object : setup.variableObjects()) {
        const std::vector<int>& levels = setup.objects()[object].optionLevels;
        for (std::size_t j = 0; j + 1 < levels.size(); ++j) {
            pixels += double(differingPixels(setup.layer(object, levels[j]), setup.layer(object, levels[j + 1])));
            ++steps;
        }
    }
    return steps > 0 ? pixels / steps : 0.0;
}

LayerEvaluator::LayerEvaluator(const ViewSetup& setup, const metrics::MetricParameters& parameters, int threads,
                               DirtyRegions regions, int states, PartCaching caching, std::size_t groupCacheBytes)
    : mSetup(setup), mParameters(parameters), mThreads(std::max(threads, 1)) {
    const bool changedPixels = regions == DirtyRegions::ChangedPixels;
    // Groups need a fitness made only of window sums; otherwise the owned windows serve.
    const bool automatic = caching == PartCaching::Auto;
    if ((automatic || caching == PartCaching::Groups) &&
        !(changedPixels && metrics::RegionScorer::supports(parameters))) {
        caching = PartCaching::On;
    }
    if (automatic && caching == PartCaching::Auto) caching = PartCaching::Groups;
    // Both caches' analyses start from where each object can show; Auto may need both.
    std::optional<detail::VisibilityBounds> visibility;
    if (caching == PartCaching::Groups) {
        visibility.emplace(setup);
        mScorer = std::make_unique<metrics::RegionScorer>(viewOf(setup.reference()), parameters);
        mGroups = std::make_unique<detail::WindowGroups>(setup, *visibility, *mScorer, groupCacheBytes);
        const double objects = double(std::max<std::size_t>(setup.variableObjects().size(), 1));
        if (automatic && meanLevelStepPixels(setup) < kMinStepPixelsPerGroup * double(mGroups->size()) / objects) {
            mGroups.reset();
            mScorer.reset();
            caching = PartCaching::On;
        }
    }
    const int count = std::max(states, mThreads);
    if (mGroups) {
        for (int t = 0; t < count; ++t) {
            mGroupStates.push_back(std::make_unique<detail::GroupState>(setup, *mScorer, *mGroups));
        }
    } else {
        if (caching == PartCaching::On && changedPixels && !setup.variableObjects().empty()) {
            const std::vector<int> counts = setup.levelCounts();
            if (!visibility) visibility.emplace(setup);
            mPartCache = metrics::makePartCache(setup.width(), setup.height(), parameters,
                                                pixelParts(setup, *visibility), counts);
        }
        for (int t = 0; t < count; ++t) {
            mStates.push_back(std::make_unique<State>(setup, parameters, regions, mPartCache));
        }
    }
    mAssigned.resize(stateCount());
    mBusy.reserve(stateCount());
    for (int object : setup.variableObjects()) {
        std::vector<std::uint64_t> pixels;
        for (int level : setup.objects()[object].optionLevels) pixels.push_back(setup.layer(object, level).coveredPixels);
        mOptionPixels.push_back(std::move(pixels));
    }
}

LayerEvaluator::~LayerEvaluator() = default;

std::size_t LayerEvaluator::stateCount() const { return mGroups ? mGroupStates.size() : mStates.size(); }

const optimizer::Combination& LayerEvaluator::currentOf(std::size_t state) const {
    return mGroups ? mGroupStates[state]->current() : mStates[state]->current;
}

void LayerEvaluator::moveState(std::size_t state, const optimizer::Combination& combination) {
    if (mGroups) {
        mGroupStates[state]->moveTo(combination);
    } else {
        mStates[state]->moveTo(mSetup, combination);
    }
}

metrics::MetricResult LayerEvaluator::resultOf(std::size_t state) const {
    return mGroups ? mGroupStates[state]->result() : mStates[state]->metrics.result();
}

const optimizer::Combination& LayerEvaluator::planned(std::size_t state,
                                                      std::span<const optimizer::Combination> batch) const {
    return mAssigned[state].empty() ? currentOf(state) : batch[mAssigned[state].back()];
}

std::size_t LayerEvaluator::nearestState(const optimizer::Combination& combination,
                                         std::span<const optimizer::Combination> batch, std::size_t cap) const {
    // Cost of a move: the pixels the changed objects' old and new layers cover, an upper bound
    // of what gets recomposited (re-scoring follows the pixels that really change).
    std::size_t best = stateCount();
    std::uint64_t bestCost = 0;
    for (std::size_t s = 0; s < stateCount(); ++s) {
        if (mAssigned[s].size() >= cap) continue;
        const optimizer::Combination& from = planned(s, batch);
        std::uint64_t cost = 0;
        for (std::size_t v = 0; v < combination.size() && (best == stateCount() || cost < bestCost); ++v) {
            if (combination[v] != from[v]) {
                cost += mOptionPixels[v][std::size_t(from[v])] + mOptionPixels[v][std::size_t(combination[v])];
            }
        }
        if (best == stateCount() || cost < bestCost) {
            best = s;
            bestCost = cost;
        }
    }
    return best;
}

optimizer::Score LayerEvaluator::evaluate(const optimizer::Combination& combination) {
    optimizer::Score score;
    evaluateBatch(std::span<const optimizer::Combination>(&combination, 1), std::span<optimizer::Score>(&score, 1));
    return score;
}

void LayerEvaluator::evaluateBatch(std::span<const optimizer::Combination> combinations,
                                   std::span<optimizer::Score> scores) {
    if (combinations.empty()) return;
    // Each candidate goes to its nearest state, at most `cap` per state so that every thread
    // gets work; a state's candidates are evaluated in batch order by one thread. Scores do
    // not depend on the assignment (bit-exact metrics), only the time does.
    const std::size_t threads = std::min<std::size_t>(std::size_t(mThreads), combinations.size());
    const std::size_t cap = (combinations.size() + threads - 1) / threads;
    for (std::size_t k = 0; k < combinations.size(); ++k) {
        mAssigned[nearestState(combinations[k], combinations, cap)].push_back(k);
    }
    auto run = [&](std::size_t s) {
        for (std::size_t k : mAssigned[s]) {
            moveState(s, combinations[k]);
            scores[k] = toScore(resultOf(s));
        }
    };
    mBusy.clear();
    for (std::size_t s = 0; s < stateCount(); ++s) {
        if (!mAssigned[s].empty()) mBusy.push_back(s);
    }
    if (threads <= 1 || mBusy.size() <= 1) {
        for (std::size_t s : mBusy) run(s);
    } else {
        // Thread t runs the busy states t, t + workers, ...; the caller's thread takes t = 0.
        const std::size_t workers = std::min(threads, mBusy.size());
        auto runShare = [&](std::size_t t) {
            for (std::size_t i = t; i < mBusy.size(); i += workers) run(mBusy[i]);
        };
        std::vector<std::thread> pool;
        for (std::size_t t = 1; t < workers; ++t) pool.emplace_back(runShare, t);
        runShare(0);
        for (std::thread& worker : pool) worker.join();
    }
    for (std::vector<std::size_t>& assigned : mAssigned) assigned.clear();  // capacity kept
}

metrics::MetricResult LayerEvaluator::metricsOf(const optimizer::Combination& combination) {
    moveState(0, combination);
    return resultOf(0);
}

renderer::Frame LayerEvaluator::imageOf(const optimizer::Combination& combination) {
    moveState(0, combination);
    return mGroups ? mGroupStates[0]->image() : mStates[0]->frame;
}

GroupCacheStats LayerEvaluator::groupCacheStats() const { return mGroups ? mGroups->stats() : GroupCacheStats{}; }

metrics::PartCacheStats LayerEvaluator::partCacheStats() const {
    return mPartCache ? metrics::partCacheStats(*mPartCache) : metrics::PartCacheStats{};
}

FullRenderEvaluator::FullRenderEvaluator(const ViewSetup& setup, renderer::Renderer& renderer,
                                         const metrics::MetricParameters& parameters)
    : mSetup(setup), mRenderer(renderer), mMetrics(viewOf(setup.reference()), parameters) {}

metrics::MetricResult FullRenderEvaluator::metricsOf(const optimizer::Combination& combination) {
    mRenderer.render(mSetup.toScene(combination), mSetup.camera(), mFrame);
    mMetrics.setCandidate(viewOf(mFrame));  // every pixel, from scratch
    return mMetrics.result();
}

optimizer::Score FullRenderEvaluator::evaluate(const optimizer::Combination& combination) {
    return toScore(metricsOf(combination));
}

metrics::JudgeResult judgeFrame(const renderer::Frame& candidate, const renderer::Frame& reference,
                                const metrics::JudgeParameters& parameters) {
    return metrics::judge(viewOf(candidate), viewOf(reference), parameters);
}

std::vector<optimizer::VariableHints> computeHints(const ViewSetup& setup) {
    const scenes::Scene& scene = setup.scene();
    const scenes::Camera& camera = setup.camera();
    const glm::vec3 viewDirection = glm::normalize(camera.target - camera.position);
    std::vector<optimizer::VariableHints> hints;
    for (int object : setup.variableObjects()) {
        const scenes::Object& sceneObject = scene.objects[object];
        const scenes::Bounds bounds = scenes::worldBounds(sceneObject, 0);
        const glm::vec3 toObject = bounds.sphereCenter - camera.position;
        const double distance = std::max(double(glm::length(toObject)), 1e-6);
        optimizer::VariableHints hint;
        hint.distance = distance;
        const double cosine = glm::dot(glm::normalize(toObject), viewDirection);
        hint.viewAngleRadians = std::min(std::acos(std::clamp(cosine, -1.0, 1.0)), 1.5);
        // Dong et al.'s s: the projected area, here in hundreds of covered pixels at level 0.
        hint.projectedArea = std::max(double(setup.objects()[object].referencePixels) / 100.0, 1e-3);
        hint.screenCoverage = scenes::screenSize(bounds, camera);
        hint.boundingRadius = std::max(double(bounds.sphereRadius), 1e-9);
        // Pixels per world unit at the object's nearest point (its world box; the near plane
        // when the eye is inside), where its deviation shows largest.
        const glm::vec3 nearest = glm::clamp(camera.position, bounds.min, bounds.max);
        const double nearestDistance =
            std::max(double(glm::length(nearest - camera.position)), double(std::max(camera.nearPlane, 1e-6f)));
        const double tanHalfFov = std::tan(glm::radians(double(camera.fovYDegrees)) / 2.0);
        hint.pixelsPerWorldUnit = double(setup.height()) / (2.0 * nearestDistance * tanHalfFov);
        const std::vector<int>& options = setup.objects()[object].optionLevels;
        bool allDeviations = true;
        for (int level : options) allDeviations = allDeviations && sceneObject.levels[level].geometricError.has_value();
        if (allDeviations) {
            for (int level : options) hint.levelDeviation.push_back(double(*sceneObject.levels[level].geometricError));
        }
        bool allCoverage = true;
        for (int level : options) allCoverage = allCoverage && sceneObject.levels[level].screenCoverage.has_value();
        const double triangles0 = double(std::max<std::uint64_t>(sceneObject.levels[0].stats.triangles, 1));
        for (int level : options) {
            const scenes::Level& sceneLevel = sceneObject.levels[level];
            if (allCoverage) hint.levelScreenCoverage.push_back(*sceneLevel.screenCoverage);
            // Geometric error relative to the object's size: meshoptimizer's when the level was
            // generated, else a proxy from the triangle ratio (authored levels carry none).
            double relativeError = sceneLevel.simplificationError;
            if (relativeError <= 0.0 && level > 0) {
                relativeError = 0.25 * (1.0 - std::sqrt(double(sceneLevel.stats.triangles) / triangles0));
            }
            // The object's diameter on screen in pixels is its screen size times the viewport height.
            hint.levelPixelError.push_back(std::max(relativeError, 0.0) * hint.screenCoverage * double(setup.height()));
        }
        hints.push_back(std::move(hint));
    }
    return hints;
}

}  // namespace lodopt::evaluation
