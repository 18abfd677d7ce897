#include "scheduler/measurement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using lodopt::scheduler::bandCeiling;

TEST(BandCeiling, IdenticalMeasurementsAllFitOneBand) {
    const std::vector<double> times(20, 4.0);
    EXPECT_DOUBLE_EQ(bandCeiling(times), 1.0);
}

TEST(BandCeiling, CountsTheBestWindowOfWidthElevenNinths) {
    // 10, 12.2 and 12.3: a band holding 10 reaches 10 * 1.1 / 0.9 = 12.22..., so 12.2 is in and
    // 12.3 out; the band starting at 12.2 holds 12.2, 12.3 and 14.9 but not 15.
    const std::vector<double> times = {10.0, 12.2, 12.3, 14.9, 15.0};
    EXPECT_DOUBLE_EQ(bandCeiling(times), 3.0 / 5.0);
    // A tighter tolerance: (1.05 / 0.95) = 1.105..., each band holds two at most.
    EXPECT_DOUBLE_EQ(bandCeiling(times, 0.05), 2.0 / 5.0);
}

TEST(BandCeiling, IgnoresWhatIsNotATime) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<double> times = {nan, -1.0, 0.0, 5.0, 5.1, 9.0};
    EXPECT_DOUBLE_EQ(bandCeiling(times), 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(bandCeiling(std::vector<double>{nan, 0.0}), 0.0);
    EXPECT_THROW(bandCeiling(times, 0.0), std::invalid_argument);
    EXPECT_THROW(bandCeiling(times, 1.0), std::invalid_argument);
}

TEST(BandCeiling, BoundsWhatAnyTargetAchievesOnScatteredMeasurements) {
    // Multiplicative scatter of ±20 % (uniform): whatever the frame's true time, the share of
    // its measurements within ±10 % of a budget is at most the ceiling, and a target at the
    // best ratio reaches it.
    std::mt19937 random(7);
    std::uniform_real_distribution<double> scatter(0.8, 1.2);
    std::vector<double> noise(400);
    for (double& n : noise) n = scatter(random);
    const double ceiling = bandCeiling(noise);
    EXPECT_GT(ceiling, 0.4);
    EXPECT_LT(ceiling, 0.6);  // (1.1/0.9 − 1) spans about half of a ±20 % uniform scatter
    double bestShare = 0.0;
    for (double trueTime = 5.0; trueTime <= 15.0; trueTime += 0.01) {
        int within = 0;
        for (double n : noise) within += std::abs(trueTime * n - 10.0) <= 1.0 ? 1 : 0;
        const double share = double(within) / double(noise.size());
        EXPECT_LE(share, ceiling + 1e-12) << "true time " << trueTime;
        bestShare = std::max(bestShare, share);
    }
    EXPECT_NEAR(bestShare, ceiling, 0.02);
}
