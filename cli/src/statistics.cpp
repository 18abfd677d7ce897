#include "statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace lodopt::cli {

Spread spreadOf(std::vector<double> values) {
    Spread spread;
    if (values.empty()) return spread;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    spread.median = median(values);
    spread.p90 = values[std::min(n - 1, std::size_t(std::ceil(0.9 * double(n))) - 1)];
    spread.max = values.back();
    double sum = 0.0;
    for (double v : values) sum += v;
    spread.mean = sum / double(n);
    return spread;
}

}  // namespace lodopt::cli
