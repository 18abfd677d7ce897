// lodopt tune's choice of views and coefficient sets, without running it: held-out views
// spread over the list, cross-validation folds, and the rule that picks the written set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "scheduler/tuning.hpp"

// 16 views sampled in turn around 4 named views: the 4 held out are around 4 different ones
// (the first version held out views 3, 7, 11, 15: all around the last named view).
TEST(TuneHoldout, SpreadOverTheListAndOverTheNamedViews) {
    const std::vector<bool> sixteen = lodopt::scheduler::heldOutViews(16, 4);
    std::vector<int> positions;
    for (int k = 0; k < 16; ++k) {
        if (sixteen[std::size_t(k)]) positions.push_back(k);
    }
    ASSERT_EQ(positions, (std::vector<int>{3, 6, 9, 12}));
    std::vector<bool> namedViews(4, false);
    for (int k : positions) namedViews[std::size_t(k % 4)] = true;
    EXPECT_EQ(std::count(namedViews.begin(), namedViews.end(), true), 4);
    // One per run of count / holdout views, the default quarter included; never out of range.
    for (int count = 2; count <= 40; ++count) {
        for (int holdout = 1; holdout < count; ++holdout) {
            const std::vector<bool> flags = lodopt::scheduler::heldOutViews(count, holdout);
            ASSERT_EQ(flags.size(), std::size_t(count));
            EXPECT_EQ(std::count(flags.begin(), flags.end(), true), holdout) << count << " " << holdout;
            const int stride = count / holdout;
            for (int j = 0; j < holdout; ++j) {
                EXPECT_EQ(std::count(flags.begin() + j * stride, flags.begin() + (j + 1) * stride, true), 1);
            }
        }
    }
    const std::vector<bool> none = lodopt::scheduler::heldOutViews(4, 4);  // out of range: none held out
    EXPECT_EQ(std::count(none.begin(), none.end(), true), 0);
}

TEST(TuneCrossValidation, FoldsSpreadOverTheTuningViewsAndSkipHeldOutOnes) {
    const std::vector<bool> heldOut = lodopt::scheduler::heldOutViews(16, 4);
    const std::vector<int> folds = lodopt::scheduler::tuningFolds(heldOut, 3);
    ASSERT_EQ(folds.size(), 16u);
    std::vector<int> perFold(3, 0);
    int previous = -1;
    for (std::size_t k = 0; k < 16; ++k) {
        if (heldOut[k]) {
            EXPECT_EQ(folds[k], -1) << k;
            continue;
        }
        ASSERT_GE(folds[k], 0);
        ASSERT_LT(folds[k], 3);
        EXPECT_EQ(folds[k], (previous + 1) % 3) << k;  // in turn along the list
        previous = folds[k];
        ++perFold[std::size_t(folds[k])];
    }
    EXPECT_EQ(perFold, (std::vector<int>{4, 4, 4}));
}

TEST(TuneCrossValidation, DefaultsStayUnlessATunedSetScoresBetterOutOfFold) {
    using lodopt::scheduler::firstBestAbove;
    // Cross-validation: the floor is the defaults' score.
    EXPECT_EQ(firstBestAbove(1.0, {0.99, 0.98}), -1);   // both lose: the defaults
    EXPECT_EQ(firstBestAbove(1.0, {1.0, 1.0}), -1);     // ties keep the defaults
    EXPECT_EQ(firstBestAbove(1.0, {1.01, 0.99}), 0);
    EXPECT_EQ(firstBestAbove(1.0, {1.01, 1.02}), 1);
    EXPECT_EQ(firstBestAbove(1.0, {1.02, 1.02}), 0);    // a tie between forms: the first
    EXPECT_EQ(firstBestAbove(1.0, {NAN, 1.01}), 1);     // a form without a score never wins
    EXPECT_EQ(firstBestAbove(1.0, {1.0 + 1e-13}), -1);  // within the margin
    // By tuning score: no floor, so some form is always chosen, ties to the first.
    EXPECT_EQ(firstBestAbove(-INFINITY, {0.5, 0.4}), 0);
    EXPECT_EQ(firstBestAbove(-INFINITY, {0.5, 0.5 + 1e-13}), 0);
    EXPECT_EQ(firstBestAbove(-INFINITY, {0.5, 0.6}), 1);
}
