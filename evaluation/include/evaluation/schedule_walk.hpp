// The real-time scheduler walked along a camera path and measured: what `lodopt schedule` runs.
//
// Per frame, the scheduler decides from the camera alone (no rendering; the decision's wall time
// is recorded). With rendering, the frame is then drawn headless and scored against the
// all-finest reference (and the unscheduled baseline, the distance thresholds' levels, likewise),
// timed as the calibration's clock times a draw (the least or the median of `repeats` draws),
// and the measured time fed back into the scheduler's time model (DONG15 eq. 9).
//
// A walk can be resumed: record() keeps what cannot be recomputed (wall times, measured times,
// fitness) with the predicted time, a hash of the levels and the feedback scale; replay() decides
// the frame again, which restores the switch-control state, and feeds the recorded time back,
// which restores the model's feedback, and throws ReplayMismatch when the decision or the
// feedback differs from the record. Without rendering a resumed walk equals an uninterrupted one.
#pragma once

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "metrics/metrics.hpp"
#include "renderer/renderer.hpp"
#include "scenes/scene.hpp"
#include "scheduler/scheduler.hpp"

namespace lodopt::evaluation {

struct WalkOptions {
    bool render = false;         // draw, time and score every frame; feed the time back
    bool fitness = true;         // with render: score the frame against the reference
    bool baseline = true;        // with render: the unscheduled baseline too
    bool feedback = true;        // with render: correct the time model from measured times
    bool checkFeatures = false;  // predict each decision from exact features as well (slow)
    int repeats = 5;             // timed draws per frame, >= 1: the frame's time is their median
    metrics::MetricParameters metrics;
};

// One walked frame; NaN where not measured.
struct WalkFrame {
    int frame = 0;  // index in the camera path
    double timeSeconds = 0.0;
    double decisionMicroseconds = 0.0;
    double predictedMs = 0.0;
    double finestPredictedMs = 0.0;    // every visible object at level 0
    double baselinePredictedMs = 0.0;  // the distance thresholds' levels
    double exactPredictedMs = NAN;     // checkFeatures
    double measuredMs = NAN;
    double baselineMeasuredMs = NAN;
    double fitness = NAN;
    double baselineFitness = NAN;
    double feedbackScale = 1.0;  // after this frame's feedback
    scheduler::FrameDecision decision;
    std::vector<int> histogram;  // drawn objects per level
};

// What a resumed walk needs of a frame walked earlier.
struct RecordedFrame {
    int frame = 0;
    double decisionMicroseconds = 0.0;
    double measuredMs = NAN;
    double baselineMeasuredMs = NAN;
    double fitness = NAN;
    double baselineFitness = NAN;
    double exactPredictedMs = NAN;
    // Checks of the replay: it must reproduce these exactly.
    double predictedMs = 0.0;
    double feedbackScale = 1.0;
    std::uint64_t levelsHash = 0;
};

// FNV-1a over the levels.
std::uint64_t levelsHash(const scenes::Combination& levels);
RecordedFrame record(const WalkFrame& frame);

class ReplayMismatch : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class ScheduleWalk {
public:
    // `scheduler` decides (its index built for `scene` at the render size); `renderer` draws
    // `scene` at that size and is required when options.render, unused otherwise. All must
    // outlive the walk. Throws std::invalid_argument for a missing renderer or repeats < 1.
    ScheduleWalk(const scenes::Scene& scene, const scenes::CameraPath& path, scheduler::FrameScheduler& scheduler,
                 renderer::Renderer* renderer, WalkOptions options);

    // Decides frame `frame` of the path (frames in increasing order) and measures it.
    WalkFrame walk(int frame);
    // Decides frame `frame` again and takes `recorded`'s measurements; throws ReplayMismatch.
    WalkFrame replay(int frame, const RecordedFrame& recorded);

private:
    WalkFrame decide(int frame);
    void measure(WalkFrame& row);

    const scenes::Scene& mScene;
    const scenes::CameraPath& mPath;
    scheduler::FrameScheduler& mScheduler;
    renderer::Renderer* mRenderer;
    WalkOptions mOptions;
    scenes::Combination mReference, mFinest, mBaseline;
    renderer::Frame mReferenceFrame, mFrame;
};

// How far one frame's measurement scatters here (scheduler/measurement.hpp): the first, middle
// and last walked frames' decisions, each timed `measurements` times back to back as a frame is
// timed. `ceiling` is the mean of the probes' ceilings, NaN when nothing was probed.
struct CeilingProbe {
    int frame = 0;
    int measurements = 0;
    double medianMs = 0.0;
    double p10Ratio = 0.0;  // 10th-percentile time over the median
    double p90Ratio = 0.0;
    double ceiling = 0.0;  // share of the measurements one ±10% band can hold at best
};
struct MeasurementCeiling {
    double tolerance = 0.1;
    double ceiling = NAN;
    std::vector<CeilingProbe> probes;
};
MeasurementCeiling probeMeasurementCeiling(renderer::Renderer& renderer, const scenes::CameraPath& path,
                                           const std::vector<WalkFrame>& frames, int measurements, int repeats);

}  // namespace lodopt::evaluation
