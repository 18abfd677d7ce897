// The report's sweep section (report_sections.hpp): what a sweep found over its viewpoints.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "report_data.hpp"
#include "report_sections.hpp"
#include "sweep_files.hpp"

namespace lodopt::cli {

namespace fs = std::filesystem;

namespace {

// Fitness and predicted time per view, with the budget.
void plotSweepViews(ReportContext& context, const SweepTable& table, double budget) {
    std::ostringstream data;
    data << "# view fitness predicted_ms feasible\n";
    for (std::size_t k = 0; k < table.views.size(); ++k) {
        const SweepTableView& view = table.views[k];
        data << k << ' ' << view.fitness << ' ' << view.predictedMs << ' ' << (view.feasible ? 1 : 0) << '\n';
    }
    PlotSpec spec;
    spec.name = context.prefix + "sweep_views";
    spec.title = "The optimizer's answer per view";
    spec.data = {{spec.name + ".dat", data.str()}};
    double top = std::isfinite(budget) ? budget : 0.0;
    for (const SweepTableView& view : table.views) top = std::max(top, view.predictedMs);
    spec.script = "set xlabel 'view'\nset ylabel 'fitness'\nset y2label 'predicted ms'\nset ytics nomirror\n"
                  "set y2tics\nset y2range [0:" + formatNumber(top * 1.15, 6) +
                  "]\nset key outside top center horizontal samplen 2\nplot '" +
                  spec.name + ".dat' using 1:2 with points pt 7 ps 0.5 lc rgb '" + seriesColor(0) +
                  "' title 'fitness', '' using 1:3 axes x1y2 with points pt 6 ps 0.5 lc rgb '" + seriesColor(1) +
                  "' title 'predicted ms'" +
                  (std::isfinite(budget) ? ", " + formatNumber(budget, 8) +
                                               " axes x1y2 with lines dt 2 lw 2 lc rgb '#000000' title 'budget'"
                                         : std::string()) +
                  "\n";
    context.plot(spec, "Per view (in sweep order): the answer's fitness (left axis) and predicted time (right axis).");
}

// Every searched (object, view) pair's chosen level against the object's screen size there: the
// choices an engine's screen-size rule would have to reproduce (objects out of view, below a
// pixel or hidden made no choice). At most 20,000 points (an even stride).
void plotLevelsAgainstScreenSize(ReportContext& context, const SweepTable& table) {
    std::size_t pairs = 0;
    for (const SweepTableView& view : table.views) pairs += view.searched.size();
    if (pairs == 0) return;
    const std::size_t stride = std::max<std::size_t>(1, pairs / 20000);
    std::ostringstream data;
    data << "# screen_size level (every " << stride << "th of " << pairs << " searched object-view pairs)\n";
    std::map<int, std::vector<double>> sizesByLevel;
    int coarsest = 0;
    std::size_t index = 0;
    for (const SweepTableView& view : table.views) {
        for (int object : view.searched) {
            const auto i = std::size_t(object);
            const double size = view.screenSizes[i];
            const bool plotted = index++ % stride == 0;
            if (!(size > 0.0)) continue;
            sizesByLevel[view.levels[i]].push_back(size);
            coarsest = std::max(coarsest, view.levels[i]);
            if (plotted) data << size << ' ' << view.levels[i] << '\n';
        }
    }
    PlotSpec spec;
    spec.name = context.prefix + "sweep_levels";
    spec.title = "Chosen level against screen size";
    spec.data = {{spec.name + ".dat", data.str()}};
    spec.script = "set logscale x\nset xlabel 'screen size (bounding-sphere diameter / view height)'\n"
                  "set ylabel 'level (0 = finest)'\nset ytics 1\nset yrange [" + std::to_string(coarsest) +
                  ".5:-0.5]\nunset key\nplot '" +
                  spec.name + ".dat' using 1:($2 + 0.3 * (rand(0) - 0.5)) with points pt 7 ps 0.3 lc rgb '" +
                  seriesColor(0) + "'\n";
    context.plot(spec, "Each point is one searched object in one view (levels jittered vertically to show "
                       "density); a per-object screen-size threshold rule draws the finer level above each "
                       "switch point.");
    std::vector<std::vector<std::string>> rows;
    for (auto& [level, sizes] : sizesByLevel) {
        const Summary s = summarize(sizes);
        rows.push_back({std::to_string(level), std::to_string(s.count), formatNumber(s.min), formatNumber(s.median),
                        formatNumber(s.max)});
    }
    context.html.table({"level", "searched object-views", "min screen size", "median", "max"}, rows);
}

// Per rank: views and busy seconds (sweep_timing.csv), the work queue's balance.
void addRankBalance(ReportContext& context, const fs::path& timingCsv) {
    if (!fs::exists(timingCsv)) return;
    const CsvTable timing = readCsv(timingCsv.string());
    if (!timing.has("rank") || !timing.has("setup_seconds") || !timing.has("search_seconds")) return;
    std::map<int, std::pair<int, double>> ranks;
    for (std::size_t r = 0; r < timing.rows.size(); ++r) {
        auto& [views, seconds] = ranks[int(timing.number(r, "rank"))];
        ++views;
        seconds += timing.number(r, "setup_seconds") + timing.number(r, "search_seconds");
    }
    std::vector<std::vector<std::string>> rows;
    for (const auto& [rank, entry] : ranks) {
        rows.push_back({std::to_string(rank), std::to_string(entry.first), formatNumber(entry.second)});
    }
    context.html.table({"rank (last run of each view)", "views", "busy seconds"}, rows);
}

}  // namespace

void addSweepSection(ReportContext& context, const fs::path& folder) {
    const SweepTable table = readSweepTable(folder);
    const double budget = table.settings.value("budget-ms", NAN);
    context.html.heading(2, "sweep: " + table.settings.value("scene", std::string("?")));
    std::vector<double> fitness, predicted;
    std::size_t infeasible = 0;
    for (const SweepTableView& view : table.views) {
        fitness.push_back(view.fitness);
        predicted.push_back(view.predictedMs);
        infeasible += view.feasible ? 0 : 1;
    }
    const Summary f = summarize(fitness);
    const Summary p = summarize(predicted);
    context.html.paragraph("From " + folder.string() + ": " + std::to_string(table.views.size()) + " views, " +
                           std::to_string(table.objects.size()) + " objects, budget " + formatNumber(budget) +
                           " ms, algorithm " + table.settings.value("algo", std::string("?")) + "; " +
                           std::to_string(infeasible) +
                           " view(s) over the budget even with every object at its coarsest level.");
    context.html.table({"", "min", "median", "max"},
                       {{"fitness", formatNumber(f.min), formatNumber(f.median), formatNumber(f.max)},
                        {"predicted ms", formatNumber(p.min), formatNumber(p.median), formatNumber(p.max)}});
    plotSweepViews(context, table, budget);
    plotLevelsAgainstScreenSize(context, table);
    addRankBalance(context, folder / "sweep_timing.csv");
}

}  // namespace lodopt::cli
