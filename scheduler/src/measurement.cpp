#include "scheduler/measurement.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace lodopt::scheduler {

double bandCeiling(std::span<const double> measurements, double tolerance) {
    if (!(tolerance > 0.0 && tolerance < 1.0)) throw std::invalid_argument("bandCeiling: tolerance must be in (0, 1)");
    std::vector<double> times;
    for (double t : measurements) {
        if (std::isfinite(t) && t > 0.0) times.push_back(t);
    }
    if (times.empty()) return 0.0;
    std::sort(times.begin(), times.end());
    // A band [(1 − t)B, (1 + t)B] holding times[i] as its least member holds everything up to
    // times[i] · (1 + t) / (1 − t); the best band has some measurement at its lower end.
    const double ratio = (1.0 + tolerance) / (1.0 - tolerance);
    std::size_t best = 0, end = 0;
    for (std::size_t i = 0; i < times.size(); ++i) {
        end = std::max(end, i);
        while (end < times.size() && times[end] <= times[i] * ratio) ++end;
        best = std::max(best, end - i);
    }
    return double(best) / double(times.size());
}

}  // namespace lodopt::scheduler
