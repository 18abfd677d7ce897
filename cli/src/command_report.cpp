// lodopt report: one self-contained HTML page from the output of optimize, compare, tune,
// schedule, calibrate or bench (docs/report.md). Files are recognised by name and content, in
// the given folder and up to two folder levels below it (optimize --view all, or a folder
// holding several commands' outputs), so the page shows whatever is present.
#include <algorithm>
#include <filesystem>
#include <iostream>

#include "cli_common.hpp"
#include "optimize_run.hpp"
#include "report_bench.hpp"
#include "report_data.hpp"
#include "report_html.hpp"
#include "report_plot.hpp"
#include "report_sections.hpp"
#include "scenes/atomic_file.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::cli {
namespace {

namespace fs = std::filesystem;

enum class Kind { Optimize, Compare, Schedule, Tune, Profile, Bench, Sweep, Thresholds };

const char* kindName(Kind kind) {
    switch (kind) {
        case Kind::Optimize:
            return "optimize";
        case Kind::Compare:
            return "compare";
        case Kind::Schedule:
            return "schedule";
        case Kind::Tune:
            return "tune";
        case Kind::Profile:
            return "calibrate";
        case Kind::Bench:
            return "bench";
        case Kind::Sweep:
            return "sweep";
        case Kind::Thresholds:
            return "thresholds";
    }
    return "?";
}

struct Found {
    Kind kind;
    fs::path path;  // the folder (optimize, compare, bench) or the file (schedule, tune, profile)
};

bool endsWith(const std::string& text, const std::string& suffix) {
    return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Files that belong to a recognised folder kind and are not inputs of their own.
bool isKnownFile(const std::string& name) {
    static const std::vector<std::string> kKnown = {
        "result.json", "curve.csv",        "optimized.png",  "reference.png",   "compare.json", "compare.csv",
        "curves.csv",  "frames.csv",       "summary.json",   "report.html",     kBenchJson,     kBenchAlgorithmsCsv,
        kBenchRunsCsv, kBenchEvalPathsCsv, kBenchMetricsCsv, kBenchTimeModelCsv, "sweep.json", "sweep.csv",
        "sweep_timing.csv", "sweep.plan.json", "sweep_run.json"};
    return std::find(kKnown.begin(), kKnown.end(), name) != kKnown.end() || name.rfind("bench_pareto", 0) == 0 ||
           name.rfind(".", 0) == 0;
}

// A JSON file that is a tune output or a device profile.
bool classifyJson(const fs::path& file, std::vector<Found>& found) {
    nlohmann::json document;
    try {
        document = readJsonFile(file.string());
    } catch (const UsageError&) {
        return false;  // not ours to judge: listed with the other files
    }
    if (!document.is_object()) return false;
    if (document.contains("tuning") && document["tuning"].is_object()) {
        found.push_back({Kind::Tune, file});
        return true;
    }
    const std::string format = jsonText(document, "format");
    if (format.rfind("lodopt-device-profile", 0) == 0) {
        found.push_back({Kind::Profile, file});
        return true;
    }
    if (format == "lodopt-thresholds") {
        found.push_back({Kind::Thresholds, file});
        return true;
    }
    return false;
}

void scanFolder(const fs::path& folder, int depth, const fs::path& skip, std::vector<Found>& found,
                std::vector<fs::path>& other) {
    if (fs::exists(folder / "result.json")) found.push_back({Kind::Optimize, folder});
    if (fs::exists(folder / "compare.json") || fs::exists(folder / "curves.csv"))
        found.push_back({Kind::Compare, folder});
    if (fs::exists(folder / kBenchJson)) found.push_back({Kind::Bench, folder});
    if (fs::exists(folder / "frames.csv")) found.push_back({Kind::Schedule, folder / "frames.csv"});
    if (fs::exists(folder / "sweep.json")) found.push_back({Kind::Sweep, folder});
    const bool sweepFolder = fs::exists(folder / "sweep.plan.json");
    std::vector<fs::path> entries;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) entries.push_back(entry.path());
    std::sort(entries.begin(), entries.end());
    for (const fs::path& entry : entries) {
        const std::string name = entry.filename().string();
        if (fs::is_directory(entry)) {
            // The report's own plot folder and tune's per-view checkpoints are not inputs.
            std::error_code ignored;
            // A sweep's per-view files are what sweep.json merges.
            if (fs::equivalent(entry, skip, ignored) || endsWith(name, "_views") || endsWith(name, "_files") ||
                (sweepFolder && name == "views"))
                continue;
            if (depth < 2) scanFolder(entry, depth + 1, skip, found, other);
            continue;
        }
        if (isKnownFile(name)) continue;
        if (entry.extension() == ".json" && classifyJson(entry, found)) continue;
        if (endsWith(name, "_report.html")) continue;
        other.push_back(entry);
    }
}

std::string prefixOf(const fs::path& root, const fs::path& path) {
    std::string relative = fs::relative(path, root).string();
    if (relative == ".") return "";
    std::string prefix;
    for (char c : relative) prefix += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return prefix + "_";
}

struct ReportCommandOptions {
    std::string input;
    std::string out;
    ReportOptions report;
    OutputOptions output;
};

// The outputs `input` holds (a folder is scanned, `other` gets what is not recognised); throws
// UsageError when there is none.
std::vector<Found> findOutputs(const fs::path& input, const fs::path& plotDir, std::vector<fs::path>& other) {
    const std::string name = input.string();
    std::vector<Found> found;
    if (fs::is_directory(input)) {
        scanFolder(input, 0, plotDir, found, other);
    } else if (input.filename() == "result.json") {
        found.push_back({Kind::Optimize, input.parent_path()});
    } else if (input.filename() == "compare.json" || input.filename() == "curves.csv") {
        found.push_back({Kind::Compare, input.parent_path()});
    } else if (input.filename() == "sweep.json") {
        found.push_back({Kind::Sweep, input.parent_path()});
    } else if (input.filename() == kBenchJson) {
        found.push_back({Kind::Bench, input.parent_path()});
    } else if (input.extension() == ".csv") {
        found.push_back({Kind::Schedule, input});
    } else if (input.extension() != ".json" || !classifyJson(input, found)) {
        throw UsageError(name +
                         ": not an output lodopt report knows (a folder of optimize, compare, "
                         "schedule, bench or sweep, a tune coefficients file, a calibrate profile or a thresholds.json)");
    }
    if (found.empty()) {
        throw UsageError(name +
                         ": no output of optimize (result.json), compare (compare.json), schedule "
                         "(frames.csv), bench (bench.json), sweep (sweep.json), tune, calibrate or thresholds found");
    }
    return found;
}

void addSection(ReportContext& context, const Found& item) {
    switch (item.kind) {
        case Kind::Optimize:
            addOptimizeSection(context, item.path);
            break;
        case Kind::Compare:
            addCompareSection(context, item.path);
            break;
        case Kind::Bench:
            addBenchSection(context, item.path);
            break;
        case Kind::Schedule:
            addScheduleSection(context, item.path);
            break;
        case Kind::Tune:
            addTuneSection(context, item.path, readJsonFile(item.path.string()));
            break;
        case Kind::Profile:
            addProfileSection(context, item.path);
            break;
        case Kind::Sweep:
            addSweepSection(context, item.path);
            break;
        case Kind::Thresholds:
            addThresholdsSection(context, item.path, readJsonFile(item.path.string()));
            break;
    }
}

void runReport(const ReportCommandOptions& options) {
    const fs::path input(options.input);
    if (!fs::exists(input)) throw UsageError(options.input + ": no such file or folder");
    const bool folder = fs::is_directory(input);
    const fs::path out = !options.out.empty() ? fs::path(options.out)
                         : folder             ? input / "report.html"
                                              : input.parent_path() / (input.stem().string() + "_report.html");
    const fs::path plotDir = out.parent_path() / (out.stem().string() + "_files");
    fs::create_directories(plotDir);
    std::vector<fs::path> other;
    const std::vector<Found> found = findOutputs(input, plotDir, other);
    const fs::path root = folder ? input : input.parent_path();

    const Plotter plotter(plotDir.string());
    const fs::path canonical = fs::weakly_canonical(input);
    HtmlReport html("lodopt report: " +
                    (canonical.filename().empty() ? canonical.string() : canonical.filename().string()));
    html.raw("<p class=\"meta\">" +
             escapeHtml("From " + canonical.string() + ", " + timemodel::currentDateUtc() +
                        ", lodopt " LODOPT_VERSION ". Plots: " + plotter.description() +
                        "; their data and gnuplot scripts are in " + plotDir.filename().string() +
                        "/ beside this page.") +
             "</p>\n");
    if (!plotter.available()) html.note("No plots could be drawn: " + plotter.description() + ".");
    nlohmann::json sections = nlohmann::json::array();
    for (const Found& item : found) {
        ReportContext context{
            html, plotter, options.report,
            prefixOf(root, fs::is_directory(item.path) ? item.path : item.path.parent_path()) +
                (item.kind == Kind::Tune || item.kind == Kind::Profile ? item.path.stem().string() + "_"
                                                                       : std::string())};
        addSection(context, item);
        sections.push_back({{"kind", kindName(item.kind)}, {"path", item.path.string()}});
    }
    if (!other.empty()) {
        html.heading(2, "Other files");
        std::vector<std::vector<std::string>> rows;
        for (const fs::path& file : other) rows.push_back({fs::relative(file, root).string()});
        html.table({"not shown (not recognised)"}, rows);
    }
    scenes::writeTextAtomically(out.string(), html.finish());

    const nlohmann::json summary = {{"out", out.string()},
                                    {"plots", plotDir.string()},
                                    {"plot_tool", plotter.description()},
                                    {"plots_available", plotter.available()},
                                    {"images_embedded", html.embeddedImages()},
                                    {"sections", sections}};
    if (options.output.json) {
        printJson(summary);
        return;
    }
    std::cout << "wrote " << out.string() << " (" << sections.size() << " section" << (sections.size() == 1 ? "" : "s")
              << ", " << html.embeddedImages() << " images embedded; plot files in " << plotDir.string() << ")\n";
    if (!plotter.available()) std::cout << "  no plots: " << plotter.description() << "\n";
}

}  // namespace

void addReportCommand(CLI::App& app) {
    auto options = std::make_shared<ReportCommandOptions>();
    CLI::App* command = app.add_subcommand(
        "report",
        "One self-contained HTML page from the output of optimize, compare, tune, schedule, calibrate or bench");
    command->add_option("input", options->input, "Output folder (or a profile / coefficients JSON file)")->required();
    command->add_option("--out", options->out, "HTML file (default: INPUT/report.html)");
    command->add_option("--baseline", options->report.baseline, "Algorithm shown beside the optimized image, or 'none'")
        ->capture_default_str();
    command->add_option("--profile", options->report.profile,
                        "Device profile for the baseline's time model (default: the one result.json names)");
    addOutputOptions(*command, options->output);
    command->callback([options] {
        if (options->report.baseline != "none") checkAlgorithmName(options->report.baseline);
        runReport(*options);
    });
}

}  // namespace lodopt::cli
