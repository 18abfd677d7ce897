// The summary statistics the commands report, one definition each.
#pragma once

#include <vector>

#include "timemodel/timing.hpp"

namespace lodopt::cli {

// The project's one median (NaN for an empty list).
using timemodel::median;

// Median, 90th percentile (nearest rank), max and mean of `values` (all 0 for an empty list:
// the schedule's per-frame columns, where no frame means nothing was spent).
struct Spread {
    double median = 0.0, p90 = 0.0, max = 0.0, mean = 0.0;
};
Spread spreadOf(std::vector<double> values);

}  // namespace lodopt::cli
