// The report's sections for series over runs and frames: compare (fitness curves with min–max
// bands over seeds), schedule (frame times and levels along a camera path) and tune (scheduler
// vs optimizer fitness per view).
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "cli_common.hpp"
#include "report_data.hpp"
#include "report_sections.hpp"

namespace lodopt::cli {

namespace fs = std::filesystem;

void ReportContext::plot(const PlotSpec& spec, const std::string& caption) const {
    const PlotOutput out = plotter.plot(spec);
    html.images({makeImage(
        out.image, caption + (out.made ? " Script: " + fs::path(out.script).filename().string() : ""), out.note)});
}

std::vector<std::vector<std::string>> flattenScalars(const nlohmann::json& document) {
    std::vector<std::vector<std::string>> rows;
    if (!document.is_object()) return rows;
    auto scalar = [](const nlohmann::json& value) {
        if (value.is_string()) return value.get<std::string>();
        if (value.is_number_float()) return formatNumber(value.get<double>(), 5);
        return value.dump();
    };
    for (auto it = document.begin(); it != document.end(); ++it) {
        if (it->is_object()) {
            for (auto inner = it->begin(); inner != it->end(); ++inner) {
                if (!inner->is_structured()) rows.push_back({it.key() + "." + inner.key(), scalar(*inner)});
            }
        } else if (!it->is_array()) {
            rows.push_back({it.key(), scalar(*it)});
        }
    }
    return rows;
}

namespace {

// One run's curve: (evaluations, best fitness) in log order.
using Curve = std::vector<std::pair<double, double>>;

// Best fitness of `curve` after `evaluations` (the last logged row at or before it).
double valueAt(const Curve& curve, double evaluations) {
    double value = NAN;
    for (const auto& [x, y] : curve) {
        if (x > evaluations) break;
        value = y;
    }
    return value;
}

void addCompareCurves(ReportContext& context, const fs::path& curvesPath) {
    const CsvTable table = readCsv(curvesPath.string());
    for (const char* column : {"algorithm", "seed", "evaluations", "best_fitness"}) {
        if (!table.has(column)) throw UsageError(curvesPath.string() + ": no column '" + column + "'");
    }
    std::vector<std::string> order;  // algorithms in file order
    std::map<std::string, std::map<std::string, Curve>> runs;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        const std::string& algorithm = table.text(r, "algorithm");
        if (!runs.count(algorithm)) order.push_back(algorithm);
        runs[algorithm][table.text(r, "seed")].emplace_back(table.number(r, "evaluations"),
                                                            table.number(r, "best_fitness"));
    }
    if (order.empty()) return;
    std::ostringstream data;
    data << "# per algorithm (one index block each): evaluations, median, min, max of the best fitness over seeds;\n"
            "# every x appears twice (before and after the step) so bands and lines are step functions\n";
    std::ostringstream script;
    // A little room above 1.0 so curves that reach the best known stay visible under the border.
    script << "set xlabel 'evaluations (renders)'\nset ylabel 'best fitness so far'\nset key bottom right\n"
           << "set offsets 0, 0, graph 0.04, graph 0.02\n";
    // Runs that end early (one-shot heuristics, converged searches) keep their best fitness to
    // the right edge, so a 1-evaluation answer shows as a level line, not a dot at x = 1.
    double lastEvaluation = 0.0;
    for (const auto& [algorithm, seeds] : runs) {
        for (const auto& [seed, curve] : seeds) lastEvaluation = std::max(lastEvaluation, curve.back().first);
    }
    std::ostringstream plots;
    int block = 0;
    for (std::size_t a = 0; a < order.size(); ++a) {
        const auto& seeds = runs[order[a]];
        std::vector<double> grid;
        double start = 0.0;
        for (const auto& [seed, curve] : seeds) {
            start = std::max(start, curve.front().first);
            for (const auto& point : curve) grid.push_back(point.first);
        }
        std::sort(grid.begin(), grid.end());
        grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
        grid.erase(std::remove_if(grid.begin(), grid.end(), [&](double x) { return x < start; }), grid.end());
        data << "# " << order[a] << " (" << seeds.size() << " seeds)\n";
        std::string previous;
        for (std::size_t g = 0; g < grid.size(); ++g) {
            std::vector<double> values;
            for (const auto& [seed, curve] : seeds) values.push_back(valueAt(curve, grid[g]));
            const Summary s = summarize(values);
            std::ostringstream line;
            line << ' ' << s.median << ' ' << s.min << ' ' << s.max << '\n';
            if (!previous.empty()) data << grid[g] << previous;
            data << grid[g] << line.str();
            previous = line.str();
        }
        if (grid.back() < lastEvaluation) {
            data << lastEvaluation << previous;
        } else if (grid.size() == 1) {
            data << grid[0] + 0.5 << previous;  // a one-point run still shows
        }
        data << "\n\n";
        const std::string color = seriesColor(int(a));
        plots << (a ? ", " : "") << "'" << context.prefix << "compare_curves.dat' index " << block
              << " using 1:3:4 with filledcurves fc rgb '" << color << "' fs transparent solid 0.18 noborder notitle"
              << ", '' index " << block << " using 1:2 with lines lw 2 lc rgb '" << color << "' title "
              << gnuplotString(order[a] + " (" + std::to_string(seeds.size()) +
                               (seeds.size() == 1 ? " run)" : " seeds)"));
        ++block;
    }
    script << "plot " << plots.str() << "\n";
    PlotSpec spec;
    spec.name = context.prefix + "compare_curves";
    spec.title = "Best fitness against evaluations: median and min–max over seeds";
    spec.data = {{spec.name + ".dat", data.str()}};
    spec.script = script.str();
    spec.height = 480;
    context.plot(spec,
                 "Each line is the median over seeds of the best fitness found after that many evaluations; "
                 "the shaded band spans the worst and the best seed (the published GA-PSO vs PSO vs GA figure). "
                 "A run that stops early keeps its best fitness to the right edge.");
}

void addCompareFinal(ReportContext& context, const nlohmann::json& document) {
    if (!document.contains("algorithms") || !document["algorithms"].is_array()) return;
    std::vector<std::vector<std::string>> rows;
    std::ostringstream data;
    data << "# algorithm median_fitness min_fitness max_fitness median_wall_seconds\n";
    for (const nlohmann::json& row : document["algorithms"]) {
        const std::string name = jsonText(row, "algorithm", "?");
        rows.push_back(
            {name, jsonText(row, "runs", "–"), formatNumber(jsonNumber(row, "median_fitness", NAN), 5),
             formatNumber(jsonNumber(row, "min_fitness", NAN), 5), formatNumber(jsonNumber(row, "max_fitness", NAN), 5),
             formatNumber(jsonNumber(row, "median_evals_to_99pct", NAN), 4), jsonText(row, "reached_99pct", "–"),
             formatNumber(jsonNumber(row, "median_wall_seconds", NAN), 3)});
        data << gnuplotDataField(name) << ' ' << jsonNumber(row, "median_fitness", NAN) << ' '
             << jsonNumber(row, "min_fitness", NAN) << ' ' << jsonNumber(row, "max_fitness", NAN) << ' '
             << jsonNumber(row, "median_wall_seconds", NAN) << '\n';
    }
    context.html.table(
        {"algorithm", "runs", "median fitness", "min", "max", "median evals to 99%", "reached 99%", "median wall s"},
        rows);
    PlotSpec spec;
    spec.name = context.prefix + "compare_final";
    spec.title = "Final best fitness per algorithm (median, min–max over seeds)";
    spec.data = {{spec.name + ".dat", data.str()}};
    spec.script = "set ylabel 'best fitness'\nset xrange [-0.6:" + std::to_string(rows.size() - 0.4) +
                  "]\nset key off\nset xtics rotate by -30\nplot '" + spec.name +
                  ".dat' using 0:2:3:4:xtic(1) with yerrorbars pt 7 ps 1.5 lw 2 lc rgb '" + seriesColor(0) + "'\n";
    spec.height = 360;
    context.plot(spec, "Dots: median over seeds; bars: the worst and best seed.");
}

}  // namespace

void addCompareSection(ReportContext& context, const fs::path& folder) {
    nlohmann::json document;
    if (fs::exists(folder / "compare.json")) document = readJsonFile((folder / "compare.json").string());
    context.html.heading(2, "compare: " + jsonText(document, "scene", "?") + " / " + jsonText(document, "view", "?"));
    context.html.paragraph("From " + folder.string() + ".");
    if (!document.is_null()) {
        context.html.paragraph(jsonText(document, "scene", "?") + " / " + jsonText(document, "view", "?") +
                               ", budget " + formatNumber(jsonNumber(document, "budget_ms", NAN)) + " ms, " +
                               jsonText(document, "evaluation_budget", "?") + " evaluations per run, " +
                               jsonText(document, "seeds", "?") + " seeds; best fitness any run found " +
                               formatNumber(jsonNumber(document, "best_known_fitness", NAN), 6) + ".");
    }
    if (fs::exists(folder / "curves.csv")) addCompareCurves(context, folder / "curves.csv");
    addCompareFinal(context, document);
}

namespace {

std::vector<int> levelColumns(const CsvTable& frames) {
    std::vector<int> levels;
    for (int k = 0;; ++k) {
        if (!frames.has("level_" + std::to_string(k))) break;
        levels.push_back(k);
    }
    return levels;
}

bool anyFinite(const std::vector<double>& values) {
    return std::any_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

namespace {

// Frame times along the path, with the budget.
void plotScheduleTimes(ReportContext& context, const CsvTable& frames, double budget) {
    const std::vector<std::string> series = {"predicted_ms", "measured_ms", "baseline_measured_ms",
                                             "exact_predicted_ms", "finest_predicted_ms"};
    const std::vector<std::string> labels = {"predicted (scheduled)", "measured (scheduled)", "measured (unscheduled)",
                                             "predicted from exact features", "predicted, every visible object finest"};
    std::ostringstream data, plots;
    data << "# frame";
    std::vector<std::string> present;
    for (const std::string& name : series) {
        if (frames.has(name) && anyFinite(frames.numbers(name))) present.push_back(name);
    }
    for (const std::string& name : present) data << ' ' << name;
    data << '\n';
    for (std::size_t r = 0; r < frames.rows.size(); ++r) {
        data << frames.number(r, "frame");
        for (const std::string& name : present) data << ' ' << frames.number(r, name);
        data << '\n';
    }
    PlotSpec times;
    times.name = context.prefix + "schedule_times";
    times.title = "Frame time along the path";
    times.data = {{times.name + ".dat", data.str()}};
    for (std::size_t p = 0; p < present.size(); ++p) {
        const std::size_t which = std::find(series.begin(), series.end(), present[p]) - series.begin();
        const bool finest = present[p] == "finest_predicted_ms";
        plots << (p ? ", " : "") << "'" << times.name << ".dat' using 1:" << p + 2 << " with lines lw "
              << (finest ? "1 dt 3" : "1.6") << " lc rgb '" << (finest ? "#7a7a7a" : seriesColor(int(which)))
              << "' title '" << labels[which] << "'";
    }
    if (std::isfinite(budget)) plots << ", " << budget << " with lines dt 2 lw 2 lc rgb '#000000' title 'budget'";
    // The all-finest prediction can be many times the budget: the axis follows the scheduled and
    // measured times (and the budget) so the part that matters stays readable.
    double top = std::isfinite(budget) ? budget : 0.0;
    for (const std::string& name : present) {
        if (name == "finest_predicted_ms") continue;
        for (double v : frames.numbers(name)) top = std::isfinite(v) ? std::max(top, v) : top;
    }
    times.script = "set xlabel 'frame'\nset ylabel 'milliseconds'\nset yrange [0:" +
                   (top > 0.0 ? formatNumber(top * 1.3, 4) : std::string("*")) +
                   "]\nset key outside top center horizontal samplen 2\nplot " + plots.str() + "\n";
    context.plot(times,
                 "Predicted and measured frame time per frame (measured columns appear when schedule ran with "
                 "--render); the all-finest prediction is cut off where it leaves the axis.");
}

}  // namespace

namespace {

// Levels over frames: objects at each level per frame, stacked, and their shares.
void plotScheduleLevels(ReportContext& context, const CsvTable& frames) {
    const std::vector<int> levels = levelColumns(frames);
    if (!levels.empty()) {
        std::ostringstream stacked, plot;
        stacked << "# frame, then the running sum of objects at levels 0..k (stacked areas)\n";
        std::vector<double> totals(levels.size(), 0.0);
        for (std::size_t r = 0; r < frames.rows.size(); ++r) {
            stacked << frames.number(r, "frame");
            double sum = 0.0;
            for (int k : levels) {
                const double count = frames.number(r, "level_" + std::to_string(k));
                sum += std::isfinite(count) ? count : 0.0;
                totals[k] += std::isfinite(count) ? count : 0.0;
                stacked << ' ' << sum;
            }
            stacked << '\n';
        }
        PlotSpec histogram;
        histogram.name = context.prefix + "schedule_levels";
        histogram.title = "Objects drawn at each level, per frame";
        histogram.data = {{histogram.name + ".dat", stacked.str()}};
        for (std::size_t k = 0; k < levels.size(); ++k) {
            plot << (k ? ", " : "") << "'" << histogram.name
                 << ".dat' using 1:" << (k == 0 ? "(0)" : "($" + std::to_string(k + 1) + ")") << ":" << k + 2
                 << " with filledcurves fc rgb '" << seriesColor(int(k)) << "' fs solid 0.75 title 'level " << k << "'";
        }
        histogram.script =
            "set xlabel 'frame'\nset ylabel 'objects drawn'\nset yrange [0:*]\nset key outside right\nplot " +
            plot.str() + "\n";
        context.plot(histogram, "Stacked: how many drawn objects sit at each level (0 = finest) in every frame.");
        const double all = [&] {
            double s = 0.0;
            for (double t : totals) s += t;
            return s;
        }();
        std::vector<std::vector<std::string>> rows;
        for (std::size_t k = 0; k < levels.size(); ++k) {
            rows.push_back({"level " + std::to_string(k), formatNumber(totals[k], 8),
                            all > 0 ? formatNumber(100.0 * totals[k] / all, 3) + "%" : "–"});
        }
        context.html.table({"level", "object-frames", "share"}, rows);
    }
}

}  // namespace

namespace {

// Decision time and switches per frame.
void plotScheduleDecisions(ReportContext& context, const CsvTable& frames) {
    if (frames.has("decision_us")) {
        std::ostringstream decision;
        decision << "# frame decision_us switches\n";
        const bool switches = frames.has("switches");
        for (std::size_t r = 0; r < frames.rows.size(); ++r) {
            decision << frames.number(r, "frame") << ' ' << frames.number(r, "decision_us") << ' '
                     << (switches ? frames.number(r, "switches") : NAN) << '\n';
        }
        PlotSpec spec;
        spec.name = context.prefix + "schedule_decision";
        spec.title = "Decision time and level switches per frame";
        spec.data = {{spec.name + ".dat", decision.str()}};
        spec.script =
            "set xlabel 'frame'\nset ylabel 'decision time (µs)'\nset yrange [0:*]\nset key outside top center "
            "horizontal samplen 2\n";
        if (switches) spec.script += "set y2label 'switches'\nset y2range [0:*]\nset y2tics\nset ytics nomirror\n";
        spec.script += "plot '" + spec.name + ".dat' using 1:2 with lines lw 1.4 lc rgb '" + seriesColor(0) +
                       "' title 'decision time'";
        if (switches) {
            spec.script += ", '' using 1:3 axes x1y2 with impulses lw 1.5 lc rgb '" + seriesColor(1) +
                           "' title 'switches (right axis)'";
        }
        spec.script += "\n";
        spec.height = 360;
        context.plot(spec, "The scheduler's own cost per frame, and how many drawn objects changed level.");
    }
}

// Fitness along the path, when schedule scored its frames.
void plotScheduleFitness(ReportContext& context, const CsvTable& frames) {
    if (frames.has("fitness") && anyFinite(frames.numbers("fitness"))) {
        std::ostringstream fitness;
        fitness << "# frame fitness baseline_fitness\n";
        const bool baseline = frames.has("baseline_fitness") && anyFinite(frames.numbers("baseline_fitness"));
        for (std::size_t r = 0; r < frames.rows.size(); ++r) {
            fitness << frames.number(r, "frame") << ' ' << frames.number(r, "fitness") << ' '
                    << (baseline ? frames.number(r, "baseline_fitness") : NAN) << '\n';
        }
        PlotSpec spec;
        spec.name = context.prefix + "schedule_fitness";
        spec.title = "Fitness along the path";
        spec.data = {{spec.name + ".dat", fitness.str()}};
        spec.script = "set xlabel 'frame'\nset ylabel 'fitness'\nset key bottom right\nplot '" + spec.name +
                      ".dat' using 1:2 with lines lw 1.6 lc rgb '" + seriesColor(0) + "' title 'scheduled'";
        if (baseline)
            spec.script += ", '' using 1:3 with lines lw 1.2 lc rgb '" + seriesColor(1) + "' title 'unscheduled'";
        spec.script += "\n";
        spec.height = 340;
        context.plot(spec, "Fused fitness of every frame against its full-detail reference.");
    }
}

}  // namespace

void addScheduleSection(ReportContext& context, const fs::path& framesPath) {
    const CsvTable frames = readCsv(framesPath.string());
    for (const char* column : {"frame", "predicted_ms"}) {
        if (!frames.has(column)) throw UsageError(framesPath.string() + ": no column '" + column + "'");
    }
    const fs::path summaryPath = framesPath.parent_path() / "summary.json";
    nlohmann::json summary;
    if (fs::exists(summaryPath)) summary = readJsonFile(summaryPath.string());
    context.html.heading(2, "schedule: " + jsonText(summary, "scene", "?") + " / " + jsonText(summary, "path", "?"));
    context.html.paragraph("From " + framesPath.string() + (summary.is_null() ? "" : " and summary.json") + ", " +
                           std::to_string(frames.rows.size()) + " frames.");
    if (!summary.is_null()) context.html.details("Summary (summary.json)", summary.dump(2));
    if (frames.rows.empty()) return;
    const double budget = jsonNumber(summary, "budget_ms", NAN);
    // Goal 1 beside what the machine's clock allows (docs/scheduler.md "Measurement ceiling").
    if (summary.is_object() && summary.contains("measured_vs_budget")) {
        const nlohmann::json binding = summary["measured_vs_budget"].value("binding", nlohmann::json());
        std::string text = "Measured within ±10% of the budget on " +
                           formatNumber(100.0 * jsonNumber(binding, "within_10_percent", NAN), 3) + "% of the " +
                           jsonText(binding, "frames", "?") + " frames where the budget binds";
        if (summary.contains("measurement_ceiling")) {
            text += "; measurement ceiling " +
                    formatNumber(100.0 * jsonNumber(summary["measurement_ceiling"], "ceiling", NAN), 3) +
                    "% (the largest share of one frame's repeated measurements a ±10% band holds: no scheduler "
                    "can expect more on this machine)";
        }
        context.html.paragraph(text + ".");
    }

    plotScheduleTimes(context, frames, budget);
    plotScheduleLevels(context, frames);
    plotScheduleDecisions(context, frames);
    plotScheduleFitness(context, frames);
}

void addTuneSection(ReportContext& context, const fs::path& file, const nlohmann::json& document) {
    const nlohmann::json& tuning = document["tuning"];
    context.html.heading(2, "tune: " + jsonText(tuning, "scene", "?") + " (" + file.filename().string() + ")");
    const nlohmann::json defaults = tuning.value("defaults", nlohmann::json::object());
    const nlohmann::json tuned = tuning.value("tuned", nlohmann::json::object());
    context.html.table(
        {"scheduler fitness / optimizer fitness", "tuning views", "held-out views"},
        {{"published defaults", formatNumber(jsonNumber(defaults, "tuning_fraction", NAN)),
          formatNumber(jsonNumber(defaults, "held_out_fraction", NAN))},
         {"tuned (" + jsonText(tuning, "form", "?") + ")", formatNumber(jsonNumber(tuned, "tuning_fraction", NAN)),
          formatNumber(jsonNumber(tuned, "held_out_fraction", NAN))}});
    std::vector<std::vector<std::string>> facts;
    for (auto& row : flattenScalars(tuning)) {
        if (row[0].rfind("defaults.", 0) != 0 && row[0].rfind("tuned.", 0) != 0) facts.push_back(row);
    }
    context.html.table({"setting", "value"}, facts);
    if (!tuning.contains("per_view") || !tuning["per_view"].is_array() || tuning["per_view"].empty()) return;
    std::ostringstream data;
    data << "# view default_fraction tuned_fraction\n";
    std::vector<std::vector<std::string>> rows;
    for (const nlohmann::json& view : tuning["per_view"]) {
        const bool heldOut = view.value("held_out", false);
        const std::string name = jsonText(view, "view", "?") + (heldOut ? " (held out)" : "");
        data << gnuplotDataField(name) << ' ' << jsonNumber(view, "default_fraction", NAN) << ' '
             << jsonNumber(view, "tuned_fraction", NAN) << '\n';
        rows.push_back({name, formatNumber(jsonNumber(view, "optimizer_fitness", NAN)),
                        formatNumber(jsonNumber(view, "default_fraction", NAN)),
                        formatNumber(jsonNumber(view, "tuned_fraction", NAN)),
                        formatNumber(jsonNumber(view, "tuned_predicted_ms", NAN))});
    }
    PlotSpec spec;
    spec.name = context.prefix + "tune_views";
    spec.title = "Scheduler fitness as a fraction of the optimizer's, per view";
    spec.data = {{spec.name + ".dat", data.str()}};
    spec.script =
        "set style data histogram\nset style histogram clustered gap 1\nset style fill solid 0.85 border -1\n"
        "set ylabel 'fraction of the optimizer fitness'\nset yrange [0:*]\nset xtics rotate by -35\n"
        "set key outside top center horizontal samplen 2\nplot '" +
        spec.name + ".dat' using 2:xtic(1) lc rgb '" + seriesColor(1) +
        "' title 'published defaults', '' using 3 lc rgb '" + seriesColor(0) + "' title 'tuned'\n";
    context.plot(spec, "Per view: the scheduler's fitness divided by the optimizer's on the same view.");
    context.html.table({"view", "optimizer fitness", "default fraction", "tuned fraction", "tuned predicted ms"}, rows);
}

}  // namespace lodopt::cli
