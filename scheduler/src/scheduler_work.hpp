// Scratch buffers of one FrameScheduler, kept between frames so a decision does not allocate.
#pragma once

#include <algorithm>
#include <vector>

#include "scheduler/scheduler.hpp"

namespace lodopt::scheduler {

// A decision's levels and feature sums, kept to go back to (no allocation once reserved).
struct SavedDecision {
    std::vector<int> levels;
    timemodel::FrameFeatures features;

    void save(const FrameDecision& d) {
        levels.assign(d.levels.begin(), d.levels.end());
        features = d.features;
    }
    void restore(FrameDecision& d) const {
        std::copy(levels.begin(), levels.end(), d.levels.begin());
        d.features = features;
    }
};

struct FrameScheduler::Work {
    std::vector<int> visible;          // visible objects (tiles: leaf by leaf, nearest leaf first)
    std::vector<int> leafEnds;         // tiles: end of each leaf's run in `visible`
    std::vector<int> leaves;           // tiles: visible leaves, nearest first
    std::vector<double> leafDistance;  // tiles: scratch of Quadtree::visibleLeaves
    std::vector<int> order;            // processing order
    std::vector<double> denominators;  // per entry of `visible`
    std::vector<double> scratch;
    timemodel::FrameFeatures trial;
    SavedDecision held;            // the refill's hysteresis decision, kept for comparison
    SavedDecision beforeExchange;  // the decision before a trial exchange

    void reserve(std::size_t objects) {
        visible.reserve(objects);
        leafEnds.reserve(objects);
        leaves.reserve(objects);
        order.reserve(objects);
        denominators.reserve(objects);
        scratch.reserve(objects);
        held.levels.reserve(objects);
        beforeExchange.levels.reserve(objects);
    }
};

}  // namespace lodopt::scheduler
