// The rules engines apply for free: each level's geometric error projected to pixels, the level
// chosen where that error stays under a tolerance. They are what a user would compare lodopt
// with, so they are baselines here (docs/optimizer.md "Engine rules"), each with one bias, as
// the engines give one (Godot's lod_bias and mesh_lod_threshold, Unreal's pixel error and
// r.StaticMeshLODDistanceScale):
//
// - pixelerror: the coarsest level whose deviation, seen at the object's nearest point at this
//   view's resolution and field of view, spans at most `pixelError` pixels
//   (hints.levelDeviation x hints.pixelsPerWorldUnit). Godot 4's automatic mesh LOD
//   (mesh_lod_threshold, default 1 px), meshoptimizer's README (deviation x lod factor against
//   the projected size) and Cesium's screen-space error (16 px by default) are this rule.
// - unreal-auto: Unreal's "Auto Compute LOD Screen Size". Level k's screen size is that of the
//   object's bounding sphere seen from the distance at which its deviation spans `pixelError`
//   pixels on a 1920x1080 view with a 90 degree horizontal field of view:
//       viewDistance_k = deviation_k x 960 / pixelError              (UE CalculateViewDistance)
//       S_k = 2 x (0.5 x 1920 / 1080) x R / (viewDistance_k + R)     (UE ComputeBoundsScreenSize)
//   and at run time the object takes the coarsest level k >= 1 with S_k > its screen size
//   (hints.screenCoverage, the same measure), else level 0 (UE ComputeStaticMeshLOD's loop).
//   Unlike pixelerror it ignores this view's resolution and field of view: its assumptions are
//   fixed at import.
//
// Both choose, per variable, the coarsest level whose own threshold the bias reaches, so one
// larger bias never gives a finer level. With `fitBudget` (the default) the bias is the smallest
// at which the whole combination is predicted within the budget: what a user tuning the engine's
// one bias to the budget gets, so the rule is compared with lodopt at equal cost. Without it the
// rule runs at `pixelError` and, when over budget, is lowered as the screensize baseline is.
#pragma once

#include <string_view>
#include <vector>

#include "optimizer/algorithm.hpp"

namespace lodopt::optimizer {

enum class EngineRule { PixelError, UnrealAuto };

struct EngineRuleParameters {
    double pixelError = 1.0;  // > 0, finite, pixels: the tolerance with no bias
    bool fitBudget = true;    // tune the bias to the budget (above) instead of using pixelError
};

// Per variable and level, the pixel error (the rule's bias) from which the rule allows that
// level: 0 for level 0, +infinity for a level the rule never reaches at any bias. Level k is
// used at bias b when it is the coarsest level with threshold <= b. Throws ProblemError naming
// the variable and hint when a needed hint is missing (pixelerror: levelDeviation and
// pixelsPerWorldUnit; unreal-auto: levelDeviation, boundingRadius, screenCoverage).
std::vector<std::vector<double>> engineRuleThresholds(const Problem& problem, EngineRule rule);

// Unreal's automatic screen size of a level: S = 2 (0.5 x 1920 / 1080) R / (deviation x 960 /
// pixelError + R), the size below which the engine draws that level or a coarser one.
//   deviation: >= 0, world units; radius: > 0, world units; pixelError: > 0, pixels.
double unrealAutoScreenSize(double deviation, double radius, double pixelError);

// The screen size (bounding-sphere diameter over the view height, seen from the sphere's centre)
// at or below which a level's deviation spans at most `pixelError` pixels on a viewport
// `viewportHeight` pixels high: 2 R pixelError / (deviation x viewportHeight); +infinity for a
// deviation of 0. The pixelerror rule as a screen-size threshold (the view-independent form
// engines export; the optimizer's rule measures at the object's nearest point instead).
double pixelErrorScreenSize(double deviation, double radius, double pixelError, double viewportHeight);

// The combination the rule gives at bias `pixelError` (> 0) from its thresholds.
Combination engineRuleLevels(const std::vector<std::vector<double>>& thresholds, double pixelError);

class EngineRuleHeuristic final : public Algorithm {
public:
    // Throws std::invalid_argument naming a bad parameter.
    explicit EngineRuleHeuristic(EngineRule rule, EngineRuleParameters parameters = {});
    std::string_view name() const override { return mRule == EngineRule::PixelError ? "pixelerror" : "unreal-auto"; }
    Result run(const Problem& problem, const Termination& termination) const override;

private:
    EngineRule mRule;
    EngineRuleParameters mParameters;
};

}  // namespace lodopt::optimizer
