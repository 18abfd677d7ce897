// Tile organisation of the scheduler: the quadtree walk and the two-phase selection of
// "A virtual globe-based time-critical adaptive visualization method for 3D city models",
// Int. J. Digital Earth 2017 (CITY17), Algorithms 1 and 2 (method.md §6). See scheduler.hpp.
#include <algorithm>
#include <cmath>

#include "scheduler/scheduler.hpp"
#include "scheduler_work.hpp"

namespace lodopt::scheduler {

void FrameScheduler::observeTiles() {
    Work& w = *mWork;
    w.visible.clear();
    w.leafEnds.clear();
    // Culled tiles take their objects with them: those objects are never looked at.
    mQuadtree->visibleLeaves(mFrame.frustum, mFrame.camera.position, w.leaves, w.leafDistance);
    const std::vector<int>& objects = mQuadtree->objects();
    for (int leaf : w.leaves) {
        const Quadtree::Tile& tile = mQuadtree->tiles()[leaf];
        for (int k = tile.firstObject; k < tile.firstObject + tile.objectCount; ++k) {
            if (mIndex.observe(objects[k], mFrame)) w.visible.push_back(objects[k]);
        }
        w.leafEnds.push_back(int(w.visible.size()));
    }
}

void FrameScheduler::decideTiles() {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    const double budget = mParameters.budgetMs;
    // Within each leaf (already nearest first), decreasing importance.
    w.order.assign(w.visible.begin(), w.visible.end());
    int begin = 0;
    for (int end : w.leafEnds) {
        std::sort(w.order.begin() + begin, w.order.begin() + end, [&](int a, int b) {
            return mImportance[a] != mImportance[b] ? mImportance[a] > mImportance[b] : a < b;
        });
        begin = end;
    }

    // Algorithm 1: add objects at their coarsest allowed level while the budget lasts.
    int drawn = 0;
    for (int o : w.order) {
        const int level = mIndex.levelCount(o) - 1;
        w.trial = d.features;
        w.trial += contribution(o, level);
        const double added = estimate(w.trial);
        if (added > budget) break;
        setLevel(o, level);
        ++drawn;
    }

    // Algorithm 2: raise toward the distance level; when a step does not fit, stop there or
    // drop the last drawn objects, whichever loses fewer pixels.
    const int coarsestLimit = std::max(1, int(std::ceil(mParameters.coarsestShare * drawn)));
    int atCoarsest = 0;
    int end = drawn;  // w.order[end..] are not drawn
    for (int i = 0; i < end; ++i) {
        if (atCoarsest >= coarsestLimit) break;  // the rest stay coarsest
        const int o = w.order[i];
        const int target = mInitial[o];
        const std::vector<double>& rates = mIndex.rates(o);
        const double pixels = mFrame.views[o].projectedPixels;
        while (d.levels[o] > target) {
            const int level = d.levels[o];
            w.trial = d.features;
            w.trial += contribution(o, level - 1);
            w.trial -= contribution(o, level);
            double raised = estimate(w.trial);
            if (raised <= budget) {
                setLevel(o, level - 1);
                continue;
            }
            const double stayLoss = pixels * (rates[level] - rates[level - 1]);
            double dropLoss = 0.0;
            int k = end;
            // Dropping more than the stop would lose is never chosen: stop scanning there.
            while (k > i + 1 && raised > budget && dropLoss < stayLoss) {
                --k;
                w.trial -= contribution(w.order[k], d.levels[w.order[k]]);
                dropLoss += mFrame.views[w.order[k]].projectedPixels;
                raised = estimate(w.trial);
            }
            if (raised > budget || !(dropLoss < stayLoss)) break;  // stop at this level
            for (int j = k; j < end; ++j) setLevel(w.order[j], scenes::kNotDrawn);
            end = k;
            setLevel(o, level - 1);
        }
        // Counted only when the budget held it there: an object whose distance level is its
        // coarsest sits there by choice, and counting it would end the raising after the first
        // far tiles, with most of the budget unused.
        if (d.levels[o] == mIndex.levelCount(o) - 1 && target < d.levels[o]) ++atCoarsest;
    }
}

}  // namespace lodopt::scheduler
