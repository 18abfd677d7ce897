// The summary statistics the commands report, one definition each.
#pragma once

#include <vector>

namespace lodopt::cli {

// Middle value, the mean of the two middle ones for an even count; NaN for an empty list (JSON
// null), so that a missing median never reads as a measured 0.
double median(std::vector<double> values);

// Median, 90th percentile (nearest rank), max and mean of `values` (all 0 for an empty list:
// the schedule's per-frame columns, where no frame means nothing was spent).
struct Spread {
    double median = 0.0, p90 = 0.0, max = 0.0, mean = 0.0;
};
Spread spreadOf(std::vector<double> values);

}  // namespace lodopt::cli
