// The report's thresholds section (report_sections.hpp): what `lodopt thresholds` fitted, the
// rules compared on the held-out views, and per object the optimizer's choices against screen
// size with the fitted switch points drawn over them.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "evaluation/engine_thresholds.hpp"
#include "report_data.hpp"
#include "report_sections.hpp"
#include "sweep_files.hpp"

namespace lodopt::cli {

namespace fs = std::filesystem;

namespace {

std::string numberOrDash(const nlohmann::json& value, int digits = 4) {
    return value.is_number() ? formatNumber(value.get<double>(), digits) : "–";
}

void addHeldOutTable(ReportContext& context, const nlohmann::json& document) {
    if (!document.contains("held_out") || !document["held_out"].is_array() || document["held_out"].empty()) return;
    std::vector<std::vector<std::string>> rows;
    for (const nlohmann::json& row : document["held_out"]) {
        rows.push_back({jsonText(row, "rule"), numberOrDash(row.value("lod_bias", nlohmann::json())),
                        numberOrDash(row.value("mean_fitness", nlohmann::json()), 6),
                        numberOrDash(row.value("gain_fraction", nlohmann::json()), 3),
                        numberOrDash(row.value("over_budget_share", nlohmann::json()), 3),
                        numberOrDash(row.value("mean_predicted_ms", nlohmann::json()))});
    }
    const nlohmann::json reference = document.value("held_out_reference", nlohmann::json::object());
    rows.push_back({"(optimizer)", "", numberOrDash(reference.value("optimizer_mean_fitness", nlohmann::json()), 6),
                    "1", "0", ""});
    rows.push_back({"(all coarsest)", "", numberOrDash(reference.value("coarsest_mean_fitness", nlohmann::json()), 6),
                    "0", "", ""});
    context.html.table({"rule", "LOD bias", "mean fitness", "gain fraction", "over budget", "mean predicted ms"}, rows);
    context.html.paragraph("On the " + std::to_string(document.value("held_out_views", 0)) +
                           " held-out views: each rule with its own global LOD bias, set so that its mean predicted "
                           "time on the fitting views is within the budget; the gain fraction is the rule's fitness "
                           "above the all-coarsest combination's over the optimizer's above it (weighted by the "
                           "optimizer's gain per view).");
}

// One object's choices (fitting and held-out views) against its screen size, with the fitted
// switch points (the bias baked in) as vertical lines.
void plotObject(ReportContext& context, const SweepTable& table, const nlohmann::json& object, std::size_t index,
                int holdoutEvery) {
    std::ostringstream fitting, heldOut;
    double low = INFINITY, high = 0.0;
    std::size_t feasible = 0;
    for (const SweepTableView& view : table.views) {
        if (!view.feasible) continue;
        const bool held = evaluation::isHeldOutView(feasible, holdoutEvery);  // the split thresholds used
        ++feasible;
        if (std::find(view.searched.begin(), view.searched.end(), int(index)) == view.searched.end()) continue;
        const double size = view.screenSizes[index];
        if (!(size > 0.0)) continue;
        (held ? heldOut : fitting) << size << ' ' << view.levels[index] << '\n';
        low = std::min(low, size);
        high = std::max(high, size);
    }
    const std::vector<double> thresholds = object.value("screen_size", std::vector<double>());
    for (double t : thresholds) {
        if (!(t > 0.0) || !std::isfinite(t)) continue;
        low = std::min(low, t);
        high = std::max(high, t);
    }
    const int levels = object.value("levels", 1);
    const std::string name = context.prefix + "thresholds_object_" + std::to_string(index);
    PlotSpec spec;
    spec.name = name;
    spec.title = jsonText(object, "name") + ": chosen level against screen size";
    spec.data = {{name + "_fit.dat", "# screen_size level\n" + fitting.str()},
                 {name + "_held.dat", "# screen_size level\n" + heldOut.str()}};
    spec.height = 300;
    std::string script = "set logscale x\nset xlabel 'screen size (bounding-sphere diameter / view height)'\n"
                         "set ylabel 'level (0 = finest)'\nset ytics 1\nset yrange [" +
                         std::to_string(levels - 1) + ".5:-0.5]\nset key outside top center horizontal samplen 2\n";
    if (high > 0.0) script += "set xrange [" + formatNumber(low / 1.5, 6) + ":" + formatNumber(high * 1.5, 6) + "]\n";
    for (std::size_t k = 0; k < thresholds.size(); ++k) {
        script += "set arrow from " + formatNumber(thresholds[k], 8) + ", graph 0 to " + formatNumber(thresholds[k], 8) +
                  ", graph 1 nohead dt 2 lw 2 lc rgb '#000000'\n";
    }
    script += "plot '" + name + "_fit.dat' using 1:2 with points pt 7 ps 0.6 lc rgb '" + seriesColor(0) +
              "' title 'fitting views', '" + name + "_held.dat' using 1:2 with points pt 6 ps 0.9 lc rgb '" +
              seriesColor(1) + "' title 'held-out views', NaN with lines dt 2 lw 2 lc rgb '#000000' title 'switch points'\n";
    spec.script = script;
    context.plot(spec, "Each point is the level the optimizer chose for " + jsonText(object, "name") +
                           " in one view; the dashed lines are the exported switch points: the rule draws level k "
                           "right of the k-th line and left of the one before.");
}

}  // namespace

void addThresholdsSection(ReportContext& context, const fs::path& file, const nlohmann::json& document) {
    context.html.heading(2, "thresholds: " + jsonText(document, "scene"));
    const nlohmann::json bias = document.value("lod_bias", nlohmann::json::object());
    context.html.paragraph(
        "From " + file.string() + ": " + std::to_string(document.value("fitted_objects", 0)) + " of " +
        std::to_string(document.value("objects_with_levels", 0)) + " objects with levels fitted on " +
        std::to_string(document.value("fitting_views", 0)) + " views of the sweep " + jsonText(document, "from") +
        " (budget " + numberOrDash(document.value("budget_ms", nlohmann::json())) + " ms; pricing " +
        jsonText(document, "pricing") + "); global LOD bias " + numberOrDash(bias.value("lod_bias", nlohmann::json())) +
        ", baked into the exported thresholds; level agreement " +
        numberOrDash(document.value("fit_agreement", nlohmann::json()), 3) + " on the fitting views, " +
        numberOrDash(document.value("held_out_agreement", nlohmann::json()), 3) + " held out.");
    addHeldOutTable(context, document);
    if (!document.contains("objects") || !document["objects"].is_array()) return;
    const fs::path from = jsonText(document, "from");
    std::error_code error;
    if (from.empty() || !fs::exists(fs::path(from) / "sweep.json", error)) {
        context.html.paragraph("The sweep " + from.string() +
                               " is not found from here: the per-object plots of the choices are left out.");
        return;
    }
    const SweepTable table = readSweepTable(from);
    // The objects with levels that the most fitting views searched, at most six.
    std::vector<std::size_t> order;
    const nlohmann::json& objects = document["objects"];
    for (std::size_t i = 0; i < objects.size() && i < table.objects.size(); ++i) {
        if (objects[i].value("levels", 1) > 1 && objects[i].value("fit_samples", 0) > 0) order.push_back(i);
    }
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const int samplesA = objects[a].value("fit_samples", 0), samplesB = objects[b].value("fit_samples", 0);
        return samplesA != samplesB ? samplesA > samplesB : a < b;
    });
    if (order.size() > 6) order.resize(6);
    for (std::size_t index : order) plotObject(context, table, objects[index], index, document.value("holdout_every", 4));
}

}  // namespace lodopt::cli
