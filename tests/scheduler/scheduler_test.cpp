// The frame scheduler (DONG15 §2.4 flat, CITY17 tiles) on scenes made of blobs, with a time
// model that counts triangles, so every prediction can be checked by hand.
#include "scheduler/scheduler.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numeric>
#include <set>

#include "fixtures.hpp"

namespace lodopt::scheduler {
namespace {

constexpr double kMsPerTriangle = 1e-3;
constexpr double kInterceptMs = 0.5;

double trianglesMs(const scenes::Scene& scene, const scenes::Combination& levels) {
    double triangles = 0.0;
    for (std::size_t o = 0; o < levels.size(); ++o) {
        if (levels[o] != scenes::kNotDrawn) triangles += double(scene.objects[o].levels[levels[o]].stats.triangles);
    }
    return kInterceptMs + kMsPerTriangle * triangles;
}

std::vector<scenes::Camera> orbit(int frames, float radius, float height) {
    std::vector<scenes::Camera> cameras;
    for (int f = 0; f < frames; ++f) {
        const float angle = 6.2831853f * float(f) / float(frames);
        cameras.push_back(testing::lookAt(glm::vec3(radius * std::cos(angle), height, radius * std::sin(angle)),
                                          glm::vec3(0.0f, 1.0f, 0.0f)));
    }
    return cameras;
}

// Three blobs on the z axis at 10, 20 and 40 units from the eye.
scenes::Scene rowScene() {
    scenes::Scene scene;
    scene.objects.push_back(testing::makeBlob("near", {0, 0, -10}, 1.0f));
    scene.objects.push_back(testing::makeBlob("middle", {0, 0, -20}, 1.0f));
    scene.objects.push_back(testing::makeBlob("far", {0, 0, -40}, 1.0f));
    scenes::updateStatistics(scene);
    return scene;
}
const scenes::Camera kRowCamera = testing::lookAt({0, 1.5f, 0}, {0, 1.5f, -10});

double levelTriangles(const scenes::Scene& scene, int level) {
    return double(scene.objects[0].levels[level].stats.triangles);
}

TEST(Scheduler, MeetsTheBudgetWheneverReachable) {
    const scenes::Scene scene = testing::makeGridScene(8, 8, 6.0f);
    const SceneIndex index(scene, 128, 96, FeatureMode::Bounds);
    for (Organisation organisation : {Organisation::Flat, Organisation::Tiles}) {
        SchedulerParameters p;
        p.organisation = organisation;
        p.switchControl.enabled = false;
        FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
        int reachable = 0, unreachable = 0;
        for (const scenes::Camera& camera : orbit(24, 40.0f, 12.0f)) {
            for (double budget : {1.0, 5.0, 12.0, 25.0, 60.0, 1000.0}) {
                scheduler.setBudgetMs(budget);
                scheduler.reset();
                const FrameDecision& d = scheduler.decide(camera, 0.0);
                // The prediction is the model's for exactly these levels.
                EXPECT_NEAR(d.predictedMs, trianglesMs(scene, d.levels), 1e-9);
                if (d.budgetReachable) {
                    ++reachable;
                    EXPECT_TRUE(d.budgetMet) << toString(organisation) << " budget " << budget;
                    EXPECT_LE(d.predictedMs, budget + 1e-9);
                } else {
                    ++unreachable;
                    if (organisation == Organisation::Flat) {
                        EXPECT_FALSE(d.budgetMet);
                        for (std::size_t o = 0; o < d.levels.size(); ++o) {  // everything coarsest
                            if (d.levels[o] != scenes::kNotDrawn) {
                                EXPECT_EQ(d.levels[o], 2);
                            }
                        }
                    } else {
                        EXPECT_TRUE(d.budgetMet);  // tiles drop objects instead
                        EXPECT_GT(d.droppedObjects, 0);
                    }
                }
                EXPECT_EQ(d.visibleObjects + d.culledObjects, int(scene.objects.size()));
            }
        }
        EXPECT_GT(reachable, 0);
        EXPECT_GT(unreachable, 0);
    }
}

TEST(Scheduler, CullsObjectsOutsideTheFrustum) {
    const scenes::Scene scene = rowScene();
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.budgetMs = 1e6;
    FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    // Looking away from the row: nothing drawn.
    const FrameDecision& away = scheduler.decide(testing::lookAt({0, 1.5f, 0}, {0, 1.5f, 10}), 0.0);
    EXPECT_EQ(away.visibleObjects, 0);
    EXPECT_EQ(away.culledObjects, 3);
    for (int level : away.levels) EXPECT_EQ(level, scenes::kNotDrawn);
    const FrameDecision& toward = scheduler.decide(kRowCamera, 1.0);
    EXPECT_EQ(toward.visibleObjects, 3);
    for (int level : toward.levels) EXPECT_EQ(level, 0);  // a loose budget raises all to level 0
}

TEST(Scheduler, RaisesInDecreasingImportance) {
    const scenes::Scene scene = rowScene();
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.coefficients.thresholds.values = {0.5, 1.0};  // every object starts at its coarsest level
    p.switchControl.enabled = false;
    // Room for one object to go from level 2 to level 0, not two.
    p.budgetMs = kInterceptMs + kMsPerTriangle * (3 * levelTriangles(scene, 2) + levelTriangles(scene, 0) -
                                                  levelTriangles(scene, 2) + 1.0);
    FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    const FrameDecision& d = scheduler.decide(kRowCamera, 0.0);
    EXPECT_GT(scheduler.importances()[0], scheduler.importances()[1]);
    EXPECT_GT(scheduler.importances()[1], scheduler.importances()[2]);
    EXPECT_EQ(d.levels, (scenes::Combination{0, 2, 2}));
    EXPECT_TRUE(d.budgetMet);
}

TEST(Scheduler, LowersImportantObjectsOnlyWhenUnavoidable) {
    const scenes::Scene scene = rowScene();
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.coefficients.thresholds.values = {1e5, 2e5};  // every object starts at level 0
    p.switchControl.enabled = false;
    FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    // Median benchmark: near I > 1, middle I = 1, far I < 1.
    const double t0 = levelTriangles(scene, 0), t2 = levelTriangles(scene, 2);
    // Lowering far and middle to coarsest is enough: near (I > 1) keeps level 0.
    scheduler.setBudgetMs(kInterceptMs + kMsPerTriangle * (t0 + 2 * t2));
    const FrameDecision& enough = scheduler.decide(kRowCamera, 0.0);
    EXPECT_GT(scheduler.importances()[0], 1.0);
    EXPECT_EQ(enough.levels, (scenes::Combination{0, 2, 2}));
    EXPECT_EQ(enough.protectedLowered, 0);
    // A tighter budget: the near object must be lowered too, and that is reported.
    scheduler.setBudgetMs(kInterceptMs + kMsPerTriangle * (levelTriangles(scene, 1) + 2 * t2));
    const FrameDecision& tight = scheduler.decide(kRowCamera, 1.0);
    EXPECT_EQ(tight.levels, (scenes::Combination{1, 2, 2}));
    EXPECT_EQ(tight.protectedLowered, 1);
    EXPECT_TRUE(tight.budgetMet);
    // Without protection the least important objects still go first, the order is the same.
    p.protectImportant = false;
    FrameScheduler unprotected(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    unprotected.setBudgetMs(kInterceptMs + kMsPerTriangle * (t0 + 2 * t2));
    EXPECT_EQ(unprotected.decide(kRowCamera, 0.0).levels, (scenes::Combination{0, 2, 2}));
}

// After lowering, the last step down often leaves budget over: a more important object that
// was not lowered takes it.
TEST(Scheduler, SpendsWhatLoweringLeftOver) {
    const scenes::Scene scene = rowScene();
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.coefficients.thresholds.values = {8.0, 16.0};  // by distance: near 0, middle 1, far 2
    p.objectWeights = {1.0, 1.0, 100.0};             // the far object matters most
    p.switchControl.enabled = false;
    const double t1 = levelTriangles(scene, 1), t2 = levelTriangles(scene, 2);
    p.budgetMs = kInterceptMs + kMsPerTriangle * (2 * t1 + t2 + 10.0);
    FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    const FrameDecision& d = scheduler.decide(kRowCamera, 0.0);
    ASSERT_EQ(scheduler.initialLevels(), (scenes::Combination{0, 1, 2}));
    ASSERT_GT(trianglesMs(scene, scheduler.initialLevels()), p.budgetMs);
    // Lowering (middle, then near: the far one is the most important) ends at {1, 2, 2} with
    // t1 - t2 + 10 triangles to spare; the far object's step to level 1 fits in them.
    EXPECT_GT(p.budgetMs, trianglesMs(scene, {1, 2, 2}) + kMsPerTriangle * (t1 - t2));
    EXPECT_EQ(d.levels, (scenes::Combination{1, 2, 1}));
    EXPECT_TRUE(d.budgetMet);
}

// An object the switch control holds coarser than the decision wanted leaves budget; objects
// the control lets move take it (each within its allowed range).
TEST(Scheduler, BudgetLeftByHeldObjectsGoesToFreeOnes) {
    const scenes::Scene scene = rowScene();
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.coefficients.thresholds.values = {0.5, 1.0};  // every object starts at its coarsest level
    p.switchControl.rule = SwitchRule::Vmi20;
    p.switchControl.delta1 = 0.01;  // one level per switch
    p.switchControl.k1 = 0.0;
    p.switchControl.delta2 = 0.05;  // dwell 0.05 s per radius of distance: seconds here
    p.switchControl.k2 = 1.0;
    const double t0 = levelTriangles(scene, 0), t1 = levelTriangles(scene, 1), t2 = levelTriangles(scene, 2);
    p.budgetMs = kInterceptMs + kMsPerTriangle * (3 * t2 + 1.0);
    FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    EXPECT_EQ(scheduler.decide(kRowCamera, 0.0).levels, (scenes::Combination{2, 2, 2}));
    // Room for near and middle to step to level 1: both switch at 0.1 s.
    scheduler.setBudgetMs(kInterceptMs + kMsPerTriangle * (2 * t1 + t2 + 1.0));
    const FrameDecision& second = scheduler.decide(kRowCamera, 0.1);
    EXPECT_EQ(second.levels, (scenes::Combination{1, 1, 2}));
    EXPECT_EQ(second.switches, 2);
    // Room for {0, 1, 2}; the near object is held at 1 (it switched 0.1 s ago), which leaves
    // t0 - t1 triangles: the far object, never switched, takes its step to level 1.
    scheduler.setBudgetMs(kInterceptMs + kMsPerTriangle * (t0 + t1 + t2));
    const FrameDecision& third = scheduler.decide(kRowCamera, 0.2);
    EXPECT_EQ(third.heldObjects, 1);
    EXPECT_EQ(third.levels, (scenes::Combination{1, 1, 1}));
    EXPECT_EQ(third.forcedSwitches, 0);
    EXPECT_TRUE(third.budgetMet);
}

TEST(Scheduler, FeedbackStaysBoundedAndMakesFramesCheaper) {
    const scenes::Scene scene = testing::makeGridScene(4, 4, 5.0f);
    const SceneIndex index(scene, 96, 96, FeatureMode::Bounds);
    SchedulerParameters p;
    p.switchControl.enabled = false;
    p.feedback.beta = 0.5;
    p.feedback.maxDrift = 4.0;
    const scenes::Camera camera = testing::lookAt({0, 15, 25}, {0, 0, 0});
    FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    scheduler.setBudgetMs(1e6);
    const double finest = scheduler.decide(camera, 0.0).predictedMs;
    scheduler.setBudgetMs(0.5 * finest);
    const FrameDecision& first = scheduler.decide(camera, 0.0);
    const int firstSum = std::accumulate(first.levels.begin(), first.levels.end(), 0);
    // The frame always measures 10x its prediction: the scale climbs to maxDrift, no further.
    for (int frame = 0; frame < 40; ++frame) {
        const FrameDecision& d = scheduler.decide(camera, frame / 30.0);
        const timemodel::FeedbackResult r = scheduler.reportMeasuredMs(10.0 * d.predictedMs);
        EXPECT_TRUE(r.applied);
        EXPECT_LE(scheduler.model().feedbackScale(), 4.0 + 1e-12);
    }
    EXPECT_NEAR(scheduler.model().feedbackScale(), 4.0, 1e-9);
    // The model now predicts 4x: the same view gets coarser levels for the same budget.
    const FrameDecision& later = scheduler.decide(camera, 2.0);
    EXPECT_GT(std::accumulate(later.levels.begin(), later.levels.end(), 0), firstSum);
    // Unusable measurements are ignored.
    EXPECT_FALSE(scheduler.reportMeasuredMs(std::nan("")).applied);
    EXPECT_FALSE(scheduler.reportMeasuredMs(-1.0).applied);
    // Ten times too slow the other way: the scale drops to 1/maxDrift, no further.
    for (int frame = 0; frame < 80; ++frame) {
        const FrameDecision& d = scheduler.decide(camera, 3.0 + frame / 30.0);
        scheduler.reportMeasuredMs(0.1 * d.predictedMs);
        EXPECT_GE(scheduler.model().feedbackScale(), 0.25 - 1e-12);
    }
    EXPECT_NEAR(scheduler.model().feedbackScale(), 0.25, 1e-9);
}

// Budget adherence against a synthetic device: the true frame time is 1.6x what the model
// predicts, with ±5% deterministic noise per frame. Once the feedback has settled, the true
// time of the scheduled frames lies within ±10% of the budget on at least 90% of the frames,
// with and without switch control; the distance levels alone miss it.
TEST(Scheduler, MeasuredTimeSettlesWithinTenPercentOfTheBudget) {
    const scenes::Scene scene = testing::makeGridScene(8, 8, 6.0f);
    const SceneIndex index(scene, 128, 96, FeatureMode::Bounds);
    const std::vector<scenes::Camera> path = orbit(150, 40.0f, 12.0f);
    constexpr double kTrueScale = 1.6;
    std::uint64_t noiseState = 7;
    auto trueMs = [&](const scenes::Combination& levels) {
        noiseState = noiseState * 6364136223846793005ull + 1442695040888963407ull;
        const double u = double(noiseState >> 11) / double(1ull << 53);  // [0, 1)
        return kTrueScale * trianglesMs(scene, levels) * (1.0 + 0.05 * (2.0 * u - 1.0));
    };
    for (const bool control : {false, true}) {
        SCOPED_TRACE(control ? "switch control" : "no switch control");
        SchedulerParameters p;
        p.switchControl.enabled = control;
        p.budgetMs = 12.0;
        FrameScheduler scheduler(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
        int counted = 0, within = 0, baselineWithin = 0;
        for (std::size_t f = 0; f < path.size(); ++f) {
            const FrameDecision& d = scheduler.decide(path[f], double(f) / 30.0);
            ASSERT_TRUE(d.budgetReachable);
            const double measured = trueMs(d.levels);
            const double baseline = trueMs(scheduler.initialLevels());
            scheduler.reportMeasuredMs(measured);
            if (f < 30) continue;  // the feedback settles
            ++counted;
            within += std::abs(measured - p.budgetMs) <= 0.1 * p.budgetMs;
            baselineWithin += std::abs(baseline - p.budgetMs) <= 0.1 * p.budgetMs;
        }
        EXPECT_NEAR(scheduler.model().feedbackScale(), kTrueScale, 0.1 * kTrueScale);
        EXPECT_GE(within, 0.9 * counted) << within << " of " << counted;
        EXPECT_LT(baselineWithin, 0.5 * counted) << baselineWithin << " of " << counted;
    }
}

TEST(Scheduler, SameInputsSameDecisions) {
    const scenes::Scene scene = testing::makeGridScene(6, 6, 5.0f);
    const SceneIndex index(scene, 96, 96, FeatureMode::Bounds);
    for (Organisation organisation : {Organisation::Flat, Organisation::Tiles}) {
        SchedulerParameters p;
        p.organisation = organisation;
        p.budgetMs = 8.0;
        FrameScheduler a(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
        FrameScheduler b(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
        const std::vector<scenes::Camera> path = orbit(30, 25.0f, 8.0f);
        for (std::size_t f = 0; f < path.size(); ++f) {
            const FrameDecision da = a.decide(path[f], f / 30.0);
            const FrameDecision& db = b.decide(path[f], f / 30.0);
            EXPECT_EQ(da.levels, db.levels);
            EXPECT_EQ(da.predictedMs, db.predictedMs);
            EXPECT_EQ(da.switches, db.switches);
            a.reportMeasuredMs(1.2 * da.predictedMs);
            b.reportMeasuredMs(1.2 * db.predictedMs);
        }
    }
}

TEST(Scheduler, ExactAndBoundsFeaturesAgreeOnTriangles) {
    const scenes::Scene scene = testing::makeGridScene(5, 5, 5.0f);
    const SceneIndex bounds(scene, 96, 96, FeatureMode::Bounds);
    const SceneIndex exact(scene, 96, 96, FeatureMode::Exact);
    SchedulerParameters p;
    p.budgetMs = 6.0;
    FrameScheduler a(bounds, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    FrameScheduler b(exact, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    for (const scenes::Camera& camera : orbit(12, 20.0f, 6.0f)) {
        const FrameDecision da = a.decide(camera, 0.0);
        EXPECT_EQ(da.levels, b.decide(camera, 0.0).levels);
    }
}

// Quadtree vs flat on a grid: tile culling is conservative (the same objects are visible), both
// meet the budget, and the tiles honour the distance levels (never finer than them) while the
// flat scheduler spends what is left of the budget on raising beyond them.
TEST(Scheduler, TilesAndFlatOnAGrid) {
    const scenes::Scene scene = testing::makeGridScene(10, 10, 5.0f);
    const SceneIndex index(scene, 128, 96, FeatureMode::Bounds);
    SchedulerParameters p;
    p.switchControl.enabled = false;
    p.budgetMs = 25.0;
    p.coefficients.thresholds.values = {6.0, 12.0};
    FrameScheduler flat(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    p.organisation = Organisation::Tiles;
    p.quadtree.leafCapacity = 4;
    FrameScheduler tiles(index, testing::triangleModel(kInterceptMs, kMsPerTriangle), p);
    int flatFiner = 0;
    for (const scenes::Camera& camera : orbit(16, 30.0f, 6.0f)) {
        const FrameDecision f = flat.decide(camera, 0.0);
        const FrameDecision& t = tiles.decide(camera, 0.0);
        EXPECT_EQ(f.visibleObjects, t.visibleObjects);
        for (int o = 0; o < index.objectCount(); ++o) {
            EXPECT_EQ(flat.frame().visible[o], tiles.frame().visible[o]) << "object " << o;
            if (t.levels[o] != scenes::kNotDrawn) {
                EXPECT_GE(t.levels[o], tiles.initialLevels()[o]);
            }
        }
        EXPECT_TRUE(f.budgetMet);
        EXPECT_TRUE(t.budgetMet);
        // When the distance levels fit, flat starts there and only raises; tiles stop there.
        if (trianglesMs(scene, tiles.initialLevels()) <= p.budgetMs) {
            EXPECT_GE(f.predictedMs + 1e-9, t.predictedMs);
            if (f.predictedMs > t.predictedMs + 1e-9) ++flatFiner;
        }
    }
    EXPECT_GT(flatFiner, 0);
}

TEST(Scheduler, RejectsBadParameters) {
    const scenes::Scene scene = rowScene();
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    SchedulerParameters p;
    p.budgetMs = 0.0;
    EXPECT_THROW(FrameScheduler(index, testing::triangleModel(0, 1), p), std::invalid_argument);
    p = {};
    p.objectWeights = {1.0, 2.0};  // three objects
    EXPECT_THROW(FrameScheduler(index, testing::triangleModel(0, 1), p), std::invalid_argument);
    p = {};
    p.coarsestShare = 0.0;
    EXPECT_THROW(FrameScheduler(index, testing::triangleModel(0, 1), p), std::invalid_argument);
    p = {};
    p.coefficients.benchmark.scale = -1.0;
    EXPECT_THROW(FrameScheduler(index, testing::triangleModel(0, 1), p), std::invalid_argument);
}

TEST(Scheduler, DecidesTheSameFromAnIndexBuiltForTheModelsFeatures) {
    // A model reading triangles, edge pixels and shaded pixels (the depth pass) but not the
    // partial blocks: an index built for its set skips their work and decides the same.
    const scenes::Scene scene = testing::makeGridScene(6, 6, 6.0f);
    auto model = timemodel::makeTimeModel("linear");
    std::vector<double> coefficients(model->coefficientNames().size(), 0.0);
    coefficients[0] = kInterceptMs;
    coefficients[std::size_t(timemodel::Feature::kTriangles) + 1] = kMsPerTriangle;
    coefficients[std::size_t(timemodel::Feature::kEdgePixels) + 1] = 1e-3;
    coefficients[std::size_t(timemodel::Feature::kShadedPixels) + 1] = 1e-5;
    model->setCoefficients(coefficients);
    const timemodel::FeatureSet read = model->readFeatures();
    ASSERT_EQ(read.count(), 3u);
    for (FeatureMode mode : {FeatureMode::Bounds, FeatureMode::Exact}) {
        const SceneIndex everything(scene, 96, 96, mode);
        const SceneIndex forTheModel(scene, 96, 96, mode, 0, read);
        SchedulerParameters p;
        p.budgetMs = 4.0;
        FrameScheduler a(everything, model->clone(), p), b(forTheModel, model->clone(), p);
        int frames = 0;
        for (const scenes::Camera& camera : orbit(16, 30.0f, 8.0f)) {
            const FrameDecision& x = a.decide(camera, frames / 30.0);
            const FrameDecision& y = b.decide(camera, frames / 30.0);
            ++frames;
            EXPECT_EQ(x.levels, y.levels) << toString(mode) << " frame " << frames;
            EXPECT_EQ(x.predictedMs, y.predictedMs);
            EXPECT_EQ(y.features[timemodel::Feature::kPartialBlocks], 0.0);  // skipped
        }
        // An index without a feature the model reads is refused, naming the feature.
        const SceneIndex without(scene, 96, 96, mode, 0,
                                 read & ~timemodel::FeatureSet().set(std::size_t(timemodel::Feature::kEdgePixels)));
        try {
            FrameScheduler refused(without, model->clone(), p);
            ADD_FAILURE() << "no exception";
        } catch (const std::invalid_argument& error) {
            EXPECT_NE(std::string(error.what()).find("edge_pixels"), std::string::npos) << error.what();
        }
    }
}

}  // namespace
}  // namespace lodopt::scheduler
