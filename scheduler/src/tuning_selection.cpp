// The selection policy of `lodopt tune`: held-out views, cross-validation folds, the pick.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "scheduler/tuning.hpp"

namespace lodopt::scheduler {

std::vector<bool> heldOutViews(int count, int holdout) {
    std::vector<bool> heldOut(std::size_t(std::max(count, 0)), false);
    if (holdout < 1 || holdout >= count) return heldOut;
    const int stride = count / holdout;
    for (int j = 0; j < holdout; ++j) heldOut[std::size_t(j * stride + (stride - 1 - j % stride))] = true;
    return heldOut;
}

std::vector<int> tuningFolds(const std::vector<bool>& heldOut, int folds) {
    std::vector<int> fold(heldOut.size(), -1);
    int next = 0;
    for (std::size_t k = 0; k < heldOut.size(); ++k) {
        if (!heldOut[k]) fold[k] = next++ % std::max(folds, 1);
    }
    return fold;
}

int firstBestAbove(double floor, const std::vector<double>& scores, double margin) {
    int chosen = -1;
    double best = floor;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        if (scores[i] > best + margin) {
            chosen = int(i);
            best = scores[i];
        }
    }
    return chosen;
}

}  // namespace lodopt::scheduler
