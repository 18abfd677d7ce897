// `lodopt bench`'s files in the report, and the Pareto plot that bench and report share.
#pragma once

#include <filesystem>
#include <string>

#include "report_data.hpp"
#include "report_plot.hpp"
#include "report_sections.hpp"

namespace lodopt::cli {

// Names of the files `lodopt bench` writes in its folder.
inline constexpr const char* kBenchJson = "bench.json";
inline constexpr const char* kBenchAlgorithmsCsv = "bench_algorithms.csv";
inline constexpr const char* kBenchRunsCsv = "bench_runs.csv";
inline constexpr const char* kBenchEvalPathsCsv = "bench_eval_paths.csv";
inline constexpr const char* kBenchMetricsCsv = "bench_metrics.csv";
inline constexpr const char* kBenchTimeModelCsv = "bench_timemodel.csv";

// Time against gap, one line per algorithm through its evaluation budgets (median over seeds),
// and the Pareto front over all points: from bench_algorithms.csv (columns algorithm,
// evaluation_budget, median_wall_seconds, median_gap). Both axes logarithmic; a gap of 0
// (the best known found) is drawn on the bottom line labelled 0. Throws UsageError naming
// the file when a column is missing.
PlotSpec paretoPlot(const CsvTable& algorithms, const std::string& name);

void addBenchSection(ReportContext& context, const std::filesystem::path& folder);

}  // namespace lodopt::cli
