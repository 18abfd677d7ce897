// Engine LOD switch rules compared at equal cost: the thresholds `lodopt thresholds` fits against
// the rules engines fall back to, each with one global LOD bias, on views held out of the fit.
//
// A rule gives each scene object screen-size thresholds (scheduler::levelForScreenSize). With a
// global bias b (Unity's QualitySettings.lodBias; Unreal's r.StaticMeshLODDistanceScale is 1/b)
// an object of screen size s draws the level the rule gives at s * b: b > 1 keeps finer levels
// longer. At a view the rule draws the objects the view needs (the sweep's searched objects);
// the others (outside the frustum, below a pixel, hidden) are drawn coarsest, as the optimizer's
// answer draws them, so the two differ only where the optimizer chose.
//
// The bias of a rule is the largest b whose mean predicted frame time over the fitting views is
// within the budget (fitLodBias): the mean is a non-decreasing step function of b (finer levels
// cost more), changing only where s * b crosses a threshold, so a binary search over those
// crossings finds it exactly. The comparison (compareSwitchRules) then renders every held-out
// view's rule combinations, scores them against the reference like the optimizer's answer, and
// reports per rule the mean fitness, the gain fraction and the share of held-out views predicted
// over the budget. The gain fraction is the rule's fitness above the all-coarsest combination's
// over the optimizer's above it, averaged over the views weighted by the optimizer's gain there:
// sum (F_rule - F_coarsest) / sum (F_optimizer - F_coarsest) over the views where the optimizer
// gains more than kMinOptimizerGain. Unweighted, a view where the optimizer gains 1e-4 (an object
// at a few pixels) turns any rule's small gain there into a ratio of noise that swamps the mean;
// on the harbor's 48-view sweep the unweighted mean was 1.67 for a rule below the optimizer on
// mean fitness. A rule over the budget on a view can gain more than the optimizer there.
// docs/thresholds.md.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "evaluation/engine_thresholds.hpp"
#include "evaluation/time_cost.hpp"
#include "metrics/metrics.hpp"
#include "renderer/renderer.hpp"
#include "scenes/scene.hpp"
#include "timemodel/features.hpp"

namespace lodopt::evaluation {

// Per scene object, its screen-size thresholds (levels - 1 values, non-increasing).
using ObjectThresholdList = std::vector<std::vector<double>>;

struct SwitchRuleThresholds {
    std::string name;
    ObjectThresholdList thresholds;
};

// The rules engines use when nobody tuned them, as screen sizes per object of `scene`:
//   file               the scene's own Level::screenCoverage (a glTF's MSFT_screencoverage), when
//                      every object with levels has them; left out otherwise
//   msft_default       Microsoft glTF-Toolkit's published 0.5, 0.2, 0.01, read as UnityGLTF reads
//                      MSFT_screencoverage (Unity relative heights)
//   unitygltf_halving  UnityGLTF's fallback, Unity relative heights 0.5, 0.25, 0.125, ...
//   unreal_075         Unreal-style screen sizes 0.75, 0.75², ...
//   pixelerror         the engines' automatic geometric-error rule (Godot 4's mesh LOD threshold,
//                      1 px; optimizer/engine_rules.hpp): level k from the screen size at which its
//                      measured deviation spans 1 pixel on a viewport `viewportHeight` pixels high
//   unreal_auto        Unreal's Auto Compute LOD Screen Size from each level's deviation (1 px on
//                      1920x1080, 90 degrees)
// The last two need every level's Level::geometricError (scenes::computeGeometricErrors) and are
// left out without them (or with viewportHeight 0). A level a coarser one may replace at a larger
// size is drawn coarser there too, as the engines' loops do: each threshold is the largest of the
// coarser levels' own sizes. Lists shorter than an object's switches continue with their last
// ratio.
std::vector<SwitchRuleThresholds> defaultSwitchRules(const scenes::Scene& scene, int viewportHeight = 0);

// The combination the rule draws at `view` under `bias` (see above).
scenes::Combination ruleCombination(const scenes::Scene& scene, const ObjectThresholdList& thresholds,
                                    const ViewChoices& view, double bias);

// Predicted milliseconds of a combination at views[view].
using ViewTimeMs = std::function<double(std::size_t view, const scenes::Combination& combination)>;

struct LodBias {
    double bias = 1.0;
    double meanPredictedMs = 0.0;  // over the views, at `bias`
    bool meetsBudget = false;      // false: even the smallest bias is over the budget on average
};
// The largest bias whose mean predicted time over `views` is <= budgetMs (see above); without
// any, the bias that draws every needed object coarsest. A rule that stays within the budget
// drawing every needed object at level 0 gets the smallest bias that does so.
// Throws std::invalid_argument for an empty `views` or a budget that is not positive.
LodBias fitLodBias(const scenes::Scene& scene, const ObjectThresholdList& thresholds, std::span<const ViewChoices> views,
                   const ViewTimeMs& predictMs, double budgetMs);

// Views where the optimizer's answer beats the all-coarsest combination by no more than this have
// no gain to share out and are left out of the gain fraction.
constexpr double kMinOptimizerGain = 1e-6;

// Level switches a rule makes along a camera path, as THREE.LOD.update makes them with a
// hysteresis h on every level: an object at level c goes finer only once its screen size reaches
// t_(c-1) / (1 - h) (three.js lowers the current level's switch distance by h), coarser as soon as
// it falls below a threshold. Every object with levels counts, wherever it is (three.js switches
// objects out of view too). h in [0, 1).
struct RuleSwitches {
    long long switches = 0;      // level changes between consecutive frames, summed over objects
    long long objectFrames = 0;  // objects with levels x (frames - 1)
};
RuleSwitches countRuleSwitches(const scenes::Scene& scene, const ObjectThresholdList& thresholds,
                               std::span<const scenes::Camera> path, double hysteresis);

struct RuleOutcome {
    std::string rule;
    LodBias bias;                 // fitted on the fitting views
    double meanFitness = 0.0;     // held-out views
    double gainFraction = 0.0;    // held-out views, weighted by the optimizer's gain (see above)
    double overBudgetShare = 0.0; // held-out views predicted over the budget
    double meanPredictedMs = 0.0; // held-out views
};

struct RuleComparison {
    int fittingViews = 0;
    int heldOutViews = 0;
    int gainViews = 0;                 // held-out views counted in the gain fraction
    double optimizerMeanFitness = 0.0; // the optimizer's answers on the held-out views
    double coarsestMeanFitness = 0.0;  // every object at its coarsest level
    std::vector<RuleOutcome> rules;    // in the order given
};

// A sweep's view as the comparison needs it: the choices, the camera, the answer's fitness.
struct ScoredView {
    ViewChoices choices;
    scenes::Camera camera;
    double fitness = 0.0;
};

struct RuleComparisonSettings {
    double budgetMs = 0.0;  // > 0
    int holdoutEvery = 4;   // the split of fitEngineThresholds; 0: none held out (biases only)
    int width = 512;        // the sweep's image size
    int height = 512;
};

// `renderer` draws `scene` at the
// sweep's settings, `metrics` are the sweep's, `estimator` its time model (reading only
// `readFeatures`). Without held-out views only the biases are filled (the rest NaN). Throws
// std::invalid_argument when there is no fitting view.
RuleComparison compareSwitchRules(const scenes::Scene& scene, std::span<const ScoredView> views,
                                  std::span<const SwitchRuleThresholds> rules, renderer::Renderer& renderer,
                                  const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                                  const timemodel::FeatureSet& readFeatures, const RuleComparisonSettings& settings);

}  // namespace lodopt::evaluation
