// The report's bench and calibrate sections, and the Pareto plot shared with `lodopt bench`.
#include "report_bench.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "cli_common.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::cli {

namespace fs = std::filesystem;

PlotSpec paretoPlot(const CsvTable& algorithms, const std::string& name) {
    for (const char* column : {"algorithm", "evaluation_budget", "median_wall_seconds", "median_gap"}) {
        if (!algorithms.has(column)) throw UsageError(algorithms.path + ": no column '" + column + "'");
    }
    struct Point {
        double seconds, gap, budget;
    };
    std::vector<std::string> order;
    std::map<std::string, std::vector<Point>> points;
    double smallestGap = INFINITY;
    for (std::size_t r = 0; r < algorithms.rows.size(); ++r) {
        const std::string& algorithm = algorithms.text(r, "algorithm");
        if (!points.count(algorithm)) order.push_back(algorithm);
        const Point p{algorithms.number(r, "median_wall_seconds"), algorithms.number(r, "median_gap"),
                      algorithms.number(r, "evaluation_budget")};
        if (!(p.seconds > 0.0) || !(p.gap >= 0.0)) continue;
        points[algorithm].push_back(p);
        if (p.gap > 0.0) smallestGap = std::min(smallestGap, p.gap);
    }
    // A gap of 0 cannot sit on a log axis: it is drawn one decade below the smallest positive gap.
    const double floorGap = std::isfinite(smallestGap)
                                ? std::clamp(std::pow(10.0, std::floor(std::log10(smallestGap)) - 1.0), 1e-12, 1e-3)
                                : 1e-6;
    std::ostringstream data, front, plots;
    data << "# per algorithm (one index block each): median wall seconds, median gap (0 drawn as " << floorGap
         << "), evaluation budget\n";
    std::vector<Point> all;
    int block = 0;
    for (std::size_t a = 0; a < order.size(); ++a) {
        std::vector<Point>& list = points[order[a]];
        if (list.empty()) continue;
        data << "# " << order[a] << "\n";
        for (const Point& p : list) {
            data << p.seconds << ' ' << std::max(p.gap, floorGap) << ' ' << p.budget << '\n';
            all.push_back(p);
        }
        data << "\n\n";
        const std::string color = seriesColor(int(a));
        plots << (block ? ", " : "") << "'" << name << ".dat' index " << block
              << " using 1:2 with linespoints pt 7 ps 1.3 lw 1.5 lc rgb '" << color << "' title "
              << gnuplotString(order[a]) << ", '' index " << block
              << " using 1:2:(sprintf('%d', $3)) with labels offset char 0.9,0.6 font ',7' tc rgb '" << color
              << "' notitle";
        ++block;
    }
    // Pareto front: the points no other point beats in both time and gap.
    std::sort(all.begin(), all.end(), [](const Point& a, const Point& b) {
        return a.seconds < b.seconds || (a.seconds == b.seconds && a.gap < b.gap);
    });
    front << "# Pareto front: wall seconds, gap\n";
    double bestGap = INFINITY;
    for (const Point& p : all) {
        if (p.gap < bestGap) {
            front << p.seconds << ' ' << std::max(p.gap, floorGap) << '\n';
            bestGap = p.gap;
        }
    }
    PlotSpec spec;
    spec.name = name;
    spec.title = "Run time against error (median over seeds per evaluation budget)";
    spec.data = {{name + ".dat", data.str()}, {name + "_front.dat", front.str()}};
    std::ostringstream script;
    script << "set logscale xy\nset xtics enhanced\nset xlabel 'wall time per run (s)'\n"
           << "set ylabel 'gap to the best fitness known'\nset format y '10^{%L}'\nset format x '10^{%L}'\n"
           << "set ytics add ('0' " << floorGap << ")\nset yrange [" << floorGap / 2.0 << ":*]\n"
           << "set key outside right top\n"
           << "plot '" << name << "_front.dat' using 1:2 with steps dt 2 lw 2 lc rgb '#444444' title 'Pareto front'";
    if (block > 0) script << ", " << plots.str();
    script << "\n";
    spec.script = script.str();
    spec.width = 820;
    spec.height = 480;
    return spec;
}

namespace {

std::vector<std::vector<std::string>> csvRows(const CsvTable& table, const std::vector<std::string>& columns,
                                              const std::vector<double>& scale = {}) {
    std::vector<std::vector<std::string>> rows;
    for (std::size_t r = 0; r < table.rows.size(); ++r) {
        std::vector<std::string> row;
        for (std::size_t c = 0; c < columns.size(); ++c) {
            const std::string& field = table.text(r, columns[c]);
            const double factor = c < scale.size() ? scale[c] : 0.0;
            row.push_back(factor > 0.0 && !field.empty() ? formatNumber(table.number(r, columns[c]) * factor, 4)
                                                         : field);
        }
        rows.push_back(row);
    }
    return rows;
}

bool hasColumns(const CsvTable& table, const std::vector<std::string>& columns) {
    for (const std::string& column : columns) {
        if (!table.has(column)) throw UsageError(table.path + ": no column '" + column + "'");
    }
    return true;
}

}  // namespace

void addBenchSection(ReportContext& context, const fs::path& folder) {
    const nlohmann::json document = readJsonFile((folder / kBenchJson).string());
    context.html.heading(2, "bench: " + jsonText(document, "scene", "?") + " / " + jsonText(document, "view", "?"));
    const nlohmann::json best = document.value("best_known", nlohmann::json::object());
    context.html.paragraph(
        jsonText(document, "size", "?") + ", budget " + formatNumber(jsonNumber(document, "budget_ms", NAN)) + " ms (" +
        jsonText(document, "budget_source", "?") + "), time model " + jsonText(document, "time_model", "?") + ", " +
        jsonText(document, "threads", "?") + " threads, " + jsonText(document, "seeds", "?") +
        " seeds per stochastic algorithm. Best fitness known " + formatNumber(jsonNumber(best, "fitness", NAN), 6) +
        " (" + jsonText(best, "source", "?") + ", " + formatNumber(jsonNumber(best, "combinations", NAN), 4) +
        " combinations). Whole bench: " + formatNumber(jsonNumber(document, "seconds", NAN), 3) + " s.");
    if (document.contains("surrogate_table") && document["surrogate_table"].is_object()) {
        const nlohmann::json& table = document["surrogate_table"];
        context.html.paragraph("mckp's per-view loss table (measured once before any run, not in mckp's wall time): " +
                               jsonText(table, "evaluations", "?") + " evaluations, " +
                               formatNumber(jsonNumber(table, "seconds", NAN), 3) + " s.");
    }

    const fs::path algorithmsPath = folder / kBenchAlgorithmsCsv;
    if (fs::exists(algorithmsPath)) {
        const CsvTable algorithms = readCsv(algorithmsPath.string());
        context.html.heading(3, "Algorithms × evaluation budgets");
        context.plot(paretoPlot(algorithms, context.prefix + "bench_pareto"),
                     "Each line is one algorithm through its evaluation budgets (numbers at the points); lower left is "
                     "better. Gap = best fitness known − the run's fitness, median over seeds.");
        hasColumns(algorithms, {"algorithm", "evaluation_budget", "runs", "median_wall_seconds", "median_gap",
                                "min_gap", "max_gap", "median_fitness", "median_evaluations"});
        context.html.table({"algorithm", "evaluation budget", "runs", "median wall s", "median gap", "min gap",
                            "max gap", "median fitness", "median evaluations"},
                           csvRows(algorithms,
                                   {"algorithm", "evaluation_budget", "runs", "median_wall_seconds", "median_gap",
                                    "min_gap", "max_gap", "median_fitness", "median_evaluations"},
                                   {0, 0, 0, 1, 1, 1, 1, 1, 0}));
    }
    const fs::path pathsPath = folder / kBenchEvalPathsCsv;
    if (fs::exists(pathsPath)) {
        const CsvTable paths = readCsv(pathsPath.string());
        hasColumns(paths, {"path", "workload", "mode", "threads", "candidates", "evals_per_second",
                           "mean_abs_fitness_diff", "max_abs_fitness_diff"});
        context.html.heading(3, "Fast vs full evaluation path");
        context.html.paragraph(
            "The same candidates through both paths: random = independent candidates, walk = one "
            "variable changed per step. Fitness differences are against the full path.");
        context.html.table({"path", "workload", "mode", "threads", "candidates", "evaluations/s", "mean |Δ fitness|",
                            "max |Δ fitness|"},
                           csvRows(paths,
                                   {"path", "workload", "mode", "threads", "candidates", "evals_per_second",
                                    "mean_abs_fitness_diff", "max_abs_fitness_diff"},
                                   {0, 0, 0, 0, 0, 1, 1, 1}));
    }
    const fs::path metricsPath = folder / kBenchMetricsCsv;
    if (fs::exists(metricsPath)) {
        const CsvTable metricsTable = readCsv(metricsPath.string());
        hasColumns(metricsTable, {"function", "width", "height", "microseconds_per_call", "reference",
                                  "reference_microseconds_per_call", "abs_deviation"});
        context.html.heading(3, "Metrics: time per call and deviation from float64 references");
        context.html.table(
            {"function", "width", "height", "µs per call", "reference", "reference µs per call", "|deviation|"},
            csvRows(metricsTable,
                    {"function", "width", "height", "microseconds_per_call", "reference",
                     "reference_microseconds_per_call", "abs_deviation"},
                    {0, 0, 0, 1, 0, 1, 1}));
    }
    const fs::path timePath = folder / kBenchTimeModelCsv;
    if (fs::exists(timePath)) {
        const CsvTable timeTable = readCsv(timePath.string());
        hasColumns(timeTable, {"model", "source", "samples", "mean_error", "median_error", "p90_error", "max_error"});
        context.html.heading(3, "Time models: relative error |t_act − t_est| / t_act");
        context.html.table(
            {"model", "frames", "samples", "mean %", "median %", "p90 %", "max %"},
            csvRows(timeTable, {"model", "source", "samples", "mean_error", "median_error", "p90_error", "max_error"},
                    {0, 0, 0, 100, 100, 100, 100}));
        if (document.contains("time_model_warnings") && document["time_model_warnings"].is_array()) {
            for (const nlohmann::json& warning : document["time_model_warnings"]) {
                if (warning.is_string()) context.html.note("Profile: " + warning.get<std::string>());
            }
        }
    }
}

namespace {

// The models' error table and bars.
void addProfileErrors(ReportContext& context, const timemodel::DeviceProfile& profile) {
    std::vector<std::vector<std::string>> rows;
    std::ostringstream errors;
    errors << "# model held_out_mean held_out_median held_out_p90 fit_mean (percent)\n";
    for (const timemodel::ModelResult& model : profile.models) {
        if (!model.fitted) {
            rows.push_back({model.name, "not fitted: " + model.failure});
            continue;
        }
        const timemodel::ErrorStats& h = model.heldOutErrors;
        const timemodel::ErrorStats& r = model.rotatedErrors;  // count 0 in profiles from before it
        rows.push_back({model.name, std::to_string(h.count), formatNumber(100 * h.mean, 3),
                        formatNumber(100 * h.median, 3), formatNumber(100 * h.p90, 3), formatNumber(100 * h.max, 3),
                        r.count ? formatNumber(100 * r.mean, 3) + " / " + formatNumber(100 * r.p90, 3) : "–",
                        formatNumber(100 * model.fitErrors.mean, 3), formatNumber(model.fit.rmsResidualMs, 3)});
        errors << model.name << ' ' << 100 * h.mean << ' ' << 100 * h.median << ' ' << 100 * h.p90 << ' '
               << 100 * model.fitErrors.mean << '\n';
    }
    context.html.table({"model", "held-out samples", "mean %", "median %", "p90 %", "max %",
                        "every viewpoint held out: mean / p90 %", "fit mean %", "fit RMS ms"},
                       rows);
    PlotSpec bars;
    bars.name = context.prefix + "profile_errors";
    bars.title = "Relative error |t_act − t_est| / t_act per time model";
    bars.data = {{bars.name + ".dat", errors.str()}};
    bars.script =
        "set style data histogram\nset style histogram clustered gap 1\nset style fill solid 0.85 border -1\n"
        "set ylabel 'error (%)'\nset yrange [0:*]\nset key top left\nplot '" +
        bars.name + ".dat' using 2:xtic(1) lc rgb '" + seriesColor(0) + "' title 'held-out mean', '' using 3 lc rgb '" +
        seriesColor(2) + "' title 'held-out median', '' using 4 lc rgb '" + seriesColor(1) +
        "' title 'held-out p90', '' using 5 lc rgb '" + seriesColor(5) + "' title 'fit mean'\n";
    bars.height = 360;
    context.plot(bars, "Held-out samples come from viewpoints that were never fitted.");
}

// Predicted against measured time per sample and model.
void addProfileScatter(ReportContext& context, const timemodel::DeviceProfile& profile) {
    const std::string scatterName = context.prefix + "profile_scatter";
    std::ostringstream scatter, plots;
    scatter << "# per model (one index block each): measured ms, predicted ms, held out (1/0)\n";
    double largest = 0.0;
    int block = 0;
    for (const timemodel::ModelResult& result : profile.models) {
        if (!result.fitted) continue;
        const std::unique_ptr<timemodel::TimeModel> model = timemodel::modelFromProfile(profile, result.name);
        scatter << "# " << result.name << "\n";
        for (const timemodel::ProfileSample& sample : profile.samples) {
            const double predicted = model->estimateMs(sample.sample.features);
            scatter << sample.sample.measuredMs << ' ' << predicted << ' ' << int(sample.heldOut) << '\n';
            largest = std::max({largest, sample.sample.measuredMs, predicted});
        }
        scatter << "\n\n";
        plots << ", " << (block == 0 ? "'" + scatterName + ".dat'" : std::string("''")) << " index " << block
              << " using 1:($3 > 0.5 ? $2 : 1/0) with points pt 7 ps 0.8 lc rgb '" << seriesColor(block) << "' title '"
              << result.name << " (held out)', '' index " << block
              << " using 1:($3 > 0.5 ? 1/0 : $2) with points pt 6 ps 0.7 lc rgb '" << seriesColor(block) << "' title '"
              << result.name << " (fitted)'";
        ++block;
    }
    PlotSpec spec;
    spec.name = scatterName;
    spec.title = "Predicted against measured frame time";
    spec.data = {{spec.name + ".dat", scatter.str()}};
    spec.script =
        "set xlabel 'measured (ms)'\nset ylabel 'predicted (ms)'\nset xrange [0:" + formatNumber(largest * 1.05) +
        "]\nset yrange [0:" + formatNumber(largest * 1.05) +
        "]\nset size square\nset key outside right\n"
        "plot x with lines dt 2 lc rgb '#555555' title 'exact'" +
        plots.str() + "\n";
    spec.width = 760;
    spec.height = 520;
    context.plot(spec, "Every calibration sample; points on the diagonal are predicted exactly.");
}

}  // namespace

void addProfileSection(ReportContext& context, const fs::path& file) {
    std::ifstream stream(file, std::ios::binary);
    std::stringstream text;
    text << stream.rdbuf();
    timemodel::DeviceProfile profile;
    try {
        profile = timemodel::profileFromJson(text.str(), file.string());
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }
    context.html.heading(2, "calibrate: " + profile.scene + " (" + file.filename().string() + ")");
    context.html.paragraph(
        std::to_string(profile.width) + "x" + std::to_string(profile.height) + " on " + profile.glRenderer + ", " +
        profile.machine.cpuModel + " (" + std::to_string(profile.machine.cores) + " threads), " + profile.created +
        "; " + std::to_string(profile.samples.size()) + " samples from " + std::to_string(profile.viewpoints) +
        " viewpoints (" + std::to_string(profile.heldOutViewpoints) + " held out); predicts the " + profile.timing.predicts +
        " of a frame's draws on the " + profile.timing.frameClock + " clock, learned from " + profile.timing.learnedFrom +
        ", default model " + profile.defaultModel + ".");
    addProfileErrors(context, profile);
    if (!profile.samples.empty()) addProfileScatter(context, profile);
}

}  // namespace lodopt::cli
