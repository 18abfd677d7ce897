#include "scheduler/screen_thresholds.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace lodopt::scheduler {
namespace {

TEST(ScreenThresholds, TheRuleTakesTheFirstThresholdTheSizeReaches) {
    const std::vector<double> thresholds = {0.5, 0.2, 0.01};
    EXPECT_EQ(levelForScreenSize(thresholds, 0.9), 0);
    EXPECT_EQ(levelForScreenSize(thresholds, 0.5), 0);  // at the threshold: the finer level
    EXPECT_EQ(levelForScreenSize(thresholds, 0.3), 1);
    EXPECT_EQ(levelForScreenSize(thresholds, 0.01), 2);
    EXPECT_EQ(levelForScreenSize(thresholds, 0.001), 3);
    EXPECT_EQ(levelForScreenSize({}, 0.5), 0);
}

TEST(ScreenThresholds, FitsAMonotoneRuleAtTheLeastWeightedLevelError) {
    // Sorted by size: 0.8 and 0.5 chose level 0, 0.3 level 1, 0.2 level 0 (weight 0.1), 0.1 and
    // 0.05 level 2. No rule gives level 0 at 0.2 below a level 1 at 0.3: moving 0.2 to level 1
    // costs 0.1, moving 0.3 to level 0 costs 1. Thresholds between 0.5 and 0.3 and between 0.2
    // and 0.1, at their geometric means.
    const std::vector<ThresholdSample> samples = {{0.3, 1, 1.0}, {0.8, 0, 1.0}, {0.1, 2, 1.0},
                                                  {0.2, 0, 0.1}, {0.05, 2, 1.0}, {0.5, 0, 1.0}};
    const ThresholdFit fit = fitScreenThresholds(samples, 3);
    ASSERT_EQ(fit.thresholds.size(), 2u);
    EXPECT_NEAR(fit.thresholds[0], std::sqrt(0.5 * 0.3), 1e-12);
    EXPECT_NEAR(fit.thresholds[1], std::sqrt(0.2 * 0.1), 1e-12);
    EXPECT_NEAR(fit.cost, 0.1, 1e-12);
    EXPECT_NEAR(fit.totalWeight, 5.1, 1e-12);
    EXPECT_NEAR(fit.agreement, 5.0 / 5.1, 1e-12);
}

TEST(ScreenThresholds, LevelsNeverChosenGetThresholdsOutsideTheSamples) {
    // Every sample at level 2 of 4: t0 and t1 above the largest size, t2 below the smallest.
    const std::vector<ThresholdSample> samples = {{0.4, 2, 1.0}, {0.1, 2, 1.0}};
    const ThresholdFit fit = fitScreenThresholds(samples, 4);
    ASSERT_EQ(fit.thresholds.size(), 3u);
    EXPECT_DOUBLE_EQ(fit.thresholds[0], 0.8);
    EXPECT_DOUBLE_EQ(fit.thresholds[1], 0.8);
    EXPECT_DOUBLE_EQ(fit.thresholds[2], 0.05);
    EXPECT_EQ(fit.agreement, 1.0);
    // No samples: a default halving chain; one level: no threshold.
    EXPECT_EQ(fitScreenThresholds({}, 3).thresholds, (std::vector<double>{1.0, 0.5}));
    EXPECT_TRUE(fitScreenThresholds(samples, 3).thresholds.size() == 2u);
    const std::vector<ThresholdSample> one = {{0.3, 0, 1.0}};
    EXPECT_TRUE(fitScreenThresholds(one, 1).thresholds.empty());
}

TEST(ScreenThresholds, EqualSizesShareALevel) {
    // Two samples at the same size chose 0 (weight 1) and 1 (weight 3): both get level 1.
    const std::vector<ThresholdSample> samples = {{0.2, 0, 1.0}, {0.2, 1, 3.0}};
    const ThresholdFit fit = fitScreenThresholds(samples, 2);
    EXPECT_EQ(levelForScreenSize(fit.thresholds, 0.2), 1);
    EXPECT_DOUBLE_EQ(fit.cost, 1.0);
}

// Every non-decreasing assignment of levels to the distinct sizes, the least summed cost: the
// DP's answer must equal it on random instances.
double bruteForceCost(const std::vector<PricedSample>& samples, int levels) {
    std::vector<double> sizes;
    for (const PricedSample& s : samples) sizes.push_back(s.screenSize);
    std::sort(sizes.rbegin(), sizes.rend());
    sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
    double best = std::numeric_limits<double>::infinity();
    std::vector<int> assignment(sizes.size(), 0);
    std::function<void(std::size_t, int)> visit = [&](std::size_t g, int low) {
        if (g == sizes.size()) {
            double total = 0.0;
            for (const PricedSample& s : samples) {
                const auto at = std::find(sizes.begin(), sizes.end(), s.screenSize) - sizes.begin();
                total += s.levelCost[std::size_t(assignment[std::size_t(at)])];
            }
            best = std::min(best, total);
            return;
        }
        for (int k = low; k < levels; ++k) {
            assignment[g] = k;
            visit(g + 1, k);
        }
    };
    visit(0, 0);
    return best;
}

// The level error w |k - level| as per-level costs.
std::vector<PricedSample> levelErrors(const std::vector<ThresholdSample>& samples, int levels) {
    std::vector<PricedSample> priced;
    for (const ThresholdSample& s : samples) {
        PricedSample p{s.screenSize, {}};
        for (int k = 0; k < levels; ++k) p.levelCost.push_back(s.weight * std::abs(k - s.level));
        priced.push_back(p);
    }
    return priced;
}

TEST(ScreenThresholds, MatchesExhaustiveSearchOnRandomInstances) {
    std::mt19937 random(7);
    for (int instance = 0; instance < 200; ++instance) {
        const int levels = 1 + int(random() % 4);
        const int count = 1 + int(random() % 7);
        std::vector<ThresholdSample> samples;
        for (int j = 0; j < count; ++j) {
            samples.push_back({0.01 * double(1 + random() % 5), int(random() % levels), double(random() % 4)});
        }
        const ThresholdFit fit = fitScreenThresholds(samples, levels);
        EXPECT_NEAR(fit.cost, bruteForceCost(levelErrors(samples, levels), levels), 1e-9) << "instance " << instance;
        // The thresholds reproduce the cost and never increase.
        double ruleCost = 0.0;
        for (const ThresholdSample& s : samples) {
            ruleCost += s.weight * std::abs(levelForScreenSize(fit.thresholds, s.screenSize) - s.level);
        }
        EXPECT_NEAR(ruleCost, fit.cost, 1e-9) << "instance " << instance;
        EXPECT_TRUE(std::is_sorted(fit.thresholds.rbegin(), fit.thresholds.rend())) << "instance " << instance;
    }
}

// The priced fit against every non-decreasing assignment on random instances with arbitrary
// (also negative) level costs.
TEST(ScreenThresholds, PricedFitMatchesExhaustiveSearchOnRandomInstances) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> cost(-1.0, 2.0);
    for (int instance = 0; instance < 200; ++instance) {
        const int levels = 1 + int(random() % 4);
        const int count = 1 + int(random() % 6);
        std::vector<PricedSample> samples;
        for (int j = 0; j < count; ++j) {
            PricedSample sample{0.01 * double(1 + random() % 4), {}};
            for (int k = 0; k < levels; ++k) sample.levelCost.push_back(cost(random));
            samples.push_back(sample);
        }
        const ThresholdFit fit = fitScreenThresholdsToCosts(samples, levels);
        EXPECT_NEAR(fit.cost, bruteForceCost(samples, levels), 1e-9) << "instance " << instance;
        double ruleCost = 0.0;
        for (const PricedSample& s : samples) {
            ruleCost += s.levelCost[std::size_t(levelForScreenSize(fit.thresholds, s.screenSize))];
        }
        EXPECT_NEAR(ruleCost, fit.cost, 1e-9) << "instance " << instance;
        EXPECT_TRUE(std::is_sorted(fit.thresholds.rbegin(), fit.thresholds.rend())) << "instance " << instance;
    }
}

TEST(ScreenThresholds, PricedFitHandWorked) {
    // Level 1 is cheapest at 0.5 and 0.3, level 0 at 0.8, level 2 at 0.1: thresholds between.
    const std::vector<PricedSample> samples = {{0.8, {0.0, 0.2, 0.5}},
                                               {0.5, {0.1, 0.0, 0.3}},
                                               {0.3, {0.2, 0.0, 0.1}},
                                               {0.1, {0.4, 0.1, 0.0}}};
    const ThresholdFit fit = fitScreenThresholdsToCosts(samples, 3);
    ASSERT_EQ(fit.thresholds.size(), 2u);
    EXPECT_NEAR(fit.thresholds[0], std::sqrt(0.8 * 0.5), 1e-12);
    EXPECT_NEAR(fit.thresholds[1], std::sqrt(0.3 * 0.1), 1e-12);
    EXPECT_DOUBLE_EQ(fit.cost, 0.0);
    EXPECT_DOUBLE_EQ(fit.agreement, 1.0);
    // A sample that prefers a finer level at a smaller size than another's coarser choice costs
    // the cheaper of the two ways to stay monotone.
    const std::vector<PricedSample> crossing = {{0.5, {1.0, 0.0}}, {0.3, {0.0, 0.3}}};
    const ThresholdFit monotone = fitScreenThresholdsToCosts(crossing, 2);
    EXPECT_DOUBLE_EQ(monotone.cost, 0.3);  // both at level 1 (0 + 0.3), not both at 0 (1 + 0)
    EXPECT_EQ(levelForScreenSize(monotone.thresholds, 0.5), 1);
    EXPECT_EQ(levelForScreenSize(monotone.thresholds, 0.3), 1);
    EXPECT_THROW(fitScreenThresholdsToCosts(std::vector<PricedSample>{{0.1, {0.0}}}, 2), std::invalid_argument);
    EXPECT_THROW(fitScreenThresholdsToCosts(std::vector<PricedSample>{{0.1, {0.0, NAN}}}, 2), std::invalid_argument);
    EXPECT_THROW(fitScreenThresholdsToCosts(std::vector<PricedSample>{{0.0, {0.0, 1.0}}}, 2), std::invalid_argument);
}

TEST(ScreenThresholds, RefusesUnusableSamples) {
    const std::vector<std::vector<ThresholdSample>> bad = {
        {{0.0, 0, 1.0}}, {{-1.0, 0, 1.0}}, {{NAN, 0, 1.0}}, {{0.1, 3, 1.0}}, {{0.1, -1, 1.0}}, {{0.1, 0, -1.0}},
        {{0.1, 0, INFINITY}}};
    for (const auto& samples : bad) EXPECT_THROW(fitScreenThresholds(samples, 3), std::invalid_argument);
    EXPECT_THROW(fitScreenThresholds({}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace lodopt::scheduler
