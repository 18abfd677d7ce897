// Scratch buffers of one FrameScheduler, kept between frames so a decision does not allocate.
#pragma once

#include <vector>

#include "scheduler/scheduler.hpp"

namespace lodopt::scheduler {

struct FrameScheduler::Work {
    std::vector<int> visible;          // visible objects (tiles: leaf by leaf, nearest leaf first)
    std::vector<int> leafEnds;         // tiles: end of each leaf's run in `visible`
    std::vector<int> leaves;           // tiles: visible leaves, nearest first
    std::vector<double> leafDistance;  // tiles: scratch of Quadtree::visibleLeaves
    std::vector<int> order;            // processing order
    std::vector<double> denominators;  // per entry of `visible`
    std::vector<double> scratch;
    timemodel::FrameFeatures trial;
    std::vector<int> heldLevels;  // the refill's hysteresis decision, kept for comparison
    timemodel::FrameFeatures heldFeatures;
    std::vector<int> exchangeLevels;  // the decision before a trial exchange
    timemodel::FrameFeatures exchangeFeatures;

    void reserve(std::size_t objects) {
        visible.reserve(objects);
        leafEnds.reserve(objects);
        leaves.reserve(objects);
        order.reserve(objects);
        denominators.reserve(objects);
        scratch.reserve(objects);
        heldLevels.reserve(objects);
        exchangeLevels.reserve(objects);
    }
};

}  // namespace lodopt::scheduler
