// Tuning: the search space maps the published defaults exactly, the compass search finds a
// known maximum deterministically, and coefficients files round-trip and fail clearly.
#include "scheduler/tuning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "fixtures.hpp"
#include "scheduler/coefficients.hpp"

namespace lodopt::scheduler {
namespace {

TEST(TuningSpace, PublishedDefaultsMapBackExactly) {
    const TermScales scales{40.0, 3.0, 2.0, 0.5};
    for (ImportanceForm form : {ImportanceForm::Published, ImportanceForm::Extended}) {
        const TuningSpace space(form, scales, 7);
        EXPECT_EQ(space.dimension(), form == ImportanceForm::Extended ? 6 : 4);
        const SchedulerCoefficients defaults;
        const SchedulerCoefficients back = space.coefficientsAt(space.pointOf(defaults));
        if (form == ImportanceForm::Published) {
            EXPECT_NEAR(back.importance.alpha1, 0.6, 1e-12);
            EXPECT_NEAR(back.importance.alpha2, 0.4, 1e-12);
            EXPECT_EQ(back.importance.alpha3, 0.0);
        } else {
            // The extended terms start at the lower bound: present but negligible.
            EXPECT_NEAR(back.importance.alpha2 / back.importance.alpha1, 0.4 / 0.6, 1e-9);
            EXPECT_LT(back.importance.alpha3 * scales.pixels, 1e-3 * back.importance.alpha1 * scales.distance);
        }
        ASSERT_EQ(back.thresholds.values.size(), defaults.thresholds.values.size());
        for (std::size_t k = 0; k < back.thresholds.values.size(); ++k) {
            EXPECT_NEAR(back.thresholds.values[k], defaults.thresholds.values[k], 1e-9);
        }
        EXPECT_NEAR(back.benchmark.scale, 1.0, 1e-12);
    }
}

TEST(PatternSearch, FindsTheMaximumOfASmoothFunction) {
    auto objective = [](const std::vector<double>& x) {
        return -(x[0] - 1.25) * (x[0] - 1.25) - 2.0 * (x[1] + 0.5) * (x[1] + 0.5);
    };
    PatternSearchOptions options;
    options.maxEvaluations = 400;
    const PatternSearchResult r = patternSearch(objective, {0.0, 0.0}, {-4, -4}, {4, 4}, {1.0, 1.0}, options);
    EXPECT_NEAR(r.best[0], 1.25, 0.02);
    EXPECT_NEAR(r.best[1], -0.5, 0.02);
    EXPECT_LE(r.evaluations, 400);
    EXPECT_EQ(int(r.bestByEvaluation.size()), r.evaluations);
    for (std::size_t i = 1; i < r.bestByEvaluation.size(); ++i) {
        EXPECT_GE(r.bestByEvaluation[i], r.bestByEvaluation[i - 1]);
    }
    // Same seed, same path; bounds are respected.
    const PatternSearchResult again = patternSearch(objective, {0.0, 0.0}, {-4, -4}, {4, 4}, {1.0, 1.0}, options);
    EXPECT_EQ(again.best, r.best);
    EXPECT_EQ(again.bestByEvaluation, r.bestByEvaluation);
    const PatternSearchResult bounded = patternSearch(objective, {0.0, 0.0}, {-4, 0}, {4, 4}, {1.0, 1.0}, options);
    EXPECT_DOUBLE_EQ(bounded.best[1], 0.0);
}

TEST(PatternSearch, StopsAtTheEvaluationBudget) {
    int calls = 0;
    auto objective = [&](const std::vector<double>& x) {
        ++calls;
        return x[0];  // increases forever toward the bound
    };
    PatternSearchOptions options;
    options.maxEvaluations = 7;
    const PatternSearchResult r = patternSearch(objective, {0.0}, {-100}, {100}, {1.0}, options);
    EXPECT_EQ(calls, 7);
    EXPECT_EQ(r.evaluations, 7);
    EXPECT_GT(r.best[0], 0.0);
}

TEST(TermScales, MediansOverVisibleObjects) {
    const scenes::Scene scene = testing::makeGridScene(3, 3, 5.0f);
    const SceneIndex index(scene, 64, 64, FeatureMode::Bounds);
    const TermScales scales = measureTermScales(index, {testing::lookAt({0, 10, 25}, {0, 0, 0})});
    EXPECT_GT(scales.distance, 20.0);  // the grid is 20-35 units away
    EXPECT_LT(scales.distance, 60.0);
    EXPECT_GT(scales.area, 0.0);
    EXPECT_GT(scales.pixels, 0.0);
}

TEST(Coefficients, RoundTripThroughJson) {
    SchedulerCoefficients c;
    c.importance = {0.5, 0.3, 0.15, 0.05};
    c.benchmark.scale = 1.7;
    c.thresholds = DistanceThresholds::geometric(3.0, 1.8, 4);
    const SchedulerCoefficients back = coefficientsFromJson(coefficientsToJson(c), "test");
    EXPECT_DOUBLE_EQ(back.importance.alpha3, 0.15);
    EXPECT_DOUBLE_EQ(back.benchmark.scale, 1.7);
    EXPECT_FALSE(back.benchmark.view.has_value());
    EXPECT_EQ(back.thresholds.values, c.thresholds.values);
    // A fixed benchmark object (DONG15's d = 15, θ = 0°, s = 6).
    ObjectView benchmark;
    benchmark.distance = 15;
    benchmark.projectedArea = 6;
    c.benchmark.view = benchmark;
    const SchedulerCoefficients fixed = coefficientsFromJson(coefficientsToJson(c), "test");
    ASSERT_TRUE(fixed.benchmark.view.has_value());
    EXPECT_DOUBLE_EQ(fixed.benchmark.view->distance, 15.0);
    EXPECT_DOUBLE_EQ(fixed.benchmark.view->projectedArea, 6.0);
}

void expectError(const std::string& text, const std::string& fragment) {
    try {
        coefficientsFromJson(text, "coeffs.json");
        ADD_FAILURE() << "accepted: " << text;
    } catch (const CoefficientsError& error) {
        EXPECT_NE(std::string(error.what()).find("coeffs.json"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    }
}

TEST(Coefficients, BadFilesNameTheField) {
    const std::string head = R"({"format": "lodopt-scheduler-coefficients", "version": 1, )";
    const std::string thresholds = R"("distance_thresholds": {"relative_to_radius": true, "values": [4, 8]})";
    expectError("{not json", "not valid JSON");
    expectError(R"({"format": "other", "version": 1})", ".format");
    expectError(head + R"("benchmark": {"scale": 1}, )" + thresholds + "}", ".importance");
    expectError(head + R"("importance": {"alpha1": -1, "alpha2": 0.4}, "benchmark": {"scale": 1}, )" + thresholds + "}",
                "alpha1");
    expectError(
        head + R"("importance": {"alpha1": 0.6, "alpha2": "x"}, "benchmark": {"scale": 1}, )" + thresholds + "}",
        ".importance.alpha2");
    expectError(
        head + R"("importance": {"alpha1": 0.6, "alpha2": 0.4}, "benchmark": {"scale": 0}, )" + thresholds + "}",
        ".benchmark.scale");
    expectError(head + R"("importance": {"alpha1": 0.6, "alpha2": 0.4}, "benchmark": {"scale": 1}, )" +
                    R"("distance_thresholds": {"relative_to_radius": true, "values": [8, 4]}})",
                ".distance_thresholds");
    EXPECT_THROW(loadCoefficients("/nonexistent/coeffs.json"), CoefficientsError);
}

}  // namespace
}  // namespace lodopt::scheduler
