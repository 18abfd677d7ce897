// Where an object's levels can show at all, whatever the other objects' levels.
//
// The fast path's caches (owned windows, window groups) rest on one fact: a pixel's composited
// color is a function of the levels of the objects whose fragments can be the nearest there.
// Covering a pixel is not enough to matter: an object Y that covers pixel p at every level it
// can take, at depth at most D (its farthest level there), hides there every fragment of
// another object lying strictly behind D, in every combination. Such a fragment never wins the
// depth test and never changes which fragment does, so the pixel does not depend on its
// object's level. Buildings hide most of what stands behind them (city `street` at 512²: SSIM
// windows that depend on two or more objects fall from 31 % to 17 % of all); foliage, whose
// levels differ in silhouette, hides less (forest `edge`: 43 % to 35 %). Blended surfaces write
// no depth: they can show (Layer::depth covers them) but hide nothing (Layer::occluderDepth).
#pragma once

#include <cstddef>
#include <vector>

#include "evaluation/evaluation.hpp"

namespace lodopt::evaluation::detail {

// Per pixel, the smallest and second smallest depth offered, and the object that offered the
// smallest (each object offers at most once per pixel): "the nearest of the other objects" is
// one lookup. ViewSetup's hidden-object test and VisibilityBounds both keep one.
class NearestTwo {
public:
    explicit NearestTwo(std::size_t pixels) : mNearest(pixels, 1.0f), mSecond(pixels, 1.0f), mObject(pixels, -1) {}
    void offer(std::size_t pixel, float depth, int object) {
        if (depth < mNearest[pixel]) {
            mSecond[pixel] = mNearest[pixel];
            mNearest[pixel] = depth;
            mObject[pixel] = object;
        } else if (depth < mSecond[pixel]) {
            mSecond[pixel] = depth;
        }
    }
    // The smallest depth offered at `pixel` by an object other than `object` (1 when none).
    float nearestOtherThan(std::size_t pixel, int object) const {
        return mObject[pixel] == object ? mSecond[pixel] : mNearest[pixel];
    }

private:
    std::vector<float> mNearest, mSecond;
    std::vector<int> mObject;
};

class VisibilityBounds {
public:
    // Every object of the scene takes part as an occluder: searched ones over their option
    // levels, skipped ones at their fixed level.
    explicit VisibilityBounds(const ViewSetup& setup);

    // True when a fragment of `object` at `depth` on pixel `pixel` (row-major index) may be the
    // nearest in some combination: it covers the pixel, and no other object is always in front
    // of it there. Equal depths count as possibly visible (ties go by object order).
    bool canShow(std::size_t pixel, int object, float depth) const {
        return depth < 1.0f && depth <= mBounds.nearestOtherThan(pixel, object);
    }

private:
    // Per pixel, the "always covers, at most this deep" bounds the objects offer.
    NearestTwo mBounds;
};

}  // namespace lodopt::evaluation::detail
