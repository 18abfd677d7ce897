// One row per scheduled frame, and what `lodopt schedule` writes from the rows: frames.csv and
// the summary's budget shares. Private to the CLI.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evaluation/schedule_walk.hpp"
#include "schedule_common.hpp"

namespace lodopt::cli {

// A number as frames.csv writes it: 8 significant digits, empty for NaN.
std::string csvNumber(double value);
// frames.csv: one line per row, with `maxLevels` level-histogram columns.
std::string framesCsv(const std::vector<evaluation::WalkFrame>& rows, int maxLevels);

// Share of `rows` (those `counted`) whose `value` lies within ±10% of the budget, or at most 10%
// above it.
struct BudgetShares {
    int frames = 0;
    double within10 = 0.0;
    double atMost110 = 0.0;
};
template <typename Value, typename Counted>
BudgetShares budgetShares(const std::vector<evaluation::WalkFrame>& rows, double budget, Value value, Counted counted) {
    BudgetShares shares;
    int within = 0, atMost = 0;
    for (const evaluation::WalkFrame& r : rows) {
        const double v = value(r);
        if (!counted(r) || std::isnan(v)) continue;
        ++shares.frames;
        if (std::abs(v - budget) <= 0.1 * budget) ++within;
        if (v <= 1.1 * budget) ++atMost;
    }
    if (shares.frames > 0) {
        shares.within10 = double(within) / shares.frames;
        shares.atMost110 = double(atMost) / shares.frames;
    }
    return shares;
}

nlohmann::json sharesJson(const BudgetShares& s);
nlohmann::json spreadJson(const Spread& s);

}  // namespace lodopt::cli
