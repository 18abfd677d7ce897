#include "statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace lodopt::cli {

namespace {

// `sorted` non-empty.
double middleOf(const std::vector<double>& sorted) {
    const std::size_t n = sorted.size();
    return n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

}  // namespace

double median(std::vector<double> values) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    return middleOf(values);
}

Spread spreadOf(std::vector<double> values) {
    Spread spread;
    if (values.empty()) return spread;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    spread.median = middleOf(values);
    spread.p90 = values[std::min(n - 1, std::size_t(std::ceil(0.9 * double(n))) - 1)];
    spread.max = values.back();
    double sum = 0.0;
    for (double v : values) sum += v;
    spread.mean = sum / double(n);
    return spread;
}

}  // namespace lodopt::cli
