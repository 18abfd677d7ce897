// Calibration timing statistics and the choice of the fitted clock (timing.hpp).
#include "timemodel/timing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "timemodel/profile.hpp"

namespace lodopt::timemodel {

double median(std::vector<double> values) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const std::vector<double>& perPassValues(const std::string& clock, const PassTimes& times) {
    if (clock == "cpu") return times.medianCpu;
    if (clock == "wall-median") return times.medianWall;
    return times.leastWall;
}

double clockStatistic(const std::string& clock, const std::vector<double>& perPass) {
    assert(!perPass.empty());
    return clock == "wall-min" ? *std::min_element(perPass.begin(), perPass.end()) : median(perPass);
}

double timeFromPasses(const std::string& clock, const PassTimes& times) {
    const std::vector<double>& perPass = perPassValues(clock, times);
    return perPass.empty() ? 0.0 : clockStatistic(clock, perPass);
}

double passSpread(const std::vector<double>& perPass) {
    assert(!perPass.empty());
    const auto [low, high] = std::minmax_element(perPass.begin(), perPass.end());
    return (*high - *low) / median(perPass);
}

ErrorStats splitHalfRepeatability(const std::string& clock, const std::vector<PassTimes>& times,
                                  const std::vector<bool>& include) {
    assert(include.size() == times.size());
    std::vector<double> halves;
    std::vector<double> even, odd;
    for (std::size_t i = 0; i < times.size(); ++i) {
        if (!include[i]) continue;
        const std::vector<double>& perPass = perPassValues(clock, times[i]);
        if (perPass.size() < 2) continue;
        const double all = clockStatistic(clock, perPass);
        if (!(all > 0.0)) continue;
        even.clear();
        odd.clear();
        for (std::size_t k = 0; k < perPass.size(); ++k) (k % 2 ? odd : even).push_back(perPass[k]);
        halves.push_back(std::abs(clockStatistic(clock, even) - clockStatistic(clock, odd)) / all);
    }
    return summarizeErrors(halves);
}

ClockChoice chooseMostRepeatableClock(const std::vector<PassTimes>& times, const std::vector<bool>& include) {
    ClockChoice choice;
    choice.clock = kDefaultTimingClock;
    double best = 0.0;
    for (const char* clock : {"wall-min-median", "wall-min", "wall-median"}) {
        const ErrorStats repeatability = splitHalfRepeatability(clock, times, include);
        choice.candidates.push_back({clock, repeatability});
        if (repeatability.count == 0) continue;
        if (!choice.measured || repeatability.median < best) {
            choice.clock = clock;
            best = repeatability.median;
            choice.measured = true;
        }
    }
    return choice;
}

}  // namespace lodopt::timemodel
