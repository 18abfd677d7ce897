// A sweep's folder (docs/sweep.md):
//   sweep.plan.json     what is swept: the settings that change a view's answer, the scene's object
//                       names, every camera in view order (written before any view)
//   views/view_NNNNNN.json  one finished view: its settings, camera, answer, fitness, predicted
//                       time, each object's screen size, the objects searched (the others were
//                       out of view, below a pixel or hidden), and how long it took on which rank
//   sweep.json, sweep.csv   the merged table, in view order, without timings or ranks: the same
//                       bytes however the views were spread (ranks, shards, resumed runs)
//   sweep_timing.csv    per view: rank, setup and search seconds (differs run to run)
// Every file is written atomically, so a killed process leaves whole files only.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "evaluation/sweep.hpp"
#include "scenes/scene.hpp"

namespace lodopt::cli {

struct SweepPlan {
    nlohmann::json settings;  // option name -> value (checkIdentity)
    std::vector<std::string> objects;
    std::vector<scenes::Camera> cameras;
};

// A sweep's JSON files are written compact (one line): a 10,000-view table of a city with
// hundreds of objects per view is several times smaller than pretty-printed.
void writeSweepJson(const std::filesystem::path& path, const nlohmann::json& document);

nlohmann::json planJson(const SweepPlan& plan);
// Throws UsageError naming the file and what is wrong.
SweepPlan readPlan(const std::filesystem::path& folder);

std::filesystem::path viewPath(const std::filesystem::path& folder, std::size_t view);
nlohmann::json viewJson(const SweepPlan& plan, std::size_t view, const evaluation::SweepViewOutcome& outcome,
                        int rank);
// The view file of `view` when it exists and belongs to `plan` (same settings and camera);
// null when there is none. Throws UsageError when the file is unreadable or of another sweep.
nlohmann::json readViewFile(const std::filesystem::path& folder, const SweepPlan& plan, std::size_t view);
// Indices of views with a file in `folder`.
std::vector<std::size_t> savedViews(const std::filesystem::path& folder);

struct MergeSummary {
    std::size_t views = 0;
    double meanFitness = 0.0;
    double meanPredictedMs = 0.0;
    double maxPredictedMs = 0.0;
    std::size_t infeasible = 0;  // views whose budget even the coarsest combination exceeds
    std::vector<std::string> files;
};
// Merges the view files of `plan` found in `sources` (the first folder holding a view wins) into
// `out`: sweep.json, sweep.csv, sweep_timing.csv (and the plan, when `out` is not a source).
// Throws UsageError naming the missing views when some have no file.
MergeSummary mergeViews(const SweepPlan& plan, const std::vector<std::filesystem::path>& sources,
                        const std::filesystem::path& out);

// A merged sweep as its consumers (tune, report) read it.
struct SweepTableView {
    scenes::Camera camera;
    scenes::Combination levels;
    bool feasible = true;
    double fitness = 0.0;
    double predictedMs = 0.0;
    std::vector<double> screenSizes;
    std::vector<int> searched;  // object indices the search chose for
};
struct SweepTable {
    nlohmann::json settings;
    std::vector<std::string> objects;
    std::vector<SweepTableView> views;
};
// `folder`/sweep.json (or a sweep.json path). Throws UsageError naming the file and element.
SweepTable readSweepTable(const std::filesystem::path& folderOrFile);
// Throws UsageError naming the first of `options` (option name -> this run's value) that the
// sweep was made with another value.
void checkSweepSettings(const std::string& where, const SweepTable& table, const nlohmann::json& options);

}  // namespace lodopt::cli
