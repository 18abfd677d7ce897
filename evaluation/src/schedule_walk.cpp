#include "evaluation/schedule_walk.hpp"

#include <algorithm>
#include <chrono>
#include <string>

#include "scheduler/measurement.hpp"
#include "timemodel/features.hpp"
#include "timemodel/timing.hpp"

namespace lodopt::evaluation {

namespace {

// Fused fitness of `frame` against `reference` (both RGBA renders of one size).
double fitnessOf(const renderer::Frame& frame, const renderer::Frame& reference, const metrics::MetricParameters& p) {
    const metrics::ImageView candidate = metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4);
    const metrics::ImageView truth =
        metrics::makeImageView(reference.rgba.data(), reference.width, reference.height, 4);
    return metrics::evaluate(candidate, truth, p).fitness;
}

// Predicted ms of `levels` in the scheduler's last frame (every drawn object visible in it),
// with the scheduler's current model.
double predictInLastFrame(const scheduler::FrameScheduler& s, const scenes::Combination& levels) {
    const scheduler::SceneIndex& index = s.index();
    timemodel::FrameFeatures features = index.frameConstant();
    for (int o = 0; o < index.objectCount(); ++o) {
        if (levels[std::size_t(o)] == scenes::kNotDrawn) continue;
        features += s.frame().contributions[std::size_t(index.firstLevel(o) + levels[std::size_t(o)])];
    }
    return s.model().estimateMs(features);
}

// Every visible object of the scheduler's last frame at level 0, the others not drawn.
void finestVisible(const scheduler::FrameScheduler& s, scenes::Combination& levels) {
    levels.assign(std::size_t(s.index().objectCount()), scenes::kNotDrawn);
    for (std::size_t o = 0; o < levels.size(); ++o) {
        if (s.frame().visible[o]) levels[o] = 0;
    }
}

}  // namespace

std::uint64_t levelsHash(const scenes::Combination& levels) {
    std::uint64_t hash = 14695981039346656037ull;
    for (int level : levels) {
        hash ^= std::uint64_t(std::uint32_t(level));
        hash *= 1099511628211ull;
    }
    return hash;
}

RecordedFrame record(const WalkFrame& f) {
    return {f.frame,       f.decisionMicroseconds, f.measuredMs,    f.baselineMeasuredMs,
            f.fitness,     f.baselineFitness,      f.exactPredictedMs, f.predictedMs,
            f.feedbackScale, levelsHash(f.decision.levels)};
}

ScheduleWalk::ScheduleWalk(const scenes::Scene& scene, const scenes::CameraPath& path,
                           scheduler::FrameScheduler& scheduler, renderer::Renderer* renderer, WalkOptions options)
    : mScene(scene),
      mPath(path),
      mScheduler(scheduler),
      mRenderer(renderer),
      mOptions(options),
      mReference(scenes::referenceCombination(scene)) {
    if (mOptions.render && !mRenderer) throw std::invalid_argument("ScheduleWalk: rendering needs a renderer");
    if (mOptions.repeats < 1) throw std::invalid_argument("ScheduleWalk: repeats must be >= 1");
}

WalkFrame ScheduleWalk::decide(int frame) {
    const scenes::Camera& camera = mPath.frames.at(std::size_t(frame));
    WalkFrame row;
    row.frame = frame;
    row.timeSeconds = double(frame) / double(mPath.framesPerSecond);
    const auto start = std::chrono::steady_clock::now();
    const scheduler::FrameDecision& decision = mScheduler.decide(camera, row.timeSeconds);
    row.decisionMicroseconds =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    row.decision = decision;
    row.predictedMs = decision.predictedMs;
    finestVisible(mScheduler, mFinest);
    row.finestPredictedMs = predictInLastFrame(mScheduler, mFinest);
    mBaseline = mScheduler.initialLevels();
    row.baselinePredictedMs = predictInLastFrame(mScheduler, mBaseline);
    row.histogram.assign(std::size_t(mScheduler.index().maxLevelCount()), 0);
    for (int level : decision.levels) {
        if (level != scenes::kNotDrawn) ++row.histogram[std::size_t(level)];
    }
    return row;
}

void ScheduleWalk::measure(WalkFrame& row) {
    const scenes::Camera& camera = mPath.frames[std::size_t(row.frame)];
    if (mOptions.checkFeatures) {
        // The same levels with the time model's exact features (walks the geometry).
        const scheduler::SceneIndex& index = mScheduler.index();
        const timemodel::FeatureTable table(mScene, camera, index.width(), index.height());
        row.exactPredictedMs = mScheduler.model().estimateMs(table.features(row.decision.levels));
    }
    if (mOptions.render) {
        if (mOptions.fitness) {
            mRenderer->render(mReference, camera, mReferenceFrame);
            mRenderer->render(row.decision.levels, camera, mFrame);
            row.fitness = fitnessOf(mFrame, mReferenceFrame, mOptions.metrics);
            if (mOptions.baseline) {
                mRenderer->render(mBaseline, camera, mFrame);
                row.baselineFitness = fitnessOf(mFrame, mReferenceFrame, mOptions.metrics);
            }
        }
        row.measuredMs = mRenderer->timeFrames(row.decision.levels, camera, mOptions.repeats, 1).median();
        if (mOptions.baseline) row.baselineMeasuredMs = mRenderer->timeFrames(mBaseline, camera, mOptions.repeats, 1).median();
        if (mOptions.feedback) mScheduler.reportMeasuredMs(row.measuredMs);
    }
    row.feedbackScale = mScheduler.model().feedbackScale();
}

WalkFrame ScheduleWalk::walk(int frame) {
    WalkFrame row = decide(frame);
    measure(row);
    return row;
}

WalkFrame ScheduleWalk::replay(int frame, const RecordedFrame& recorded) {
    WalkFrame row = decide(frame);
    if (recorded.frame != frame || recorded.predictedMs != row.predictedMs ||
        recorded.levelsHash != levelsHash(row.decision.levels)) {
        throw ReplayMismatch("frame " + std::to_string(frame) + " does not replay to the recorded decision");
    }
    row.decisionMicroseconds = recorded.decisionMicroseconds;
    row.exactPredictedMs = recorded.exactPredictedMs;
    row.measuredMs = recorded.measuredMs;
    row.baselineMeasuredMs = recorded.baselineMeasuredMs;
    row.fitness = recorded.fitness;
    row.baselineFitness = recorded.baselineFitness;
    if (mOptions.render && mOptions.feedback) mScheduler.reportMeasuredMs(row.measuredMs);
    row.feedbackScale = mScheduler.model().feedbackScale();
    if (row.feedbackScale != recorded.feedbackScale) {
        throw ReplayMismatch("frame " + std::to_string(frame) + " replays to another feedback scale");
    }
    return row;
}

MeasurementCeiling probeMeasurementCeiling(renderer::Renderer& renderer, const scenes::CameraPath& path,
                                           const std::vector<WalkFrame>& frames, int measurements, int repeats) {
    MeasurementCeiling result;
    if (frames.empty() || measurements <= 0) return result;
    std::vector<std::size_t> probed = {0};
    if (frames.size() > 2) probed.push_back(frames.size() / 2);
    if (frames.size() > 1) probed.push_back(frames.size() - 1);
    double sum = 0.0;
    for (std::size_t r : probed) {
        const scenes::Camera& camera = path.frames[std::size_t(frames[r].frame)];
        std::vector<double> times;
        for (int k = 0; k < measurements; ++k) {
            times.push_back(renderer.timeFrames(frames[r].decision.levels, camera, repeats, 1).median());
        }
        CeilingProbe probe;
        probe.frame = frames[r].frame;
        probe.measurements = measurements;
        probe.ceiling = scheduler::bandCeiling(times, result.tolerance);
        probe.medianMs = timemodel::median(times);
        std::sort(times.begin(), times.end());
        const std::size_t n = times.size();
        auto ratioAt = [&](double q) { return times[std::size_t(q * double(n - 1) + 0.5)] / probe.medianMs; };
        probe.p10Ratio = ratioAt(0.1);
        probe.p90Ratio = ratioAt(0.9);
        sum += probe.ceiling;
        result.probes.push_back(probe);
    }
    result.ceiling = sum / double(probed.size());
    return result;
}

}  // namespace lodopt::evaluation
