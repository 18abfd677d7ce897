// Time models on synthetic samples of known coefficients, degenerate data and feedback.
#include <gtest/gtest.h>

#include <cmath>

#include "timemodel/calibration.hpp"
#include "timemodel/time_model.hpp"

using namespace lodopt;
using timemodel::Feature;
using timemodel::Sample;

namespace {

// Frames with independent, spread-out features (a SplitMix64 stream, portable).
std::vector<timemodel::FrameFeatures> randomFrames(int count, std::uint64_t seed) {
    timemodel::SplitMix64 rng(seed);
    std::vector<timemodel::FrameFeatures> frames;
    for (int i = 0; i < count; ++i) {
        timemodel::FrameFeatures f;
        f[Feature::kTriangles] = rng.between(1e3, 2e5);
        f[Feature::kVertices] = f[Feature::kTriangles] * rng.between(0.5, 1.2);
        f[Feature::kTextureBytes] = rng.between(0.0, 4e6);
        f[Feature::kDrawCalls] = std::floor(rng.between(1.0, 60.0));
        f[Feature::kPixels] = rng.between(1e3, 2.6e5);
        f[Feature::kDrawnObjects] = std::floor(rng.between(1.0, 20.0));
        f[Feature::kMatrices] = f[Feature::kDrawnObjects];  // exactly collinear, as in real frames
        f[Feature::kBoundingBoxes] = 20.0;                  // constant, as in real frames
        frames.push_back(f);
    }
    return frames;
}

// ms = 0.4 + 2e-5·triangles + 1e-5·pixels + 0.05·draw_calls, times (1 ± noise).
double linearTruth(const timemodel::FrameFeatures& f) {
    return 0.4 + 2e-5 * f[Feature::kTriangles] + 1e-5 * f[Feature::kPixels] + 0.05 * f[Feature::kDrawCalls];
}

std::vector<Sample> samplesOf(const std::vector<timemodel::FrameFeatures>& frames,
                              double (*truth)(const timemodel::FrameFeatures&), double noise, std::uint64_t seed) {
    timemodel::SplitMix64 rng(seed);
    std::vector<Sample> samples;
    for (const auto& f : frames) {
        Sample s;
        s.features = f;
        s.measuredMs = truth(f) * (1.0 + rng.between(-noise, noise));
        samples.push_back(s);
    }
    return samples;
}

double coefficient(const timemodel::TimeModel& model, const std::string& name) {
    const auto names = model.coefficientNames();
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (names[i] == name) return model.coefficients()[i];
    }
    ADD_FAILURE() << "no coefficient " << name;
    return 0.0;
}

// Linear coefficients: an intercept and a vertex cost, every other feature free.
std::vector<double> linearCoefficients(double interceptMs, double perVertexMs = 0.0) {
    std::vector<double> c(timemodel::kFeatureCount + 1, 0.0);
    c[0] = interceptMs;
    c[1 + static_cast<std::size_t>(Feature::kVertices)] = perVertexMs;
    return c;
}

bool hasNoteContaining(const timemodel::FitReport& report, const std::string& text) {
    for (const std::string& note : report.notes) {
        if (note.find(text) != std::string::npos) return true;
    }
    return false;
}

}  // namespace

TEST(LinearModel, RecoversKnownCoefficientsFromExactSamples) {
    timemodel::LinearModel model;
    const auto samples = samplesOf(randomFrames(80, 7), &linearTruth, 0.0, 1);
    const timemodel::FitReport report = model.fit(samples);
    EXPECT_NEAR(coefficient(model, "intercept_ms"), 0.4, 1e-6);
    EXPECT_NEAR(coefficient(model, "triangles"), 2e-5, 1e-10);
    EXPECT_NEAR(coefficient(model, "pixels"), 1e-5, 1e-10);
    EXPECT_NEAR(coefficient(model, "draw_calls"), 0.05, 1e-7);
    EXPECT_NEAR(coefficient(model, "vertices"), 0.0, 1e-10);
    EXPECT_LT(report.rmsResidualMs, 1e-6);
    EXPECT_LT(timemodel::relativeErrors(model, samples).max, 1e-6);
}

TEST(LinearModel, RecoversKnownCoefficientsWithinToleranceFromNoisySamples) {
    timemodel::LinearModel model;
    const auto samples = samplesOf(randomFrames(400, 11), &linearTruth, 0.05, 2);
    model.fit(samples);
    EXPECT_NEAR(coefficient(model, "triangles"), 2e-5, 0.1 * 2e-5);
    EXPECT_NEAR(coefficient(model, "pixels"), 1e-5, 0.1 * 1e-5);
    EXPECT_NEAR(coefficient(model, "draw_calls"), 0.05, 0.1 * 0.05);
    // Noise of ±5% uniform: the mean relative error of a good fit is near 2.5%.
    EXPECT_LT(timemodel::relativeErrors(model, samples).mean, 0.035);
}

TEST(LinearModel, DropsCollinearAndConstantFeaturesWithANote) {
    timemodel::LinearModel model;
    const timemodel::FitReport report = model.fit(samplesOf(randomFrames(50, 3), &linearTruth, 0.0, 1));
    EXPECT_TRUE(hasNoteContaining(report, "'matrices'")) << "matrices duplicates drawn_objects";
    EXPECT_TRUE(hasNoteContaining(report, "'bounding_boxes': constant")) << "bounding boxes never change";
    EXPECT_EQ(coefficient(model, "matrices"), 0.0);
    EXPECT_EQ(coefficient(model, "bounding_boxes"), 0.0);
    EXPECT_TRUE(std::isfinite(report.conditionNumber));
    EXPECT_LT(report.conditionNumber, 1e7);
}

TEST(LinearModel, ExactlyProportionalFeaturesDoNotBlowUp) {
    // vertices == 2 * triangles in every sample: one of them must go, the prediction stays exact.
    auto frames = randomFrames(40, 5);
    for (auto& f : frames) f[Feature::kVertices] = 2.0 * f[Feature::kTriangles];
    timemodel::LinearModel model;
    const auto samples = samplesOf(frames, &linearTruth, 0.0, 1);
    const timemodel::FitReport report = model.fit(samples);
    EXPECT_TRUE(hasNoteContaining(report, "'vertices'"));
    for (double c : model.coefficients()) {
        EXPECT_TRUE(std::isfinite(c));
        EXPECT_GE(c, 0.0);
        EXPECT_LT(c, 1.0);
    }
    EXPECT_LT(timemodel::relativeErrors(model, samples).max, 1e-6);
}

TEST(LinearModel, CoefficientsStayNonNegativeWhenTheTruthHasANegativeSlope) {
    // ms falls with draw calls (not physical): NNLS pins that coefficient at 0 instead.
    auto frames = randomFrames(60, 9);
    timemodel::SplitMix64 rng(4);
    std::vector<Sample> samples;
    for (const auto& f : frames) {
        samples.push_back({f, 5.0 + 2e-5 * f[Feature::kTriangles] - 0.01 * f[Feature::kDrawCalls], 0});
    }
    timemodel::LinearModel model;
    model.fit(samples);
    for (double c : model.coefficients()) EXPECT_GE(c, 0.0);
    EXPECT_EQ(coefficient(model, "draw_calls"), 0.0);
}

TEST(TimeModels, RejectZeroNegativeAndNonFiniteTimes) {
    const auto good = samplesOf(randomFrames(10, 1), &linearTruth, 0.0, 1);
    for (const std::string& name : timemodel::timeModelNames()) {
        for (double bad : {0.0, -1.0, std::nan(""), double(INFINITY)}) {
            auto samples = good;
            samples[3].measuredMs = bad;
            auto model = timemodel::makeTimeModel(name);
            try {
                model->fit(samples);
                ADD_FAILURE() << name << " accepted a measured time of " << bad;
            } catch (const timemodel::TimeModelError& error) {
                EXPECT_NE(std::string(error.what()).find("sample 3"), std::string::npos) << error.what();
            }
        }
        auto negative = good;
        negative[1].features[Feature::kPixels] = -5.0;
        EXPECT_THROW(timemodel::makeTimeModel(name)->fit(negative), timemodel::TimeModelError);
    }
}

TEST(TimeModels, ASingleSampleIsNotEnough) {
    const auto one = samplesOf(randomFrames(1, 1), &linearTruth, 0.0, 1);
    for (const std::string& name : timemodel::timeModelNames()) {
        auto model = timemodel::makeTimeModel(name);
        try {
            model->fit(one);
            ADD_FAILURE() << name << " fitted one sample";
        } catch (const timemodel::TimeModelError& error) {
            EXPECT_NE(std::string(error.what()).find("not enough samples"), std::string::npos) << error.what();
        }
        EXPECT_FALSE(model->fitted());
        EXPECT_THROW(model->fit({}), timemodel::TimeModelError);
    }
}

TEST(TimeModels, UnknownNameListsTheModels) {
    try {
        timemodel::makeTimeModel("funkhouser");
        FAIL();
    } catch (const timemodel::TimeModelError& error) {
        EXPECT_NE(std::string(error.what()).find("linear, dong, wimmer"), std::string::npos) << error.what();
    }
}

double dongTruth(const timemodel::FrameFeatures& f) {
    return 3e-5 * f[Feature::kTriangles] + 5e-7 * f[Feature::kTextureBytes];
}

TEST(DongModel, CramerPairsRecoverExactCoefficients) {
    timemodel::DongModel model;
    const auto samples = samplesOf(randomFrames(30, 21), &dongTruth, 0.0, 1);
    const timemodel::FitReport report = model.fit(samples);
    EXPECT_EQ(report.pairs, 30u * 29u / 2u);
    EXPECT_NEAR(coefficient(model, "triangles"), 3e-5, 1e-11);
    EXPECT_NEAR(coefficient(model, "texture_bytes"), 5e-7, 1e-12);
}

TEST(DongModel, CountsAndSkipsPairsWithAZeroDeterminant) {
    // Samples 0..9 all have texture = 10 * triangles: their 45 pairs are degenerate.
    auto frames = randomFrames(20, 22);
    for (int i = 0; i < 10; ++i) frames[i][Feature::kTextureBytes] = 10.0 * frames[i][Feature::kTriangles];
    timemodel::DongModel model;
    const timemodel::FitReport report = model.fit(samplesOf(frames, &dongTruth, 0.0, 1));
    EXPECT_GE(report.skippedPairs, 45u);
    EXPECT_LT(report.skippedPairs, report.pairs);
    EXPECT_TRUE(hasNoteContaining(report, "near-zero determinant"));
    EXPECT_NEAR(coefficient(model, "triangles"), 3e-5, 1e-9);
}

TEST(DongModel, AllPairsDegenerateIsAClearError) {
    auto frames = randomFrames(6, 23);
    for (auto& f : frames) f[Feature::kTextureBytes] = 0.0;
    timemodel::DongModel model;
    try {
        model.fit(samplesOf(frames, &dongTruth, 0.0, 1));
        FAIL();
    } catch (const timemodel::TimeModelError& error) {
        EXPECT_NE(std::string(error.what()).find("all 15 sample pairs"), std::string::npos) << error.what();
    }
}

double wimmerTruth(const timemodel::FrameFeatures& f) {
    const double gpu = 2e-5 * f[Feature::kVertices] + 1.5e-5 * f[Feature::kPixels];
    const double cpu = 0.1 * f[Feature::kMatrices] + 0.12 * f[Feature::kDrawCalls];
    return 0.5 + std::max(cpu, gpu);
}

TEST(WimmerModel, RecoversAMaxOfTwoRegimes) {
    const auto samples = samplesOf(randomFrames(200, 31), &wimmerTruth, 0.0, 1);
    std::size_t cpuBound = 0;
    for (const auto& s : samples) {
        const auto& f = s.features;
        cpuBound += 0.1 * f[Feature::kMatrices] + 0.12 * f[Feature::kDrawCalls] >
                    2e-5 * f[Feature::kVertices] + 1.5e-5 * f[Feature::kPixels];
    }
    ASSERT_GT(cpuBound, 20u);
    ASSERT_LT(cpuBound, 180u);  // both regimes occur
    timemodel::WimmerModel model;
    model.fit(samples);
    EXPECT_LT(timemodel::relativeErrors(model, samples).max, 0.02);
    EXPECT_NEAR(coefficient(model, "vertices"), 2e-5, 0.1 * 2e-5);
    EXPECT_NEAR(coefficient(model, "pixels"), 1.5e-5, 0.1 * 1.5e-5);
    EXPECT_NEAR(coefficient(model, "draw_calls"), 0.12, 0.1 * 0.12);
}

TEST(Feedback, MovesTheEstimateTowardsTheMeasurementByBeta) {
    timemodel::LinearModel model;
    model.setCoefficients(linearCoefficients(1.0));  // 1 ms, whatever the frame
    const timemodel::FrameFeatures frame;
    const timemodel::FeedbackResult result = model.applyFeedback(frame, 1.2, {0.5, 1.0, 4.0});
    EXPECT_TRUE(result.applied);
    EXPECT_NEAR(result.relativeError, 0.2, 1e-12);
    EXPECT_NEAR(result.factor, 1.1, 1e-12);  // c' = (1 + 0.5 * 0.2) c
    EXPECT_NEAR(model.estimateMs(frame), 1.1, 1e-12);
    EXPECT_NEAR(model.calibratedCoefficients()[0], 1.0, 0.0);
}

TEST(Feedback, HeavyOutliersStayBounded) {
    timemodel::LinearModel model;
    model.setCoefficients(linearCoefficients(1.0, 1e-5));
    timemodel::FrameFeatures frame;
    frame[Feature::kVertices] = 1e5;                 // estimate 2 ms
    const timemodel::FeedbackParameters parameters;  // the defaults: beta 0.7, clamp ±1, drift 4
    // One absurd frame (1000x slower) moves the estimate by at most 1 + beta.
    const timemodel::FeedbackResult spike = model.applyFeedback(frame, 2000.0, parameters);
    EXPECT_NEAR(spike.factor, 1.7, 1e-12);
    EXPECT_NEAR(model.estimateMs(frame), 3.4, 1e-9);
    // A long run of outliers in either direction never leaves [1/4, 4] x calibrated, and no
    // coefficient ever turns negative or non-finite.
    for (int i = 0; i < 200; ++i) model.applyFeedback(frame, i % 2 ? 1e9 : 1e6, parameters);
    EXPECT_LE(model.feedbackScale(), 4.0 + 1e-12);
    for (int i = 0; i < 200; ++i) model.applyFeedback(frame, 1e-9, parameters);
    EXPECT_GE(model.feedbackScale(), 0.25 - 1e-12);
    for (double c : model.coefficients()) {
        EXPECT_TRUE(std::isfinite(c));
        EXPECT_GE(c, 0.0);
    }
    // Unusable measurements are ignored.
    const double before = model.feedbackScale();
    for (double bad : {0.0, -3.0, std::nan(""), double(INFINITY)})
        EXPECT_FALSE(model.applyFeedback(frame, bad).applied);
    EXPECT_EQ(model.feedbackScale(), before);
    // A refit or new coefficients reset the feedback.
    model.setCoefficients(model.calibratedCoefficients());
    EXPECT_EQ(model.feedbackScale(), 1.0);
}

TEST(Feedback, ConvergesToASteadyBias) {
    // The machine is 30% slower than calibrated: repeated feedback learns it.
    timemodel::LinearModel model;
    model.setCoefficients(linearCoefficients(2.0));
    const timemodel::FrameFeatures frame;
    for (int i = 0; i < 60; ++i) model.applyFeedback(frame, 2.6);
    EXPECT_NEAR(model.estimateMs(frame), 2.6, 1e-3);
}

TEST(ErrorStats, QuantilesInterpolateBetweenOrderStatistics) {
    const timemodel::ErrorStats stats =
        timemodel::summarizeErrors({0.5, 0.1, 0.4, 0.2, 0.3, 0.0, 0.9, 0.8, 0.7, 0.6, 1.0});
    EXPECT_EQ(stats.count, 11u);
    EXPECT_NEAR(stats.mean, 0.5, 1e-12);
    EXPECT_NEAR(stats.median, 0.5, 1e-12);
    EXPECT_NEAR(stats.p90, 0.9, 1e-12);
    EXPECT_NEAR(stats.max, 1.0, 1e-12);
    EXPECT_EQ(timemodel::summarizeErrors({}).count, 0u);
}

TEST(TimeModels, SetCoefficientsChecksCountAndFiniteness) {
    timemodel::WimmerModel model;
    EXPECT_THROW(model.setCoefficients({1.0, 2.0}), timemodel::TimeModelError);
    EXPECT_THROW(model.setCoefficients({1.0, 0, 0, 0, 0, std::nan("")}), timemodel::TimeModelError);
    model.setCoefficients({1.0, 0, 0, 0, 0, 0});
    EXPECT_TRUE(model.fitted());
    EXPECT_NEAR(model.estimateMs({}), 1.0, 0.0);
}
