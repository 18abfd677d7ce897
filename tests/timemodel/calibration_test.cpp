// Calibration plans (deterministic, viewpoints held out whole) and the side-by-side fit.
#include "timemodel/calibration.hpp"

#include <gtest/gtest.h>

#include <set>

#include "scenes/builtin.hpp"
#include "timemodel/features.hpp"

using namespace lodopt;

namespace {

// A sample with random triangles, vertices and pixels, and texture bytes when `textured`; its
// measured time is left for the test to set.
timemodel::Sample randomSample(timemodel::SplitMix64& rng, bool textured) {
    using timemodel::Feature;
    timemodel::Sample s;
    s.features[Feature::kTriangles] = rng.between(1e3, 1e5);
    s.features[Feature::kVertices] = s.features[Feature::kTriangles] * rng.between(0.5, 1.0);
    if (textured) s.features[Feature::kTextureBytes] = rng.between(1e5, 1e6);
    s.features[Feature::kPixels] = rng.between(1e3, 1e5);
    return s;
}

}  // namespace

TEST(SplitMix64, IsAFixedPortableSequence) {
    // Reference values of SplitMix64 seeded with 0 (Vigna's splitmix64.c).
    timemodel::SplitMix64 rng(0);
    EXPECT_EQ(rng.next(), 0xE220A8397B1DCDAFull);
    EXPECT_EQ(rng.next(), 0x6E789E6AA1B965F4ull);
    timemodel::SplitMix64 a(42), b(42);
    for (int i = 0; i < 100; ++i) {
        const double u = a.uniform();
        EXPECT_EQ(u, b.uniform());
        EXPECT_GE(u, 0.0);
        EXPECT_LT(u, 1.0);
    }
}

TEST(CalibrationPlan, SameSeedSamePlanAndDifferentSeedDifferentPlan) {
    const scenes::Scene scene = scenes::makeHarborScene();
    timemodel::CalibrationOptions options;
    options.samples = 40;
    const timemodel::CalibrationPlan a = timemodel::planCalibration(scene, options);
    const timemodel::CalibrationPlan b = timemodel::planCalibration(scene, options);
    ASSERT_EQ(a.samples.size(), 40u);
    ASSERT_EQ(a.viewpoints.size(), scene.views.size() * 4);
    for (std::size_t i = 0; i < a.samples.size(); ++i) {
        EXPECT_EQ(a.samples[i].combination, b.samples[i].combination);
        EXPECT_EQ(a.samples[i].viewpoint, b.samples[i].viewpoint);
    }
    for (std::size_t v = 0; v < a.viewpoints.size(); ++v) {
        EXPECT_EQ(a.viewpoints[v].camera.position, b.viewpoints[v].camera.position);
        EXPECT_EQ(a.viewpoints[v].heldOut, b.viewpoints[v].heldOut);
    }
    options.seed = 2;
    const timemodel::CalibrationPlan c = timemodel::planCalibration(scene, options);
    bool differs = false;
    for (std::size_t i = 0; i < a.samples.size(); ++i) differs |= a.samples[i].combination != c.samples[i].combination;
    EXPECT_TRUE(differs);
}

TEST(CalibrationPlan, HoldsOutOneWholeViewpointPerNamedView) {
    const scenes::Scene scene = scenes::makeHarborScene();
    timemodel::CalibrationOptions options;
    options.samples = 64;
    const timemodel::CalibrationPlan plan = timemodel::planCalibration(scene, options);
    std::vector<int> heldOutPerView(scene.views.size(), 0), fittedPerView(scene.views.size(), 0);
    for (const timemodel::Viewpoint& v : plan.viewpoints) (v.heldOut ? heldOutPerView : fittedPerView)[v.namedView]++;
    for (std::size_t v = 0; v < scene.views.size(); ++v) {
        EXPECT_EQ(heldOutPerView[v], 1) << scene.views[v].name;
        EXPECT_EQ(fittedPerView[v], 3) << scene.views[v].name;
    }
    // Every viewpoint gets samples, every combination is valid, and some objects are left out.
    std::set<int> used;
    int notDrawn = 0;
    for (const timemodel::PlannedSample& s : plan.samples) {
        used.insert(s.viewpoint);
        EXPECT_NO_THROW(scenes::validateCombination(scene, s.combination));
        for (int level : s.combination) notDrawn += level == scenes::kNotDrawn;
    }
    EXPECT_EQ(used.size(), plan.viewpoints.size());
    EXPECT_GT(notDrawn, 0);
}

TEST(CalibrationPlan, JitteredViewpointsStayNearTheirNamedViewAndLookAtIt) {
    const scenes::Scene scene = scenes::makeHarborScene();
    timemodel::SplitMix64 rng(5);
    for (const scenes::Camera& named : scene.views) {
        const scenes::Camera jittered = timemodel::jitterCamera(named, rng);
        const float distance = glm::length(named.position - named.target);
        EXPECT_NE(jittered.position, named.position);
        EXPECT_LT(glm::length(jittered.target - named.target), 0.04f * distance * 1.8f);
        const float newDistance = glm::length(jittered.position - jittered.target);
        EXPECT_GT(newDistance, 0.77f * distance);
        EXPECT_LT(newDistance, 1.29f * distance);
        EXPECT_EQ(jittered.fovYDegrees, named.fovYDegrees);
    }
}

TEST(CalibrationPlan, SampleSpreadCoversCoarseAndFineFrames) {
    const scenes::Scene scene = scenes::makeHarborScene();
    timemodel::CalibrationOptions options;
    options.samples = 120;
    const timemodel::CalibrationPlan plan = timemodel::planCalibration(scene, options);
    double least = 1e30, most = 0.0;
    for (const timemodel::PlannedSample& s : plan.samples) {
        const auto f =
            timemodel::computeFrameFeatures(scene, s.combination, plan.viewpoints[s.viewpoint].camera, 64, 64);
        least = std::min(least, f[timemodel::Feature::kTriangles]);
        most = std::max(most, f[timemodel::Feature::kTriangles]);
    }
    EXPECT_GT(most, 4.0 * std::max(least, 1.0));
}

TEST(CalibrationPlan, RejectsUnusableOptionsWithAMessage) {
    const scenes::Scene scene = scenes::makeHarborScene();
    timemodel::CalibrationOptions options;
    options.samples = 1;
    EXPECT_THROW(timemodel::planCalibration(scene, options), timemodel::TimeModelError);
    options.samples = 10;
    options.views = {99};
    EXPECT_THROW(timemodel::planCalibration(scene, options), timemodel::TimeModelError);
    options.views = {0};
    options.jitteredPerView = 0;  // a single viewpoint cannot be split
    EXPECT_THROW(timemodel::planCalibration(scene, options), timemodel::TimeModelError);
    options.jitteredPerView = 1;
    EXPECT_NO_THROW(timemodel::planCalibration(scene, options));
}

TEST(FitAllModels, ReportsEveryModelAndKeepsGoingWhenOneFails) {
    // Texture bytes are zero everywhere: dong cannot be solved, the others can.
    std::vector<timemodel::Sample> fit, heldOut;
    timemodel::SplitMix64 rng(3);
    for (int i = 0; i < 30; ++i) {
        timemodel::Sample s = randomSample(rng, false);
        s.measuredMs = 0.5 + 3e-5 * s.features[timemodel::Feature::kTriangles];
        (i % 3 == 0 ? heldOut : fit).push_back(s);
    }
    const std::vector<timemodel::ModelResult> results = timemodel::fitAllModels(fit, heldOut);
    ASSERT_EQ(results.size(), 3u);
    EXPECT_EQ(results[0].name, "linear");
    EXPECT_TRUE(results[0].fitted);
    EXPECT_LT(results[0].heldOutErrors.max, 1e-6);
    EXPECT_EQ(results[0].heldOutErrors.count, heldOut.size());
    EXPECT_EQ(results[1].name, "dong");
    EXPECT_FALSE(results[1].fitted);
    EXPECT_NE(results[1].failure.find("determinant"), std::string::npos);
    EXPECT_TRUE(results[2].fitted);
    const std::string table = timemodel::formatErrorTable(results);
    EXPECT_NE(table.find("linear"), std::string::npos);
    EXPECT_NE(table.find("dong  not fitted"), std::string::npos);
}

TEST(CalibrationPlan, FoldsHoldOutEveryViewpointOnceAndFoldZeroIsTheHeldOutSet) {
    const scenes::Scene scene = scenes::makeHarborScene();
    for (int jitter : {3, 0}) {
        timemodel::CalibrationOptions options;
        options.samples = 32;
        options.jitteredPerView = jitter;
        for (std::uint64_t seed : {1u, 2u, 7u}) {
            options.seed = seed;
            const timemodel::CalibrationPlan plan = timemodel::planCalibration(scene, options);
            EXPECT_EQ(plan.folds, 4) << "jitter " << jitter;
            std::vector<std::set<int>> foldsPerView(scene.views.size());
            for (const timemodel::Viewpoint& v : plan.viewpoints) {
                ASSERT_GE(v.fold, 0);
                ASSERT_LT(v.fold, plan.folds);
                EXPECT_EQ(v.fold == 0, v.heldOut) << v.camera.name << ", seed " << seed;
                foldsPerView[std::size_t(v.namedView)].insert(v.fold);
            }
            // With jitter every named view's group has one viewpoint in each fold; without, the
            // named views themselves rotate through the folds.
            if (jitter == 3) {
                for (const std::set<int>& folds : foldsPerView) EXPECT_EQ(folds.size(), 4u);
            } else {
                std::set<int> all;
                for (const timemodel::Viewpoint& v : plan.viewpoints) all.insert(v.fold);
                EXPECT_EQ(all.size(), std::min<std::size_t>(4, plan.viewpoints.size()));
            }
        }
    }
}

TEST(RotatedHeldOutErrors, PoolsEveryFoldAndMatchesTheHeldOutFitOnFoldZero) {
    // A linear truth plus a small, sample-specific wobble: each fold's fit is near but not exact.
    std::vector<timemodel::Sample> samples;
    std::vector<int> folds;
    timemodel::SplitMix64 rng(11);
    for (int i = 0; i < 48; ++i) {
        timemodel::Sample s = randomSample(rng, true);
        s.measuredMs = (0.5 + 3e-5 * s.features[timemodel::Feature::kTriangles]) * rng.between(0.95, 1.05);
        s.viewpoint = i % 8;
        samples.push_back(s);
        folds.push_back(s.viewpoint % 4);
    }
    const std::vector<timemodel::ErrorStats> rotated = timemodel::rotatedHeldOutErrors(samples, folds);
    ASSERT_EQ(rotated.size(), timemodel::timeModelNames().size());
    std::vector<timemodel::Sample> fit, heldOut;
    for (std::size_t i = 0; i < samples.size(); ++i) (folds[i] == 0 ? heldOut : fit).push_back(samples[i]);
    const std::vector<timemodel::ModelResult> once = timemodel::fitAllModels(fit, heldOut);
    for (std::size_t m = 0; m < rotated.size(); ++m) {
        EXPECT_EQ(rotated[m].count, samples.size()) << once[m].name;  // every sample held out once
        EXPECT_GT(rotated[m].max, 0.0) << once[m].name;
        // Fold 0's errors are among the pooled ones: the pooled max is at least theirs.
        EXPECT_GE(rotated[m].max, once[m].heldOutErrors.max - 1e-12) << once[m].name;
    }
    EXPECT_LT(rotated[0].mean, 0.06);  // linear, on a near-linear truth
    EXPECT_THROW(timemodel::rotatedHeldOutErrors(samples, {0, 1}), timemodel::TimeModelError);
}
