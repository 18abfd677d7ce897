// Calibration timing statistics and the choice of the fitted clock, on per-pass times small
// enough to work out by hand.
#include "timemodel/timing.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "timemodel/profile.hpp"

namespace timemodel = lodopt::timemodel;

namespace {

// A sample whose passes' least wall times are `least`, medians 5% above, CPU times 3x.
timemodel::PassTimes passes(const std::vector<double>& least) {
    timemodel::PassTimes times;
    for (double t : least) {
        times.leastWall.push_back(t);
        times.medianWall.push_back(1.05 * t);
        times.medianCpu.push_back(3.0 * t);
    }
    return times;
}

double repeatabilityOf(const timemodel::ClockChoice& choice, const std::string& clock) {
    for (const auto& candidate : choice.candidates) {
        if (candidate.clock == clock) return candidate.repeatability.median;
    }
    ADD_FAILURE() << clock << " not judged";
    return -1.0;
}

}  // namespace

TEST(Timing, EachClockReducesItsOwnPerPassValues) {
    const timemodel::PassTimes times = passes({10.0, 12.0, 9.0, 11.0});
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("wall-min", times), 9.0);
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("wall-min-median", times), 10.5);  // (10 + 11) / 2
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("wall-median", times), 1.05 * 10.5);
    EXPECT_DOUBLE_EQ(timemodel::timeFromPasses("cpu", times), 3.0 * 10.5);
    EXPECT_DOUBLE_EQ(timemodel::clockStatistic("wall-min-median", {4.0, 1.0, 3.0}), 3.0);
    EXPECT_EQ(timemodel::timeFromPasses("wall-min", timemodel::PassTimes{}), 0.0);
    EXPECT_DOUBLE_EQ(timemodel::passSpread(times.leastWall), (12.0 - 9.0) / 10.5);  // (greatest − least) / median
}

TEST(Timing, SplitHalfComparesTheEvenPassesWithTheOddOnes) {
    // Even passes 10, 10; odd passes 12, 12.
    const std::vector<timemodel::PassTimes> times = {passes({10.0, 12.0, 10.0, 12.0})};
    const timemodel::ErrorStats least = timemodel::splitHalfRepeatability("wall-min", times, {true});
    ASSERT_EQ(least.count, 1u);
    EXPECT_DOUBLE_EQ(least.median, 2.0 / 10.0);  // |10 − 12| / least of all
    const timemodel::ErrorStats median = timemodel::splitHalfRepeatability("wall-min-median", times, {true});
    EXPECT_DOUBLE_EQ(median.median, 2.0 / 11.0);  // |10 − 12| / median of all
    // Excluded samples and samples with one pass are not judged.
    EXPECT_EQ(timemodel::splitHalfRepeatability("wall-min", times, {false}).count, 0u);
    EXPECT_EQ(timemodel::splitHalfRepeatability("wall-min", {passes({10.0})}, {true}).count, 0u);
}

TEST(Timing, AutoFitsTheLeastWhenASpeedJumpSplitsThePasses) {
    // The machine runs at 7 ms for the first passes and at 9.8 ms after a jump; the jump falls
    // mid-run, after the third or the fourth of seven passes depending on the sample (passes
    // interleave all samples in a shuffled order). A median over passes straddling the jump lands
    // on either level, the least stays on the fast one.
    std::vector<timemodel::PassTimes> times;
    for (int sample = 0; sample < 12; ++sample) {
        std::vector<double> least;
        const int jumpAt = 3 + sample % 2;  // passes before the jump
        for (int pass = 0; pass < 7; ++pass) least.push_back((pass < jumpAt ? 7.0 : 9.8) + 0.01 * (pass % 3));
        times.push_back(passes(least));
    }
    const timemodel::ClockChoice choice = timemodel::chooseMostRepeatableClock(times, std::vector<bool>(12, true));
    EXPECT_TRUE(choice.measured);
    EXPECT_EQ(choice.clock, "wall-min");
    ASSERT_EQ(choice.candidates.size(), 3u);  // the wall clocks; cpu is never a candidate
    EXPECT_LT(repeatabilityOf(choice, "wall-min"), 0.01);
    EXPECT_GT(repeatabilityOf(choice, "wall-min-median"), 0.1);
}

TEST(Timing, AutoFitsTheMedianOfLeastsWhenTheLeastHasALongLowerTail) {
    // Most passes' least near 10 ms, now and then one far lower (a burst of turbo, a lucky
    // cache): the least of all passes depends on whether such a pass fell in.
    std::vector<timemodel::PassTimes> times;
    for (int sample = 0; sample < 10; ++sample) {
        std::vector<double> least = {10.0, 10.1, 9.9, 10.05, 9.95, 10.02};
        least[std::size_t(sample % 2 ? 2 : 3)] = 8.0;  // in an even pass for some, odd for others
        times.push_back(passes(least));
    }
    const timemodel::ClockChoice choice = timemodel::chooseMostRepeatableClock(times, std::vector<bool>(10, true));
    EXPECT_EQ(choice.clock, "wall-min-median");
    EXPECT_GT(repeatabilityOf(choice, "wall-min"), 0.2);
    EXPECT_LT(repeatabilityOf(choice, "wall-min-median"), 0.02);
}

TEST(Timing, AutoJudgesOnlyTheIncludedSamples) {
    // Sample 0 repeats exactly on every clock; sample 1 only on the least.
    const std::vector<timemodel::PassTimes> times = {passes({10.0, 10.0, 10.0, 10.0, 10.0, 10.0}),
                                                     passes({7.0, 7.0, 7.0, 9.8, 9.8, 9.8})};
    EXPECT_EQ(timemodel::chooseMostRepeatableClock(times, {true, false}).clock, "wall-min-median");  // a tie: 0 each
    EXPECT_EQ(timemodel::chooseMostRepeatableClock(times, {false, true}).clock, "wall-min");
}

TEST(Timing, AutoKeepsTheDefaultWithOnePass) {
    const timemodel::ClockChoice choice =
        timemodel::chooseMostRepeatableClock({passes({10.0}), passes({12.0})}, {true, true});
    EXPECT_FALSE(choice.measured);
    EXPECT_EQ(choice.clock, timemodel::kDefaultTimingClock);
    EXPECT_EQ(choice.candidates.size(), 3u);
}
