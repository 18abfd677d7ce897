#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

#include "evaluation/sweep.hpp"

namespace lodopt::evaluation {
namespace {

TEST(WorkQueueModel, HandsEachViewToTheFirstFreeRank) {
    // Views 4, 1, 1, 1, 1 s on two ranks: rank 0 takes the 4 s view, rank 1 the four short
    // ones (free at 1, 2, 3, 4 s): both end at 4 s, nobody waits.
    const std::vector<double> views = {4, 1, 1, 1, 1};
    const QueueSimulation even = simulateWorkQueue(views, 2, 0.0, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(even.makespanSeconds, 4.0);
    EXPECT_DOUBLE_EQ(even.workSeconds, 8.0);
    EXPECT_DOUBLE_EQ(even.efficiency, 1.0);
    EXPECT_DOUBLE_EQ(even.idleSeconds[0], 0.0);
    EXPECT_DOUBLE_EQ(even.idleSeconds[1], 0.0);

    // The long view last: 1, 1, 1, 1 spread two each (free at 2 s), then 4 s on rank 0: 6 s.
    const std::vector<double> tail = {1, 1, 1, 1, 4};
    const QueueSimulation late = simulateWorkQueue(tail, 2, 0.0, 0.0, 0.0);
    EXPECT_DOUBLE_EQ(late.makespanSeconds, 6.0);
    EXPECT_DOUBLE_EQ(late.efficiency, 8.0 / 12.0);
    EXPECT_DOUBLE_EQ(late.idleSeconds[1], 4.0);
}

TEST(WorkQueueModel, StartupOverheadAndMergeCountAgainstEfficiency) {
    // 4 views of 1 s on 4 ranks, 1 s scene load, 0.5 s per view, 0.5 s merge: 1 + 1.5 + 0.5 = 3 s,
    // against 1 + 4 * 1.5 + 0.5 = 7.5 s on one rank: efficiency 7.5 / (4 * 3).
    const std::vector<double> views = {1, 1, 1, 1};
    const QueueSimulation s = simulateWorkQueue(views, 4, 1.0, 0.5, 0.5);
    EXPECT_DOUBLE_EQ(s.makespanSeconds, 3.0);
    EXPECT_DOUBLE_EQ(s.efficiency, 7.5 / 12.0);
    const QueueSimulation one = simulateWorkQueue(views, 1, 1.0, 0.5, 0.5);
    EXPECT_DOUBLE_EQ(one.makespanSeconds, 7.5);
    EXPECT_DOUBLE_EQ(one.efficiency, 1.0);
}

TEST(WorkQueueModel, RefusesUnusableInput) {
    const std::vector<double> views = {1.0, -1.0};
    EXPECT_THROW(simulateWorkQueue(views, 2, 0, 0, 0), std::invalid_argument);
    EXPECT_THROW(simulateWorkQueue({}, 0, 0, 0, 0), std::invalid_argument);
    EXPECT_THROW(simulateWorkQueue({}, 1, -1, 0, 0), std::invalid_argument);
    EXPECT_DOUBLE_EQ(simulateWorkQueue({}, 3, 0, 0, 0).efficiency, 1.0);
}

}  // namespace
}  // namespace lodopt::evaluation
