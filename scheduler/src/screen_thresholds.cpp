#include "scheduler/screen_thresholds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lodopt::scheduler {

int levelForScreenSize(std::span<const double> thresholds, double screenSize) {
    for (std::size_t k = 0; k < thresholds.size(); ++k) {
        if (screenSize >= thresholds[k]) return int(k);
    }
    return int(thresholds.size());
}

namespace {

void checkSamples(std::span<const ThresholdSample> samples, int levelCount) {
    if (levelCount < 1) throw std::invalid_argument("fitScreenThresholds: levelCount must be >= 1");
    for (std::size_t j = 0; j < samples.size(); ++j) {
        const ThresholdSample& s = samples[j];
        if (!(std::isfinite(s.screenSize) && s.screenSize > 0.0) || s.level < 0 || s.level >= levelCount ||
            !(std::isfinite(s.weight) && s.weight >= 0.0)) {
            throw std::invalid_argument("fitScreenThresholds: sample " + std::to_string(j) +
                                        " needs a finite screen size > 0, a level in [0, " +
                                        std::to_string(levelCount) + ") and a finite weight >= 0");
        }
    }
}

void checkPricedSamples(std::span<const PricedSample> samples, int levelCount) {
    if (levelCount < 1) throw std::invalid_argument("fitScreenThresholds: levelCount must be >= 1");
    for (std::size_t j = 0; j < samples.size(); ++j) {
        const PricedSample& s = samples[j];
        const bool finiteCosts = std::all_of(s.levelCost.begin(), s.levelCost.end(), [](double c) { return std::isfinite(c); });
        if (!(std::isfinite(s.screenSize) && s.screenSize > 0.0) || s.levelCost.size() != std::size_t(levelCount) ||
            !finiteCosts) {
            throw std::invalid_argument("fitScreenThresholds: priced sample " + std::to_string(j) +
                                        " needs a finite screen size > 0 and " + std::to_string(levelCount) +
                                        " finite level costs");
        }
    }
}

// Samples of equal screen size, in decreasing size: per level, the group's summed cost.
struct Group {
    double screenSize = 0.0;
    std::vector<double> cost;
};

std::vector<Group> groupBySize(std::span<const PricedSample> samples, int levelCount) {
    std::vector<const PricedSample*> sorted;
    for (const PricedSample& s : samples) sorted.push_back(&s);
    // A total order (size, then the costs), so each group sums its costs in one order whatever
    // order the samples came in.
    std::sort(sorted.begin(), sorted.end(), [](const PricedSample* a, const PricedSample* b) {
        if (a->screenSize != b->screenSize) return a->screenSize > b->screenSize;
        return a->levelCost < b->levelCost;
    });
    std::vector<Group> groups;
    for (const PricedSample* s : sorted) {
        if (groups.empty() || groups.back().screenSize != s->screenSize) {
            groups.push_back({s->screenSize, std::vector<double>(std::size_t(levelCount), 0.0)});
        }
        for (std::size_t k = 0; k < std::size_t(levelCount); ++k) groups.back().cost[k] += s->levelCost[k];
    }
    return groups;
}

}  // namespace

ThresholdFit fitScreenThresholdsToCosts(std::span<const PricedSample> samples, int levelCount) {
    checkPricedSamples(samples, levelCount);
    ThresholdFit fit;
    const auto levels = std::size_t(levelCount);
    if (samples.empty()) {
        for (std::size_t k = 0; k + 1 < levels; ++k) fit.thresholds.push_back(std::ldexp(1.0, -int(k)));
        return fit;
    }
    const std::vector<Group> groups = groupBySize(samples, levelCount);
    // best[g][k]: the least cost of groups 0..g with group g at level k (levels non-decreasing
    // with g); from[g][k]: group g-1's level on that path.
    std::vector<std::vector<double>> best(groups.size(), std::vector<double>(levels));
    std::vector<std::vector<int>> from(groups.size(), std::vector<int>(levels, 0));
    best[0] = groups[0].cost;
    for (std::size_t g = 1; g < groups.size(); ++g) {
        double runningMin = std::numeric_limits<double>::infinity();
        int runningLevel = 0;
        for (std::size_t k = 0; k < levels; ++k) {
            if (best[g - 1][k] < runningMin) {  // ties keep the finer level: the smaller threshold set
                runningMin = best[g - 1][k];
                runningLevel = int(k);
            }
            best[g][k] = runningMin + groups[g].cost[k];
            from[g][k] = runningLevel;
        }
    }
    std::vector<int> assigned(groups.size());
    const auto last = groups.size() - 1;
    assigned[last] = int(std::min_element(best[last].begin(), best[last].end()) - best[last].begin());
    fit.cost = best[last][std::size_t(assigned[last])];
    for (std::size_t g = last; g > 0; --g) assigned[g - 1] = from[g][std::size_t(assigned[g])];

    // t_k sits where the assigned level first exceeds k.
    for (std::size_t k = 0; k + 1 < levels; ++k) {
        std::size_t firstCoarser = 0;
        while (firstCoarser < groups.size() && assigned[firstCoarser] <= int(k)) ++firstCoarser;
        double threshold = 0.0;
        if (firstCoarser == 0) {
            threshold = 2.0 * groups.front().screenSize;  // no sample at level <= k
        } else if (firstCoarser == groups.size()) {
            threshold = 0.5 * groups.back().screenSize;  // every sample at level <= k
        } else {
            threshold = std::sqrt(groups[firstCoarser - 1].screenSize * groups[firstCoarser].screenSize);
        }
        fit.thresholds.push_back(threshold);
    }
    double agreeing = 0.0;
    for (const PricedSample& s : samples) {
        fit.totalWeight += 1.0;
        const auto cheapest = std::min_element(s.levelCost.begin(), s.levelCost.end()) - s.levelCost.begin();
        if (levelForScreenSize(fit.thresholds, s.screenSize) == int(cheapest)) agreeing += 1.0;
    }
    fit.agreement = agreeing / fit.totalWeight;
    return fit;
}

ThresholdFit fitScreenThresholds(std::span<const ThresholdSample> samples, int levelCount) {
    checkSamples(samples, levelCount);
    std::vector<PricedSample> priced;
    priced.reserve(samples.size());
    for (const ThresholdSample& s : samples) {
        PricedSample p{s.screenSize, std::vector<double>(std::size_t(levelCount))};
        for (int k = 0; k < levelCount; ++k) p.levelCost[std::size_t(k)] = s.weight * std::abs(k - s.level);
        priced.push_back(std::move(p));
    }
    ThresholdFit fit = fitScreenThresholdsToCosts(priced, levelCount);
    double agreeing = 0.0;
    fit.totalWeight = 0.0;
    for (const ThresholdSample& s : samples) {
        fit.totalWeight += s.weight;
        if (levelForScreenSize(fit.thresholds, s.screenSize) == s.level) agreeing += s.weight;
    }
    fit.agreement = fit.totalWeight > 0.0 ? agreeing / fit.totalWeight : 1.0;
    return fit;
}

}  // namespace lodopt::scheduler
