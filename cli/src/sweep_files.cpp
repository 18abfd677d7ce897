#include "sweep_files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "cli_common.hpp"
#include "report_data.hpp"
#include "schedule_common.hpp"
#include "scenes/atomic_file.hpp"

namespace lodopt::cli {

namespace {

nlohmann::json readJsonOrThrow(const std::filesystem::path& path, const char* what) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw UsageError(path.string() + ": cannot read " + what);
    std::ostringstream text;
    text << file.rdbuf();
    nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, false);
    if (json.is_discarded() || !json.is_object()) throw UsageError(path.string() + ": not a " + what + " (JSON object)");
    return json;
}

// Screen sizes with 5 significant digits: bounds are floats, and a 10,000-view table of a
// 2,000-object city stays a few hundred MB smaller.
double rounded(double value) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.5g", value);
    return std::strtod(text, nullptr);
}

std::string joined(const nlohmann::json& values) {
    std::ostringstream text;
    for (std::size_t k = 0; k < values.size(); ++k) text << (k ? " " : "") << values[k].dump();
    return text.str();
}

// A CSV field: quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string csvField(const std::string& text) {
    if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
    std::string quoted = "\"";
    for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

}  // namespace

void writeSweepJson(const std::filesystem::path& path, const nlohmann::json& document) {
    scenes::writeTextAtomically(path.string(), document.dump() + "\n");
}

nlohmann::json planJson(const SweepPlan& plan) {
    nlohmann::json cameras = nlohmann::json::array();
    for (const scenes::Camera& camera : plan.cameras) cameras.push_back(cameraToJson(camera));
    return {{"format", "lodopt-sweep-plan"},
            {"version", 1},
            {"settings", plan.settings},
            {"objects", plan.objects},
            {"cameras", cameras}};
}

SweepPlan readPlan(const std::filesystem::path& folder) {
    const std::filesystem::path path = folder / "sweep.plan.json";
    if (!std::filesystem::exists(path)) throw UsageError(folder.string() + ": no sweep.plan.json (not a sweep folder)");
    const nlohmann::json json = readJsonOrThrow(path, "sweep plan");
    if (json.value("format", "") != "lodopt-sweep-plan" || json.value("version", 0) != 1 ||
        !json.contains("settings") || !json.contains("objects") || !json["objects"].is_array() ||
        !json.contains("cameras") || !json["cameras"].is_array()) {
        throw UsageError(path.string() + ": not a lodopt sweep plan (format lodopt-sweep-plan, version 1)");
    }
    SweepPlan plan;
    plan.settings = json["settings"];
    for (const nlohmann::json& name : json["objects"]) {
        if (!name.is_string()) throw UsageError(path.string() + ": objects: expected names");
        plan.objects.push_back(name.get<std::string>());
    }
    for (std::size_t k = 0; k < json["cameras"].size(); ++k) {
        plan.cameras.push_back(cameraFromJson(json["cameras"][k], path.string() + ": cameras[" + std::to_string(k) + "]"));
    }
    return plan;
}

std::filesystem::path viewPath(const std::filesystem::path& folder, std::size_t view) {
    std::ostringstream name;
    name << "view_" << std::setw(6) << std::setfill('0') << view << ".json";
    return folder / "views" / name.str();
}

nlohmann::json viewJson(const SweepPlan& plan, std::size_t view, const evaluation::SweepViewOutcome& outcome,
                        int rank) {
    nlohmann::json sizes = nlohmann::json::array();
    for (double size : outcome.screenSizes) sizes.push_back(rounded(size));
    return {{"format", "lodopt-sweep-view"},
            {"version", 1},
            {"settings", plan.settings},
            {"view", view},
            {"camera", cameraToJson(plan.cameras.at(view))},
            {"feasible", outcome.feasible},
            {"levels", outcome.levels},
            {"fitness", outcome.fitness},
            {"judge", outcome.judgeDistance ? nlohmann::json(*outcome.judgeDistance) : nlohmann::json(nullptr)},
            {"predicted_ms", outcome.predictedMs},
            {"searched_objects", outcome.searchedObjects},
            {"searched", outcome.searched},
            {"evaluations", outcome.evaluations},
            {"screen_sizes", sizes},
            {"rank", rank},
            {"setup_seconds", outcome.setupSeconds},
            {"search_seconds", outcome.searchSeconds}};
}

nlohmann::json readViewFile(const std::filesystem::path& folder, const SweepPlan& plan, std::size_t view) {
    const std::filesystem::path path = viewPath(folder, view);
    if (!std::filesystem::exists(path)) return nullptr;
    nlohmann::json json = readJsonOrThrow(path, "sweep view");
    if (json.value("format", "") != "lodopt-sweep-view" || json.value("version", 0) != 1 || !json.contains("levels") ||
        !json.contains("camera") || !json.contains("settings") || !json["levels"].is_array() ||
        !json.contains("screen_sizes") || !json.contains("searched") || !json["searched"].is_array() ||
        json.value("view", std::size_t(-1)) != view) {
        throw UsageError(path.string() + ": not view " + std::to_string(view) + " of a lodopt sweep");
    }
    checkIdentity(path.string(), json["settings"], plan.settings);
    if (json["camera"] != cameraToJson(plan.cameras.at(view))) {
        throw UsageError(path.string() + ": made from another camera than the plan's view " + std::to_string(view) +
                         "; delete the folder or use another --out");
    }
    if (json["levels"].size() != plan.objects.size() || json["screen_sizes"].size() != plan.objects.size()) {
        throw UsageError(path.string() + ": holds " + std::to_string(json["levels"].size()) + " levels for " +
                         std::to_string(plan.objects.size()) + " objects");
    }
    return json;
}

std::vector<std::size_t> savedViews(const std::filesystem::path& folder) {
    std::vector<std::size_t> views;
    const std::filesystem::path dir = folder / "views";
    if (!std::filesystem::is_directory(dir)) return views;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.size() != 16 || name.rfind("view_", 0) != 0 || entry.path().extension() != ".json") continue;
        try {
            views.push_back(std::stoul(name.substr(5, 6)));
        } catch (const std::exception&) {
        }
    }
    std::sort(views.begin(), views.end());
    return views;
}

MergeSummary mergeViews(const SweepPlan& plan, const std::vector<std::filesystem::path>& sources,
                        const std::filesystem::path& out) {
    nlohmann::json views = nlohmann::json::array();
    std::ostringstream csv, timing;
    csv << std::setprecision(17);
    csv << "view,name,position_x,position_y,position_z,target_x,target_y,target_z,fov_y_degrees,fitness,"
           "predicted_ms,feasible,searched_objects,evaluations,levels,screen_sizes,searched,judge\n";
    timing << "view,rank,setup_seconds,search_seconds,evaluations\n";
    std::vector<std::size_t> missing;
    MergeSummary summary;
    for (std::size_t k = 0; k < plan.cameras.size(); ++k) {
        nlohmann::json saved;
        for (const std::filesystem::path& source : sources) {
            saved = readViewFile(source, plan, k);
            if (!saved.is_null()) break;
        }
        if (saved.is_null()) {
            missing.push_back(k);
            continue;
        }
        const scenes::Camera& c = plan.cameras[k];
        nlohmann::json row = {{"view", k},
                              {"camera", saved["camera"]},
                              {"feasible", saved.value("feasible", true)},
                              {"levels", saved["levels"]},
                              {"fitness", saved["fitness"]},
                              {"judge", saved.value("judge", nlohmann::json(nullptr))},
                              {"predicted_ms", saved["predicted_ms"]},
                              {"searched_objects", saved["searched_objects"]},
                              {"searched", saved["searched"]},
                              {"evaluations", saved["evaluations"]},
                              {"screen_sizes", saved["screen_sizes"]}};
        csv << k << "," << csvField(c.name) << "," << saved["camera"]["position"][0].dump() << ","
            << saved["camera"]["position"][1].dump() << "," << saved["camera"]["position"][2].dump() << ","
            << saved["camera"]["target"][0].dump() << "," << saved["camera"]["target"][1].dump() << ","
            << saved["camera"]["target"][2].dump() << "," << saved["camera"]["fov_y_degrees"].dump() << ","
            << saved["fitness"].dump() << "," << saved["predicted_ms"].dump() << ","
            << (saved.value("feasible", true) ? 1 : 0) << "," << saved["searched_objects"].dump()
            << "," << saved["evaluations"].dump() << "," << joined(saved["levels"]) << ","
            << joined(saved["screen_sizes"]) << "," << joined(saved["searched"]) << ","
            << (saved.value("judge", nlohmann::json(nullptr)).is_null() ? std::string() : saved["judge"].dump()) << "\n";
        timing << k << "," << saved.value("rank", 0) << "," << saved.value("setup_seconds", 0.0) << ","
               << saved.value("search_seconds", 0.0) << "," << saved["evaluations"].dump() << "\n";
        const double fitness = saved["fitness"].get<double>();
        const double predicted = saved["predicted_ms"].get<double>();
        summary.meanFitness += fitness;
        summary.meanPredictedMs += predicted;
        summary.maxPredictedMs = std::max(summary.maxPredictedMs, predicted);
        if (!saved.value("feasible", true)) ++summary.infeasible;
        views.push_back(std::move(row));
    }
    if (!missing.empty()) {
        std::string list;
        for (std::size_t k = 0; k < missing.size() && k < 8; ++k) list += (k ? ", " : "") + std::to_string(missing[k]);
        if (missing.size() > 8) list += ", ...";
        throw UsageError(std::to_string(missing.size()) + " of " + std::to_string(plan.cameras.size()) +
                         " views have no file (" + list + "): finish them with --resume (or the missing shards)");
    }
    summary.views = plan.cameras.size();
    if (summary.views > 0) {
        summary.meanFitness /= double(summary.views);
        summary.meanPredictedMs /= double(summary.views);
    }
    const nlohmann::json document = {{"format", "lodopt-sweep"},
                                     {"version", 1},
                                     {"settings", plan.settings},
                                     {"objects", plan.objects},
                                     {"views", views}};
    std::filesystem::create_directories(out);
    bool outIsSource = false;
    for (const std::filesystem::path& source : sources) {
        outIsSource = outIsSource || std::filesystem::weakly_canonical(source) == std::filesystem::weakly_canonical(out);
    }
    if (!outIsSource) {
        writeSweepJson(out / "sweep.plan.json", planJson(plan));
        summary.files.push_back((out / "sweep.plan.json").string());
    }
    writeSweepJson(out / "sweep.json", document);
    scenes::writeTextAtomically((out / "sweep.csv").string(), csv.str());
    scenes::writeTextAtomically((out / "sweep_timing.csv").string(), timing.str());
    for (const char* name : {"sweep.json", "sweep.csv", "sweep_timing.csv"}) summary.files.push_back((out / name).string());
    return summary;
}

SweepTable readSweepTable(const std::filesystem::path& folderOrFile) {
    const std::filesystem::path path =
        std::filesystem::is_directory(folderOrFile) ? folderOrFile / "sweep.json" : folderOrFile;
    if (!std::filesystem::exists(path)) {
        throw UsageError(path.string() + ": no merged sweep (run lodopt sweep to the end, or sweep --merge)");
    }
    const nlohmann::json json = readJsonOrThrow(path, "merged sweep");
    if (json.value("format", "") != "lodopt-sweep" || json.value("version", 0) != 1 || !json.contains("settings") ||
        !json.contains("objects") || !json.contains("views") || !json["views"].is_array()) {
        throw UsageError(path.string() + ": not a merged lodopt sweep (format lodopt-sweep, version 1)");
    }
    SweepTable table;
    table.settings = json["settings"];
    table.objects = json["objects"].get<std::vector<std::string>>();
    for (std::size_t k = 0; k < json["views"].size(); ++k) {
        const nlohmann::json& view = json["views"][k];
        const std::string where = path.string() + ": views[" + std::to_string(k) + "]";
        SweepTableView row;
        try {
            row.camera = cameraFromJson(view.at("camera"), where + ".camera");
            row.levels = view.at("levels").get<scenes::Combination>();
            row.feasible = view.value("feasible", true);
            row.fitness = view.at("fitness").get<double>();
            row.predictedMs = view.at("predicted_ms").get<double>();
            row.screenSizes = view.at("screen_sizes").get<std::vector<double>>();
            row.searched = view.at("searched").get<std::vector<int>>();
        } catch (const nlohmann::json::exception& error) {
            throw UsageError(where + ": " + error.what());
        }
        if (row.levels.size() != table.objects.size() || row.screenSizes.size() != table.objects.size()) {
            throw UsageError(where + ": levels and screen_sizes need one entry per object (" +
                             std::to_string(table.objects.size()) + ")");
        }
        for (int object : row.searched) {
            if (object < 0 || std::size_t(object) >= table.objects.size()) {
                throw UsageError(where + ": searched names object " + std::to_string(object) + " of " +
                                 std::to_string(table.objects.size()));
            }
        }
        table.views.push_back(std::move(row));
    }
    return table;
}

void checkSweepSettings(const std::string& where, const SweepTable& table, const nlohmann::json& options) {
    for (auto it = options.begin(); it != options.end(); ++it) {
        if (table.settings.contains(it.key()) && table.settings[it.key()] == it.value()) continue;
        throw UsageError(where + ": the sweep was made with --" + it.key() + " " +
                         (table.settings.contains(it.key()) ? table.settings[it.key()].dump() : "(unset)") +
                         ", this run has " + it.value().dump() + "; use the sweep's value");
    }
}

}  // namespace lodopt::cli
