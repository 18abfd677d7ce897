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
// levels differ in silhouette, hides less (forest `edge`: 43 % to 35 %).
#pragma once

#include <cstddef>
#include <vector>

#include "evaluation/evaluation.hpp"

namespace lodopt::evaluation::detail {

class VisibilityBounds {
public:
    // Every object of the scene takes part as an occluder: searched ones over their option
    // levels, skipped ones at their fixed level.
    explicit VisibilityBounds(const ViewSetup& setup);

    // True when a fragment of `object` at `depth` on pixel `pixel` (row-major index) may be the
    // nearest in some combination: it covers the pixel, and no other object is always in front
    // of it there. Equal depths count as possibly visible (ties go by object order).
    bool canShow(std::size_t pixel, int object, float depth) const {
        return depth < 1.0f && depth <= (mOccluder[pixel] == object ? mSecond[pixel] : mNearest[pixel]);
    }

private:
    // Per pixel, the nearest "always covers, at most this deep" bound, the object giving it,
    // and the nearest bound of any other object.
    std::vector<float> mNearest, mSecond;
    std::vector<int> mOccluder;
};

}  // namespace lodopt::evaluation::detail
