// LOD-switch control: the VMI20 §7 ranges and the parameters (see scheduler/switch_control.hpp;
// the hysteresis rule's passes are in scheduler.cpp, inside the decision).
#include "scheduler/switch_control.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>

namespace lodopt::scheduler {

namespace {

void check(bool ok, const char* name, double value, const char* rule) {
    if (!ok) {
        throw std::invalid_argument(std::string("switch control: ") + name + " = " + std::to_string(value) +
                                    ", must be " + rule);
    }
}

}  // namespace

const char* toString(SwitchRule rule) {
    return rule == SwitchRule::Vmi20 ? "vmi20" : "hysteresis";
}

void validateSwitchControl(const SwitchControlParameters& p) {
    check(std::isfinite(p.raiseMargin) && p.raiseMargin >= 0.0 && p.raiseMargin < 1.0, "raiseMargin", p.raiseMargin,
          "in [0, 1)");
    check(std::isfinite(p.refillBelow) && p.refillBelow >= 0.0 && p.refillBelow < 1.0, "refillBelow", p.refillBelow,
          "in [0, 1)");
    check(std::isfinite(p.delta1) && p.delta1 > 0.0, "delta1", p.delta1, "finite and > 0");
    check(std::isfinite(p.k1) && p.k1 >= 0.0, "k1", p.k1, "finite and >= 0");
    check(std::isfinite(p.delta2) && p.delta2 >= 0.0, "delta2", p.delta2, "finite and >= 0");
    check(std::isfinite(p.k2) && p.k2 >= 0.0, "k2", p.k2, "finite and >= 0");
    check(std::isfinite(p.nearDistance) && p.nearDistance >= 0.0, "near", p.nearDistance, "finite and >= 0");
}

std::vector<double> simplificationRates(const std::vector<double>& triangles) {
    std::vector<double> rates(triangles.size(), 0.0);
    if (triangles.empty() || triangles[0] <= 0.0) return rates;
    for (std::size_t l = 0; l < triangles.size(); ++l)
        rates[l] = std::clamp(1.0 - triangles[l] / triangles[0], 0.0, 1.0);
    return rates;
}

LevelRange allowedLevels(int current, double secondsSinceSwitch, double distance, const std::vector<double>& rates,
                         const SwitchControlParameters& p) {
    const int levels = int(rates.size());
    assert(current >= 0 && current < levels);
    if (!p.enabled || p.rule != SwitchRule::Vmi20) return {0, levels - 1};
    const double x = std::max(distance - p.nearDistance, 0.0);
    // 0^0 = 1 in std::pow, so k = 0 gives the constant bound δ, as the formula reads.
    const double dwell = p.delta2 * std::pow(x, p.k2);
    if (!(secondsSinceSwitch > dwell)) return {current, current};
    const double maxRateChange = p.delta1 * std::pow(x, p.k1);
    LevelRange range{current, current};
    // One step each way always; further while the rate change stays under the bound.
    if (current > 0) range.finest = current - 1;
    while (range.finest > 0 && std::abs(rates[range.finest - 1] - rates[current]) < maxRateChange) --range.finest;
    if (current + 1 < levels) range.coarsest = current + 1;
    while (range.coarsest + 1 < levels && std::abs(rates[range.coarsest + 1] - rates[current]) < maxRateChange) {
        ++range.coarsest;
    }
    return range;
}

}  // namespace lodopt::scheduler
