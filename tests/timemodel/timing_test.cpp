// Calibration timing statistics and the choice of the statistic to learn from, on times small
// enough to work out by hand.
#include "timemodel/timing.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "timemodel/profile.hpp"

namespace timemodel = lodopt::timemodel;

namespace {

// A sample whose passes' least times are `least`, medians 5% above, CPU times 3x.
timemodel::PassTimes passes(const std::vector<double>& least) {
    timemodel::PassTimes times;
    for (double t : least) {
        times.least.push_back(t);
        times.median.push_back(1.05 * t);
        times.cpu.push_back(3.0 * t);
    }
    return times;
}

// Samples of a frame time linear in two features, on viewpoints 0..7 (those with v % 4 == 0 held
// out), 4 samples each; every statistic set to the true time, for a test to disturb.
struct Samples {
    std::vector<timemodel::ProfileSample> samples;
};
Samples linearSamples() {
    Samples s;
    for (int v = 0; v < 8; ++v) {
        for (int k = 0; k < 4; ++k) {
            timemodel::ProfileSample p;
            p.sample.features[timemodel::Feature::kTriangles] = 1000.0 * (1 + (v * 7 + k * 3) % 11);
            p.sample.features[timemodel::Feature::kPixels] = 5000.0 * (1 + (v * 5 + k * 2) % 13);
            p.sample.viewpoint = v;
            const double t = 0.5 + 1e-3 * p.sample.features[timemodel::Feature::kTriangles] +
                             2e-4 * p.sample.features[timemodel::Feature::kPixels];
            p.leastMs = p.leastMedianMs = p.medianMs = p.cpuMs = t;
            p.sample.measuredMs = t;
            p.heldOut = v % 4 == 0;
            s.samples.push_back(p);
        }
    }
    return s;
}

const timemodel::LearnCandidate& candidate(const timemodel::LearnChoice& choice, const std::string& statistic) {
    for (const auto& c : choice.candidates) {
        if (c.statistic == statistic) return c;
    }
    throw std::runtime_error(statistic + " not judged");
}

}  // namespace

TEST(Timing, EachStatisticReducesItsOwnPerPassValues) {
    const timemodel::PassTimes times = passes({10.0, 12.0, 9.0, 11.0});
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("least", times), 9.0);
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("least-median", times), 10.5);  // (10 + 11) / 2
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("median", times), 1.05 * 10.5);
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("cpu", times), 3.0 * 10.5);
    EXPECT_DOUBLE_EQ(timemodel::reducePasses("least-median", {4.0, 1.0, 3.0}), 3.0);
    EXPECT_EQ(timemodel::timeFromPasses("least", timemodel::PassTimes{}), 0.0);
    EXPECT_DOUBLE_EQ(timemodel::passSpread(times.least), (12.0 - 9.0) / 10.5);  // (greatest − least) / median
}

TEST(Timing, OlderProfilesStatisticNamesMapToTheCurrentOnes) {
    EXPECT_EQ(timemodel::canonicalStatistic("wall-median"), "median");
    EXPECT_EQ(timemodel::canonicalStatistic("wall-min-median"), "least-median");
    EXPECT_EQ(timemodel::canonicalStatistic("wall-min"), "least");
    for (const std::string& name : timemodel::timingStatisticNames()) {
        EXPECT_EQ(timemodel::canonicalStatistic(name), name);
    }
    EXPECT_EQ(timemodel::canonicalStatistic("gpu"), "");
    EXPECT_EQ(timemodel::timingStatisticNames().front(), timemodel::kPredictedStatistic);
}

TEST(Timing, SplitHalfComparesTheEvenPassesWithTheOddOnes) {
    // Even passes 10, 10; odd passes 12, 12.
    const std::vector<timemodel::PassTimes> times = {passes({10.0, 12.0, 10.0, 12.0})};
    const timemodel::ErrorStats least = timemodel::splitHalfRepeatability("least", times, {true});
    ASSERT_EQ(least.count, 1u);
    EXPECT_DOUBLE_EQ(least.median, 2.0 / 10.0);  // |10 − 12| / least of all
    const timemodel::ErrorStats median = timemodel::splitHalfRepeatability("least-median", times, {true});
    EXPECT_DOUBLE_EQ(median.median, 2.0 / 11.0);  // |10 − 12| / median of all
    // Excluded samples and samples with one pass are not judged.
    EXPECT_EQ(timemodel::splitHalfRepeatability("least", times, {false}).count, 0u);
    EXPECT_EQ(timemodel::splitHalfRepeatability("least", {passes({10.0})}, {true}).count, 0u);
}

TEST(Timing, PassFactorsShowAPassDuringWhichTheMachineWasSlower) {
    // Three samples over four passes; pass 2 drew every frame 30% slower.
    std::vector<timemodel::PassTimes> times(3);
    const std::vector<double> base = {10.0, 20.0, 40.0};
    const std::vector<double> pass = {1.0, 1.02, 1.3, 0.98};
    for (std::size_t i = 0; i < times.size(); ++i) {
        for (double factor : pass) times[i].median.push_back(base[i] * factor);
    }
    const std::vector<double> factors = timemodel::passTimeFactors(times);
    ASSERT_EQ(factors.size(), 4u);
    // Against each sample's median over the passes (the mean of 1.0 and 1.02 times its base).
    for (std::size_t p = 0; p < pass.size(); ++p) EXPECT_NEAR(factors[p], pass[p] / 1.01, 1e-12) << p;
    EXPECT_NEAR(timemodel::passDrift(factors), 1.3 / 0.98 - 1.0, 1e-12);
    // A sample with a pass not timed (0) is left out; with none left, or none at all: no factors.
    times.push_back({});
    times.back().median = {0.0, 5.0, 5.0, 5.0};
    EXPECT_EQ(timemodel::passTimeFactors(times).size(), 4u);
    EXPECT_TRUE(timemodel::passTimeFactors({times.back()}).empty());
    EXPECT_TRUE(timemodel::passTimeFactors({}).empty());
    EXPECT_EQ(timemodel::passDrift({1.2}), 0.0);
}

TEST(Timing, LearnedScaleIsTheMedianRatioOfThePredictedToTheLearned) {
    EXPECT_DOUBLE_EQ(timemodel::learnedScale({10.0, 10.0, 20.0}, {11.0, 13.0, 24.0}), 1.2);  // 1.1, 1.3, 1.2
    EXPECT_DOUBLE_EQ(timemodel::learnedScale({10.0, 0.0}, {11.0, 5.0}), 1.1);                // 0: not recorded
    EXPECT_DOUBLE_EQ(timemodel::learnedScale({}, {}), 1.0);
}

TEST(Timing, AutoLearnsFromTheLeastWhenASpeedJumpMovesSomeMedians) {
    // Every median 10% above the least, but a jump to a slower level during some samples' passes
    // put a quarter of the fitting samples' medians 40% higher still: fitted on the medians, the
    // model bends towards them; fitted on the least and scaled by 1.1, it predicts every other
    // median exactly.
    Samples s = linearSamples();
    int fitting = 0;
    for (timemodel::ProfileSample& p : s.samples) {
        p.medianMs = p.sample.measuredMs = 1.1 * p.leastMs;
        if (!p.heldOut && fitting++ % 4 == 1) p.medianMs = p.sample.measuredMs = 1.4 * 1.1 * p.leastMs;
        p.leastMedianMs = p.medianMs;
    }
    const timemodel::LearnChoice choice = timemodel::chooseStatisticToLearn(s.samples, "linear");
    EXPECT_TRUE(choice.measured);
    EXPECT_EQ(choice.statistic, "least");
    ASSERT_EQ(choice.candidates.size(), 3u);  // median, least-median, least; cpu is never a candidate
    EXPECT_NEAR(candidate(choice, "least").scale, 1.1, 1e-12);
    EXPECT_LT(candidate(choice, "least").crossValidated.mean, candidate(choice, "median").crossValidated.mean);
    // Judged on the fitting viewpoints only, each held out once: 24 samples on 6 viewpoints.
    EXPECT_EQ(candidate(choice, "least").crossValidated.count, 24u);
}

TEST(Timing, AutoLearnsFromTheMedianWhenTheLeastHasALongLowerTail) {
    // The medians follow the model exactly; now and then a pass was far faster (a lucky cache),
    // and the least of all draws caught it for some samples.
    Samples s = linearSamples();
    for (std::size_t i = 0; i < s.samples.size(); ++i) {
        timemodel::ProfileSample& p = s.samples[i];
        p.medianMs = p.sample.measuredMs = 1.2 * p.leastMs;
        if (i % 3 == 0) p.leastMs *= 0.7;
    }
    const timemodel::LearnChoice choice = timemodel::chooseStatisticToLearn(s.samples, "linear");
    EXPECT_EQ(choice.statistic, "median");
    EXPECT_NEAR(candidate(choice, "median").scale, 1.0, 1e-12);
    EXPECT_LT(candidate(choice, "median").crossValidated.mean, 1e-6);
    EXPECT_GT(candidate(choice, "least").crossValidated.mean, 0.05);
}

TEST(Timing, AutoIgnoresTheHeldOutSamples) {
    // The held-out samples' least is wild; the fitting samples agree on every statistic: a tie,
    // which keeps the median.
    Samples s = linearSamples();
    for (timemodel::ProfileSample& p : s.samples) {
        if (p.heldOut) p.leastMs *= 0.3;
    }
    const timemodel::LearnChoice choice = timemodel::chooseStatisticToLearn(s.samples, "linear");
    EXPECT_EQ(choice.statistic, "median");
    EXPECT_EQ(candidate(choice, "least").crossValidated.mean, candidate(choice, "median").crossValidated.mean);
}

TEST(Timing, AutoLearnsFromTheMedianWhenOneFittingViewpointLeavesNothingToJudge) {
    Samples s = linearSamples();
    for (timemodel::ProfileSample& p : s.samples) {
        if (!p.heldOut) p.sample.viewpoint = 1;
    }
    const timemodel::LearnChoice choice = timemodel::chooseStatisticToLearn(s.samples, "linear");
    EXPECT_FALSE(choice.measured);
    EXPECT_EQ(choice.statistic, timemodel::kPredictedStatistic);
    EXPECT_EQ(choice.candidates.size(), 3u);
    EXPECT_EQ(candidate(choice, "least").crossValidated.count, 0u);
}
