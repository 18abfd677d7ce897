// The sections of `lodopt report`, one per kind of output folder (docs/report.md):
//   optimize  result.json, curve.csv, optimized.png, reference.png (a folder per view with
//             --view all): facts, reference | optimized | baseline | SSIM map | difference,
//             the chosen levels per object, the fitness curve;
//   compare   compare.json, compare.csv, curves.csv: fitness against evaluations per algorithm,
//             median with the min–max band over seeds, and the final fitness per algorithm;
//   schedule  frames.csv (+ summary.json): predicted and measured frame time along the path with
//             the budget, decision time, switches, and the levels histogram over frames;
//   tune      a coefficients file with a "tuning" object: scheduler vs optimizer fitness per view;
//   calibrate a device profile: error per time model, predicted against measured per sample;
//   bench     bench.json and its CSVs (report_bench.hpp);
//   sweep     sweep.json (+ sweep_timing.csv): fitness and predicted time per view, the chosen
//             level against screen size over every object and view, views per rank;
//   thresholds  thresholds.json: the rules on the held-out views, and for the objects the most
//             views searched, the optimizer's choices against screen size with the exported
//             switch points drawn over them (needs the sweep it names).
// Each function reads its files (bad content → UsageError naming the file), writes its plots
// through the Plotter and appends HTML. A missing optional file leaves out what needs it.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "report_html.hpp"
#include "report_plot.hpp"

namespace lodopt::cli {

struct ReportOptions {
    // Algorithm whose answer is shown beside the optimized image ("none" = no baseline). It is
    // re-run on the scene named in result.json; needs the scene (built-in, or the glTF path
    // still valid) and a time model (--profile, else the one result.json names, else shipped).
    std::string baseline = "pixelerror";  // the engines' automatic rule (Godot's, 1 px at the bias meeting the budget)
    std::string profile;  // device profile for the baseline's time model
};

struct ReportContext {
    HtmlReport& html;
    const Plotter& plotter;
    ReportOptions options;
    // Plot file names start with this (unique per section: several views, several folders).
    std::string prefix;
    // Shows a plot (or its note) with `caption` under it.
    void plot(const PlotSpec& spec, const std::string& caption) const;
};

void addOptimizeSection(ReportContext& context, const std::filesystem::path& folder);
void addCompareSection(ReportContext& context, const std::filesystem::path& folder);
void addScheduleSection(ReportContext& context, const std::filesystem::path& framesCsv);
void addTuneSection(ReportContext& context, const std::filesystem::path& file, const nlohmann::json& document);
void addProfileSection(ReportContext& context, const std::filesystem::path& file);
void addSweepSection(ReportContext& context, const std::filesystem::path& folder);
void addThresholdsSection(ReportContext& context, const std::filesystem::path& file, const nlohmann::json& document);

// Top-level scalars of `document` (and one level of nested objects as "outer.inner") as table
// rows, for summary files whose fields the report does not know one by one.
std::vector<std::vector<std::string>> flattenScalars(const nlohmann::json& document);

}  // namespace lodopt::cli
