// The real-time LOD scheduler: one decision per frame from the camera alone, no rendering.
//
// Flat organisation (DONG15 §2.4, method.md §5), per frame:
//  1. view-frustum culling (bounding spheres); culled objects are not drawn (kNotDrawn);
//  2. importance I of every visible object (importance.hpp) and its initial level from the
//     distance thresholds (eq. 4);
//  3. predicted time from the time model over the frame's features (scene_index.hpp);
//  4. over the budget: lower objects in increasing importance, each as far as needed, first
//     those with I <= 1, then, only if that was not enough, those with I > 1
//     (FrameDecision::protectedLowered counts the objects with I > 1 left coarser than their
//     initial level); then, and directly when under the budget, raise objects in decreasing
//     importance, each as far toward level 0 as the budget allows (an object whose next step
//     does not fit is passed over). Ours: raising after lowering spends what the last step
//     down left over (one step of a large object can free several milliseconds; on the harbor
//     path without switch control this took the frames predicted within 10% of the budget
//     from 67% to 94%).
// Switch control (switch_control.hpp), default rule Hysteresis (ours, flat only), inside the
// decision, with a previous frame: an object with I <= 1 drawn coarser last frame starts at that
// level; lowering first takes the lowerings that cost no switch (objects entering the view, any
// level; others back to last frame's coarser level), in increasing importance; after the
// DONG15 lowering, objects drawn finer last frame get back to that level (all the way or not
// at all) in decreasing importance within the budget; the free raise then moves an object
// drawn last frame only while the prediction stays within (1 − raiseMargin) of the budget
// (entering objects: the whole budget). Refill: a frame still under (1 − refillBelow) of the
// budget then raises again into the whole budget, switches allowed, and if still under, takes
// the decision without switch control when that is nearer the budget. Nothing is held against
// the budget: no forced switches, no frozen objects.
// Rule Vmi20 (VMI20 §7; tiles always) instead filters the decision: an object drawn in
// the previous frame whose new level the control does not allow gets the allowed level nearest
// to the decision's (its old level while its dwell time runs). If the held objects push the
// prediction over the budget, objects are lowered again in increasing importance (I <= 1
// first), within what the control allows and then beyond it (FrameDecision::forcedSwitches);
// if they leave budget over, objects the decision lowered get back toward their previous
// level, in decreasing importance, as far as it fits (a change avoided, a switch saved), and
// what is still left raises objects in decreasing importance within their allowed ranges
// (ours: otherwise the held objects' share of the budget goes unused).
// Filtering the decision, rather than constraining the loops, keeps the control from creating
// changes: constrained loops hand a held object's share of the budget to its neighbours, which
// then swap back and forth frame after frame (measured on the forest walk: four times the
// switches of no control at all).
// After the frame is rendered, reportMeasuredMs() feeds the measured time back into the time
// model (DONG15 eq. 9, bounded: timemodel::FeedbackParameters).
//
// Tile organisation (CITY17 Algorithms 1-2, method.md §6), for large scenes:
//  1. a quadtree of tiles (tiles.hpp) is culled against the frustum, visible leaves walked
//     nearest first, objects within a leaf in decreasing importance;
//  2. Algorithm 1: objects join the frame at their coarsest level while the predicted
//     time stays within the budget; the rest are not drawn (FrameDecision::droppedObjects).
//     CITY17 keeps separate CPU and GPU budgets; our time model already combines the two
//     (wimmer: RT_sys + max(RT_cpu, RT_gpu); linear: their sum), so one predicted-time budget
//     stands for both;
//  3. Algorithm 2: each drawn object in that order is raised toward its distance level; when a
//     step does not fit, either it stops there ("lower the level") or the last N drawn objects
//     are dropped to make room, whichever loses fewer pixels: stopping loses the object's
//     projected pixels times the step's simplification-rate difference, dropping loses the
//     dropped objects' projected pixels. Once `coarsestShare` (20%) of the drawn objects sit
//     at their coarsest level, the rest stay where Algorithm 1 put them. Ours: an object counts
//     toward the 20% only when the budget kept it at its coarsest level (its distance level is
//     finer); counting objects whose distance level is the coarsest anyway would end the
//     raising after the first far tiles with most of the budget unused.
// A decision allocates nothing once the scheduler has seen a frame (Bounds features).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scenes/scene.hpp"
#include "scheduler/importance.hpp"
#include "scheduler/scene_index.hpp"
#include "scheduler/switch_control.hpp"
#include "scheduler/tiles.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::scheduler {

enum class Organisation { Flat, Tiles };
// "flat", "tiles".
const char* toString(Organisation organisation);

// B of eq. 12: a fixed benchmark object (DONG15), or, unset, `scale` times the median
// denominator of the frame's visible objects (as the optimizer's importance baseline does with
// scale 1), so that about half of them are protected.
struct Benchmark {
    std::optional<ObjectView> view;
    double scale = 1.0;  // > 0, finite; used when `view` is unset
};

// What tuning fits and a coefficients file holds.
struct SchedulerCoefficients {
    ImportanceCoefficients importance;
    Benchmark benchmark;
    DistanceThresholds thresholds;
};

struct SchedulerParameters {
    double budgetMs = 33.0;  // > 0, finite: milliseconds of predicted render time per frame
    SchedulerCoefficients coefficients;
    std::vector<double> objectWeights;      // empty, or one finite weight > 0 per object (w of I)
    bool protectImportant = true;           // DONG15: objects with I > 1 are lowered last
    SwitchControlParameters switchControl;  // Tiles: the Vmi20 rule whatever `rule` says
    timemodel::FeedbackParameters feedback;
    Organisation organisation = Organisation::Flat;
    QuadtreeParameters quadtree;
    double coarsestShare = 0.2;  // (0, 1]: CITY17's share of coarsest objects that ends Algorithm 2
};

// Throws std::invalid_argument naming the first bad parameter; `objectCount` for the weights.
void validateParameters(const SchedulerParameters& parameters, int objectCount);

struct FrameDecision {
    scenes::Combination levels;    // one per object; kNotDrawn = culled or dropped
    double predictedMs = 0.0;      // the time model's prediction for `levels`
    double minimumMs = 0.0;        // prediction with every visible object at its coarsest level
    bool budgetReachable = false;  // minimumMs <= budget: reachable without dropping objects
    bool budgetMet = false;        // predictedMs <= budget
    int visibleObjects = 0;        // passed culling
    int culledObjects = 0;
    int droppedObjects = 0;             // visible but not drawn (tiles only)
    int protectedLowered = 0;           // objects with I > 1 left coarser than their initial level
    int forcedSwitches = 0;             // level changes against the switch control, for the budget
    int switches = 0;                   // objects drawn in both frames whose level changed
    int heldObjects = 0;                // objects the switch control kept at their level this frame
    timemodel::FrameFeatures features;  // of `levels`, for the feedback
};

class FrameScheduler {
public:
    // `index` (built for the scene and render size) must outlive the scheduler; `model` fitted.
    // Throws std::invalid_argument for bad parameters, or when `model` reads a feature that
    // `index` was built without (SceneIndex's `needed`).
    FrameScheduler(const SceneIndex& index, std::unique_ptr<timemodel::TimeModel> model,
                   SchedulerParameters parameters);
    ~FrameScheduler();

    // The decision for the frame seen from `camera` at path time `timeSeconds` (non-decreasing
    // between calls unless reset()). Valid until the next call.
    const FrameDecision& decide(const scenes::Camera& camera, double timeSeconds);
    // DONG15 eq. 9 for the last decision's features; an unusable time is ignored and reported.
    timemodel::FeedbackResult reportMeasuredMs(double measuredMs);
    // Forgets the previous frame (levels and switch times); keeps the model's feedback.
    void reset();

    void setCoefficients(const SchedulerCoefficients& coefficients);  // throws like the constructor
    void setBudgetMs(double budgetMs);                                // > 0, finite
    const SchedulerParameters& parameters() const { return mParameters; }
    const timemodel::TimeModel& model() const { return *mModel; }
    const SceneIndex& index() const { return mIndex; }

    // Of the last frame, per object: importance (0 when not visible), the distance-threshold
    // level of eq. 4 (kNotDrawn when not visible: the unscheduled baseline), and the observed
    // views and features.
    const std::vector<double>& importances() const { return mImportance; }
    const scenes::Combination& initialLevels() const { return mInitial; }
    const FrameObjects& frame() const { return mFrame; }

private:
    struct Work;
    void observeFlat();
    void observeTiles();
    void computeImportanceAndRanges(double timeSeconds);
    void decideFlat();
    // The flat decision (DONG15 lowering and raising), with the hysteresis passes or without.
    void decideFlatLevels(bool hysteresis);
    void exchangeTowardBudget(double bandFloor);
    void decideTiles();
    void applySwitchControl();
    // After the control's filter left budget over: raises objects in decreasing importance
    // (Work::order), each toward the finest level its range allows, while the prediction fits.
    void raiseWithinRange();
    // Raises `object` one level at a time toward `finest` while the prediction fits `budgetMs`.
    void raiseWhileFits(int object, int finest, double budgetMs);
    // Hysteresis rule, before the free raise: objects drawn finer last frame get back to that
    // level (all the way or not at all) in decreasing importance (Work::order, sorted by the
    // caller) where the whole budget allows.
    void restorePreviousLevels();
    // Sorts the visible objects into Work::order by importance (ties by index).
    void sortByImportance(bool increasing);
    // How far lowerToBudget may take an object: its coarsest level; its switch-control limit
    // (VMI20 filter); or, for the hysteresis rule before the DONG15 lowering, only as far as
    // it costs no switch (an object entering the view to any level, one drawn coarser last
    // frame back to that level), and objects with I <= 1 only.
    enum class LowerLimit { Coarsest, SwitchRange, WithoutSwitch };
    // Lowers objects in Work::order (I <= 1 first when protecting) until the prediction fits,
    // each at most to `limit`.
    double lowerToBudget(double ms, LowerLimit limit);
    void finishFrame(double timeSeconds);
    double estimate(const timemodel::FrameFeatures& features) const { return mModel->estimateMs(features); }
    const timemodel::FrameFeatures& contribution(int object, int level) const;
    // Moves `object` to `level` in the decision, keeping its features and prediction current.
    void setLevel(int object, int level);

    const SceneIndex& mIndex;
    std::unique_ptr<timemodel::TimeModel> mModel;
    SchedulerParameters mParameters;
    std::unique_ptr<Quadtree> mQuadtree;
    SwitchControlParameters mFilterControl;  // the VMI20 filter: enabled for Vmi20 or tiles
    FrameObjects mFrame;
    FrameDecision mDecision;
    std::vector<double> mImportance;
    scenes::Combination mInitial;
    scenes::Combination mPrevious;        // last frame's levels (kNotDrawn when not drawn)
    std::vector<double> mLastSwitchTime;  // per object, path seconds
    std::vector<LevelRange> mRange;       // this frame's allowed levels per visible object
    std::unique_ptr<Work> mWork;          // scratch buffers
    bool mHavePrevious = false;
};

}  // namespace lodopt::scheduler
