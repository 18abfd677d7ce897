// Evaluation: joins the renderer, the metrics and the time model behind the optimizer's
// Evaluator and Cost interfaces, for one scene, one viewpoint and one image size.
//
// Preparation (ViewSetup), once per view:
//  1. render the reference (every object at level 0) and every level of every object as a
//     layer (color + depth, cropped to its covered pixels);
//  2. skip what the view does not need: an object none of whose levels covers a pixel (outside
//     the frustum, or smaller than a pixel) or whose every level is hidden behind the other
//     objects' level-0 depth is fixed at its coarsest level and left out of the search; levels
//     whose layer is bit-identical to the next coarser level's are merged into that coarser
//     (cheaper) level;
//  3. the remaining objects become the optimizer's variables; variable i's option j is the
//     scene level optionLevels[i][j] (option 0 the finest distinct level).
//
// Fast path (LayerEvaluator, the default): a candidate is composited from the layers, only
// where an object whose level changed since the state's previous candidate covers pixels (per
// row, its old and new layers' covered columns), and the metrics are updated incrementally only
// around the pixels whose color actually changed (tight rectangles per band of rows, merged
// where one update is cheaper). Several states, each left at the last candidate it evaluated,
// serve the candidates nearest to them, and make batches parallel; because the incremental
// metrics equal a from-scratch computation to the bit, the scores do not depend on which
// state evaluates a candidate, the order or the thread count.
// Full path (FullRenderEvaluator, `--eval full`): render the whole combination with OpenGL
// and compute the metrics from scratch over the whole image; serial (one GL context). The
// metric buffers are kept between candidates (IncrementalEvaluator::setCandidate, the same
// bits as metrics::evaluate): allocating them per candidate cost more than the metrics here.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "metrics/incremental_evaluator.hpp"
#include "metrics/judge.hpp"
#include "metrics/metrics.hpp"
#include "metrics/region_scorer.hpp"
#include "optimizer/problem.hpp"
#include "renderer/renderer.hpp"
#include "scenes/scene.hpp"

namespace lodopt::evaluation {

// Why an object is not searched.
enum class SkipReason { None, OutsideFrustum, BelowOnePixel, Hidden };
const char* toString(SkipReason reason);

struct ObjectSetup {
    SkipReason skip = SkipReason::None;
    int fixedLevel = 0;               // the level used when skipped (the coarsest)
    std::vector<int> optionLevels;    // scene levels searched, finest first (empty when skipped)
    int mergedLevels = 0;             // levels merged into a coarser identical one
    std::uint64_t referencePixels = 0;  // pixels covered by level 0 alone
};

struct SkipSummary {
    int searchedObjects = 0;
    int outsideFrustum = 0;
    int belowOnePixel = 0;
    int hidden = 0;
    int mergedLevels = 0;
};

// The prepared view: reference image, layers and the variable mapping.
class ViewSetup {
public:
    // Renders the reference and all layers with `renderer` (which must draw `scene`).
    ViewSetup(const scenes::Scene& scene, const scenes::Camera& camera, renderer::Renderer& renderer);

    const scenes::Scene& scene() const { return mScene; }
    const scenes::Camera& camera() const { return mCamera; }
    const renderer::Frame& reference() const { return mReference; }
    int width() const { return mReference.width; }
    int height() const { return mReference.height; }
    glm::vec4 clearColor() const { return mClearColor; }

    const std::vector<ObjectSetup>& objects() const { return mObjects; }
    const SkipSummary& skipSummary() const { return mSkip; }
    // Scene object index of each optimizer variable.
    const std::vector<int>& variableObjects() const { return mVariableObjects; }
    // Options per variable (optimizer::Problem::levelCounts).
    std::vector<int> levelCounts() const;
    // The scene combination of an optimizer combination (skipped objects at their fixed level).
    scenes::Combination toScene(const optimizer::Combination& combination) const;
    // The optimizer combination closest to a scene combination (each variable's option whose
    // level is the smallest >= the scene level; the coarsest option otherwise).
    optimizer::Combination fromScene(const scenes::Combination& combination) const;
    // The layer of object `object` at scene level `level`.
    const renderer::Layer& layer(int object, int level) const { return mLayers[object][level]; }
    // Its covered columns per row of layer(object, level).rect (renderer::coveredRowSpans).
    const std::vector<renderer::RowSpan>& coverage(int object, int level) const {
        return mLayers[object][level].rowSpans;
    }

    double setupSeconds() const { return mSetupSeconds; }

private:
    const scenes::Scene& mScene;
    scenes::Camera mCamera;
    glm::vec4 mClearColor;
    renderer::Frame mReference;
    std::vector<std::vector<renderer::Layer>> mLayers;  // [object][level]
    std::vector<ObjectSetup> mObjects;
    std::vector<int> mVariableObjects;
    SkipSummary mSkip;
    double mSetupSeconds = 0.0;
};

// What a search needs of the metrics: `parameters` without precision/recall. Those are
// reported, never fused into the fitness, and cost about a sixth of the fast path's time
// (forest `dense` walk at 512²: 387 against 323 µs, evaluation_bench); an answer's full
// metrics come from a FullRenderEvaluator built with the user's parameters.
metrics::MetricParameters searchParameters(metrics::MetricParameters parameters);

// Names of the score components the evaluators report, in Score::components order: the three
// fidelities, then precision and recall when `precisionRecall`.
std::vector<std::string> componentNames(bool precisionRecall = true);
// A metrics result as an optimizer score (fitness + ssim, boundary and information
// fidelities, then precision and recall when they were computed).
optimizer::Score toScore(const metrics::MetricResult& result);

// Where the fast path updates the metrics after a level change. Both give identical scores.
enum class DirtyRegions {
    ChangedPixels,  // tight rectangles around the pixels whose color changed (default)
    ObjectBounds,   // the changed objects' whole bounding rectangles: the earlier way, kept to measure against
};

// The fast path. It keeps `states` >= `threads` evaluation states (each the last candidate it
// evaluated: composite + incremental metrics, about 48 bytes per pixel, the metrics' ~40 of
// incremental_evaluator.hpp and the frame's 8) and gives each candidate to the state that needs
// the least recompositing (nearestState): a swarm revisits the neighbourhoods of several
// particles, and a state left near one of them makes the next move there cheap. A batch is
// spread over up to `threads` threads, each state used by one thread at a time.
//
// How the fast path scores a candidate (ChangedPixels only; docs/optimizer.md):
// - Auto (the default): Groups where a level step of a searched object changes, on average,
//   at least kMinStepPixelsPerGroup pixels per group of the view's groups per searched object
//   (meanLevelStepPixels(setup) >= kMinStepPixelsPerGroup * groups / searched objects), else
//   On. Each group a move touches costs a lookup, or on a miss a score over the whole group,
//   while On works only around the pixels that changed; so groups pay where moves change many
//   pixels and the view has few groups per object (forest `dense`, `sparse`, `edge`, city
//   `street`, the harbor), and On where objects are small and their seams meet in many
//   combinations (forest `overview`, city `avenue`, `aerial`, `skyline`; docs/optimizer.md).
// - Groups: every metric window depends on the levels of the searched objects whose layers
//   can show at its pixels (cover them, and are not behind an object that covers them at
//   every level it can take: detail::VisibilityBounds); windows with the same objects form a
//   group, and a group's
//   score (its SSIM windows' exact sum and its histogram counts) is kept per combination of
//   those objects' levels, shared by all states. A candidate re-scores only the groups of the
//   objects that moved: a kept score is a lookup, a new one composites and scores just the
//   pixels that group reads. Needs a fitness made of window sums (metrics::RegionScorer::
//   supports: histogram entropies, no precision/recall); otherwise the evaluator uses On.
// - On: owned windows. A pixel where only one object's levels can ever show depends on that
//   object's level alone, and so does every metric window made only of such pixels (and of
//   pixels where no searched object can show). Those windows are scored once per (object, level) and
//   copied in when the object moves to that level; windows where two searched objects' levels
//   meet are computed per candidate, on the recomposited frame.
// - Off: every changed pixel's windows are computed per candidate.
// Scores are the same, bit for bit, whichever is used.
enum class PartCaching { Auto, Groups, On, Off };

// The mean, over the searched objects and each pair of consecutive option levels of theirs, of
// the pixels whose color or coverage differs between the two levels' layers: how many pixels a
// one-step level change of one object touches (PartCaching::Auto's measure of a move's size).
// 0 when no object has two options.
double meanLevelStepPixels(const ViewSetup& setup);

// The window groups' figures (zeros without them).
struct GroupCacheStats {
    int groups = 0;
    int largestGroup = 0;        // most searched objects one group depends on
    int uncacheableGroups = 0;   // groups whose key does not fit 64 bits (scored every time)
    std::uint64_t ssimWindows = 0, multiObjectSsimWindows = 0;  // the latter in groups of 2+ objects
    std::uint64_t entries = 0, bytes = 0;  // kept scores and their memory
    std::uint64_t hits = 0, misses = 0;    // group look-ups answered from kept scores, and not
};

namespace detail {
class WindowGroups;
class GroupState;
}  // namespace detail

class LayerEvaluator final : public optimizer::Evaluator {
public:
    static constexpr int kDefaultStates = 4;
    // Memory the window groups keep scores in, at most: beyond it new scores are still
    // computed and used, but not kept.
    static constexpr std::size_t kGroupCacheBytes = std::size_t(256) << 20;
    // PartCaching::Auto's threshold (measured on the forest's and city's views at 512²: 298 or
    // more where groups were faster, 127 or less where owned windows were; docs/optimizer.md).
    static constexpr double kMinStepPixelsPerGroup = 200.0;
    LayerEvaluator(const ViewSetup& setup, const metrics::MetricParameters& parameters, int threads = 1,
                   DirtyRegions regions = DirtyRegions::ChangedPixels, int states = kDefaultStates,
                   PartCaching caching = PartCaching::Auto, std::size_t groupCacheBytes = kGroupCacheBytes);
    ~LayerEvaluator() override;

    optimizer::Score evaluate(const optimizer::Combination& combination) override;
    void evaluateBatch(std::span<const optimizer::Combination> combinations,
                       std::span<optimizer::Score> scores) override;
    std::vector<std::string> componentNames() const override {
        return evaluation::componentNames(mParameters.computePrecisionRecall);
    }

    // Metrics of a combination (every component its parameters compute), through state 0.
    metrics::MetricResult metricsOf(const optimizer::Combination& combination);
    // The composited image of a combination.
    renderer::Frame imageOf(const optimizer::Combination& combination);
    // The owned-window cache's figures (zeros without one).
    metrics::PartCacheStats partCacheStats() const;
    // The window groups' figures (zeros without them).
    GroupCacheStats groupCacheStats() const;

private:
    struct State;
    // The combination state `state` will hold once the candidates of `batch` assigned to it so
    // far are evaluated (its current one when none is).
    const optimizer::Combination& planned(std::size_t state, std::span<const optimizer::Combination> batch) const;
    // Index of the state cheapest to move to `combination` among those with fewer than `cap`
    // candidates assigned (lowest index on ties).
    std::size_t nearestState(const optimizer::Combination& combination, std::span<const optimizer::Combination> batch,
                             std::size_t cap) const;
    const ViewSetup& mSetup;
    metrics::MetricParameters mParameters;
    int mThreads = 1;
    std::vector<std::unique_ptr<State>> mStates;
    std::vector<std::vector<std::uint64_t>> mOptionPixels;  // [variable][option] covered pixels
    std::shared_ptr<metrics::PartCache> mPartCache;  // null without PartCaching::On
    // PartCaching::Groups: the scorer, the groups and their states (then mStates is empty).
    std::unique_ptr<metrics::RegionScorer> mScorer;
    std::unique_ptr<detail::WindowGroups> mGroups;
    std::vector<std::unique_ptr<detail::GroupState>> mGroupStates;
    std::size_t stateCount() const;
    const optimizer::Combination& currentOf(std::size_t state) const;
    void moveState(std::size_t state, const optimizer::Combination& combination);
    metrics::MetricResult resultOf(std::size_t state) const;
    // evaluateBatch's working lists, empty between calls (kept to avoid allocating per batch):
    std::vector<std::vector<std::size_t>> mAssigned;  // per state, its candidates in batch order
    std::vector<std::size_t> mBusy;                   // states with candidates
};

// The full path: renders every candidate and scores it from scratch.
class FullRenderEvaluator final : public optimizer::Evaluator {
public:
    FullRenderEvaluator(const ViewSetup& setup, renderer::Renderer& renderer,
                        const metrics::MetricParameters& parameters);
    optimizer::Score evaluate(const optimizer::Combination& combination) override;
    std::vector<std::string> componentNames() const override {
        return evaluation::componentNames(mMetrics.parameters().computePrecisionRecall);
    }
    metrics::MetricResult metricsOf(const optimizer::Combination& combination);

private:
    const ViewSetup& mSetup;
    renderer::Renderer& mRenderer;
    renderer::Frame mFrame;
    metrics::IncrementalEvaluator mMetrics;  // reused: setCandidate recomputes every pixel
};

// The judge's verdict on a rendered answer against the view's reference (metrics::judge):
// what every command reports beside the fused fitness, and what no search reads.
metrics::JudgeResult judgeFrame(const renderer::Frame& candidate, const renderer::Frame& reference,
                                const metrics::JudgeParameters& parameters);

// Plain-number hints for the distance, importance and screen-size baselines.
std::vector<optimizer::VariableHints> computeHints(const ViewSetup& setup);

}  // namespace lodopt::evaluation
