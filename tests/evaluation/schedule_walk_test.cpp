// The scheduler walked along a path (evaluation/schedule_walk.hpp): what a walk measures, and
// that a walk resumed from its records continues exactly as the uninterrupted one.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "evaluation/schedule_walk.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/profile.hpp"

using namespace lodopt;

namespace {

constexpr int kSize = 64;

struct Walker {
    const scenes::Scene& scene;
    scheduler::SceneIndex index;
    scheduler::FrameScheduler frameScheduler;

    Walker(const scenes::Scene& s, const timemodel::TimeModel& model)
        : scene(s),
          index(s, kSize, kSize, scheduler::FeatureMode::Bounds, 0, model.readFeatures()),
          frameScheduler(index, model.clone(), parameters()) {}

    static scheduler::SchedulerParameters parameters() {
        scheduler::SchedulerParameters p;
        p.budgetMs = 2.0;
        return p;
    }
};

const scenes::Scene& forest() {
    static const scenes::Scene scene = scenes::makeBuiltinScene("forest");
    return scene;
}

std::unique_ptr<timemodel::TimeModel> forestModel() {
    return timemodel::modelFromProfile(timemodel::shippedProfile("forest"));
}

}  // namespace

TEST(ScheduleWalk, WithoutRenderingDecidesOnlyAndReplaysToTheSameFrames) {
    const scenes::Scene& scene = forest();
    const scenes::CameraPath& path = scene.paths.at(0);
    const auto model = forestModel();
    Walker first(scene, *model);
    evaluation::ScheduleWalk walk(scene, path, first.frameScheduler, nullptr, {});
    std::vector<evaluation::WalkFrame> frames;
    std::vector<evaluation::RecordedFrame> records;
    for (int f = 0; f < 30; f += 3) {
        frames.push_back(walk.walk(f));
        records.push_back(evaluation::record(frames.back()));
        const evaluation::WalkFrame& row = frames.back();
        EXPECT_EQ(row.frame, f);
        EXPECT_TRUE(std::isnan(row.measuredMs));
        EXPECT_TRUE(std::isnan(row.fitness));
        EXPECT_EQ(row.predictedMs, row.decision.predictedMs);
        EXPECT_GE(row.finestPredictedMs, row.predictedMs - 1e-9);
        int drawn = 0;
        for (int level : row.decision.levels) drawn += level != scenes::kNotDrawn;
        int histogram = 0;
        for (int count : row.histogram) histogram += count;
        EXPECT_EQ(histogram, drawn);
    }

    // A second scheduler replaying the records reaches the same state: the frames that follow
    // are decided alike.
    Walker second(scene, *model);
    evaluation::ScheduleWalk resumed(scene, path, second.frameScheduler, nullptr, {});
    for (std::size_t i = 0; i + 1 < records.size(); ++i) {
        const evaluation::WalkFrame row = resumed.replay(records[i].frame, records[i]);
        EXPECT_EQ(row.decision.levels, frames[i].decision.levels);
        EXPECT_EQ(row.decisionMicroseconds, records[i].decisionMicroseconds);
    }
    EXPECT_EQ(resumed.walk(frames.back().frame).decision.levels, frames.back().decision.levels);

    // A record the replay does not reproduce is refused.
    Walker third(scene, *model);
    evaluation::ScheduleWalk tampered(scene, path, third.frameScheduler, nullptr, {});
    evaluation::RecordedFrame wrong = records[0];
    wrong.predictedMs += 0.5;
    EXPECT_THROW(tampered.replay(wrong.frame, wrong), evaluation::ReplayMismatch);
}

TEST(ScheduleWalk, RenderedFramesAreTimedScoredAndFedBack) {
    const scenes::Scene& scene = forest();
    const scenes::CameraPath& path = scene.paths.at(0);
    const auto model = forestModel();
    renderer::RenderSettings settings;
    settings.width = settings.height = kSize;
    renderer::Renderer renderer(scene, settings);
    evaluation::WalkOptions options;
    options.render = true;
    options.repeats = 1;

    Walker first(scene, *model);
    evaluation::ScheduleWalk walk(scene, path, first.frameScheduler, &renderer, options);
    std::vector<evaluation::RecordedFrame> records;
    std::vector<evaluation::WalkFrame> frames;
    for (int f : {0, 10, 20}) {
        frames.push_back(walk.walk(f));
        records.push_back(evaluation::record(frames.back()));
        const evaluation::WalkFrame& row = frames.back();
        EXPECT_GT(row.measuredMs, 0.0);
        EXPECT_GT(row.baselineMeasuredMs, 0.0);
        EXPECT_GT(row.fitness, 0.0);
        EXPECT_LE(row.fitness, 1.0);
        EXPECT_GT(row.baselineFitness, 0.0);
        EXPECT_EQ(row.feedbackScale, first.frameScheduler.model().feedbackScale());
    }
    EXPECT_NE(frames.back().feedbackScale, 1.0);  // measured times differ from predictions

    // Resumed after two frames from the records: the feedback and the third decision agree.
    Walker second(scene, *model);
    evaluation::ScheduleWalk resumed(scene, path, second.frameScheduler, &renderer, options);
    resumed.replay(0, records[0]);
    const evaluation::WalkFrame replayed = resumed.replay(10, records[1]);
    EXPECT_EQ(replayed.feedbackScale, frames[1].feedbackScale);
    EXPECT_EQ(replayed.fitness, frames[1].fitness);
    EXPECT_EQ(resumed.walk(20).decision.levels, frames[2].decision.levels);

    const evaluation::MeasurementCeiling ceiling = evaluation::probeMeasurementCeiling(
        renderer, path, frames, 4, 1);
    ASSERT_EQ(ceiling.probes.size(), 3u);
    EXPECT_EQ(ceiling.probes[1].frame, 10);
    EXPECT_GT(ceiling.ceiling, 0.0);
    EXPECT_LE(ceiling.ceiling, 1.0);

    EXPECT_THROW(evaluation::ScheduleWalk(scene, path, first.frameScheduler, nullptr, options), std::invalid_argument);
}
