// The report's optimize section: facts, the images side by side (reference, optimized, a
// baseline algorithm's answer, SSIM map, difference heat map, the judge's maps of the answer
// and of the baseline), the chosen levels per object and the fitness curve.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>

#include "cli_common.hpp"
#include "optimize_run.hpp"
#include "report_data.hpp"
#include "report_images.hpp"
#include "report_sections.hpp"
#include "scenes/builtin.hpp"

namespace lodopt::cli {
namespace {

namespace fs = std::filesystem;

// Above this many objects the levels are summarised as a histogram instead of one mark each.
constexpr std::size_t kLevelsPlottedPerObject = 60;
// Renders narrower than this are shown scaled up (without smoothing) so they stay readable.
constexpr int kSmallImage = 256;
// Wider renders are shown at this width (the files keep their size).
constexpr int kLargeImage = 340;

struct SceneFacts {
    std::vector<std::string> names;  // object order
    std::vector<int> levelCounts;
};

struct Baseline {
    std::string note;  // why there is none, when `image` is empty
    renderer::Frame image;
    std::vector<int> levels;  // scene combination
    double fitness = NAN;
    double predictedMs = NAN;
    std::int64_t evaluations = 0;
    JudgeMap judge;  // `image` against the reference, by the judge
};

// The judge's viewing conditions result.json records (defaults where it has none).
metrics::JudgeParameters judgeParametersOf(const nlohmann::json& result) {
    metrics::JudgeParameters parameters;
    if (result.contains("judge") && result["judge"].is_object()) {
        const nlohmann::json& judge = result["judge"];
        parameters.pnorm = jsonNumber(judge, "pnorm", parameters.pnorm);
        parameters.intensityTargetNits = jsonNumber(judge, "intensity_target_nits", parameters.intensityTargetNits);
        parameters.displayScale = int(jsonNumber(judge, "display_scale", parameters.displayScale));
    }
    return parameters;
}

// The options `lodopt optimize` ran with, as far as `folder`/result.json tells them. Throws
// UsageError when the profile it names cannot be found (the baseline would otherwise run under
// another time model than the optimizer did).
OptimizeOptions optionsOf(const nlohmann::json& result, const fs::path& folder, const ReportOptions& report) {
    OptimizeOptions options;
    options.scene = jsonText(result, "scene", scenes::kDefaultSceneName);
    options.view = jsonText(result, "view", "0");
    options.budgetMs = jsonNumber(result, "budget_ms", 0.0);
    options.seed = std::uint64_t(jsonNumber(result, "seed", 1.0));
    options.size = std::to_string(int(jsonNumber(result, "width", 512))) + "x" +
                   std::to_string(int(jsonNumber(result, "height", 512)));
    options.threads = 1;
    auto computed = [&](const char* key) {
        return result.contains(key) && result[key].is_object() ? result[key].value("computed", true) : true;
    };
    // Only which components were on is recorded, not their ratio: equal weights for those.
    options.weights = std::string(computed("ssim") ? "1" : "0") + "," + (computed("boundary_entropy") ? "1" : "0") +
                      "," + (computed("information_entropy") ? "1" : "0");
    // "linear (device.json)" or "linear (shipped profile 'harbor')".
    const std::string model = jsonText(result, "time_model");
    options.model = model.substr(0, model.find(' '));
    options.profile = report.profile;
    const std::size_t open = model.find(" ("), close = model.rfind(')');
    if (options.profile.empty() && open != std::string::npos && close != std::string::npos && close > open) {
        const std::string source = model.substr(open + 2, close - open - 2);
        if (source.rfind("shipped", 0) != 0) {
            // The path was relative to where optimize ran: try here, then beside the result.
            for (const fs::path& candidate : {fs::path(source), folder / source, folder.parent_path() / source}) {
                if (fs::exists(candidate)) {
                    options.profile = candidate.string();
                    break;
                }
            }
            if (options.profile.empty()) {
                throw UsageError("the device profile '" + source +
                                 "' that result.json names is not found here; pass "
                                 "--profile FILE (or --baseline none)");
            }
        }
    }
    return options;
}

Baseline runBaseline(const nlohmann::json& result, const fs::path& folder, const ReportOptions& report,
                     SceneFacts& facts) {
    Baseline baseline;
    try {
        checkAlgorithmName(report.baseline);
        const OptimizeOptions options = optionsOf(result, folder, report);
        if (!(options.budgetMs > 0.0)) throw UsageError("result.json has no budget_ms");
        PreparedScene prepared = prepareScene(options, needsGeometricErrors(report.baseline));
        for (const scenes::Object& object : prepared.scene.objects) {
            facts.names.push_back(object.name);
            facts.levelCounts.push_back(int(object.levels.size()));
        }
        evaluation::SearchView context = prepareView(prepared, prepared.views[0], options);
        const optimizer::Result run = runAlgorithm(context, options, report.baseline, options.seed);
        const scenes::Combination levels = context.setup->toScene(run.best);
        baseline.image = prepared.renderer->render(levels, context.setup->camera());
        evaluation::FullRenderEvaluator full(*context.setup, *prepared.renderer, prepared.metrics);
        baseline.fitness = full.metricsOf(run.best).fitness;
        baseline.predictedMs = run.predictedMs;
        baseline.evaluations = run.evaluations;
        baseline.levels.assign(levels.begin(), levels.end());
        baseline.judge =
            judgeMap(baseline.image, context.setup->reference(), judgeParametersOf(result), "baseline");
    } catch (const std::exception& error) {
        baseline.image = {};
        baseline.note = "No baseline: " + std::string(error.what());
    }
    return baseline;
}

SceneFacts loadSceneFacts(const nlohmann::json& result) {
    SceneFacts facts;
    try {
        const scenes::Scene scene = scenes::loadScene(jsonText(result, "scene", scenes::kDefaultSceneName),
                                                      std::uint32_t(jsonNumber(result, "seed", 1)));
        for (const scenes::Object& object : scene.objects) {
            facts.names.push_back(object.name);
            facts.levelCounts.push_back(int(object.levels.size()));
        }
    } catch (const std::exception&) {
        // Not loadable here (a glTF path that moved): the names come from result.json alone.
    }
    return facts;
}

std::string fixed(double value, int digits) {
    if (std::isnan(value)) return "–";
    std::ostringstream out;
    out.setf(std::ios::fixed);
    out.precision(digits);
    out << value;
    return out.str();
}

void addFacts(ReportContext& context, const nlohmann::json& result, const Baseline& baseline,
              const std::string& baselineName) {
    auto fidelity = [&](const char* key) {
        return result.contains(key) && result[key].is_object() ? jsonNumber(result[key], "fidelity", NAN) : NAN;
    };
    const bool judged = result.contains("judge") && result["judge"].is_object();
    std::vector<std::vector<std::string>> rows = {
        {"fitness (full render)", fixed(jsonNumber(result, "fitness", NAN), 4)},
        {"judge: butteraugli p-norm / max (lower is better; no search reads it)",
         judged ? fixed(jsonNumber(result["judge"], "butteraugli", NAN), 3) + " / " +
                      fixed(jsonNumber(result["judge"], "butteraugli_max", NAN), 3)
                : std::string("– (optimize --no-judge)")},
        {"SSIM / boundary / information fidelity", fixed(fidelity("ssim"), 4) + " / " +
                                                       fixed(fidelity("boundary_entropy"), 4) + " / " +
                                                       fixed(fidelity("information_entropy"), 4)},
        {"precision / recall",
         fixed(jsonNumber(result, "precision", NAN), 4) + " / " + fixed(jsonNumber(result, "recall", NAN), 4)},
        {"predicted / budget (ms)",
         fixed(jsonNumber(result, "predicted_ms", NAN), 2) + " / " + fixed(jsonNumber(result, "budget_ms", NAN), 2)},
        {"time model", jsonText(result, "time_model", "–")},
        {"evaluations (cache hits)",
         jsonText(result, "evaluations", "–") + " (" + jsonText(result, "cache_hits", "–") + ")"},
        {"iterations, stop", jsonText(result, "iterations", "–") + ", " + jsonText(result, "stop_reason", "–")},
        {"wall time (setup + search, s)", fixed(jsonNumber(result, "wall_seconds", NAN), 3) + " (" +
                                              fixed(jsonNumber(result, "setup_seconds", NAN), 3) + " + " +
                                              fixed(jsonNumber(result, "search_seconds", NAN), 3) + ")"},
        {"evaluation path, evaluations/s",
         jsonText(result, "eval_path", "–") + ", " + fixed(jsonNumber(result, "evals_per_second", NAN), 0)},
    };
    if (result.contains("owned_windows") && result["owned_windows"].is_object()) {
        // The fast path's cache: how much of the SSIM work one object's level alone decides.
        const nlohmann::json& owned = result["owned_windows"];
        const double ownedWindows = jsonNumber(owned, "owned_ssim_windows", NAN);
        const double reached = ownedWindows + jsonNumber(owned, "live_ssim_windows", NAN);
        rows.push_back({"owned SSIM windows (share), cache entries filled",
                        jsonText(owned, "owned_ssim_windows", "–") + " (" +
                            fixed(reached > 0 ? 100.0 * ownedWindows / reached : NAN, 1) + " %), " +
                            jsonText(owned, "entries_filled", "–") + " of " + jsonText(owned, "entries", "–")});
    }
    if (result.contains("window_groups") && result["window_groups"].is_object()) {
        // The fast path's groups: how much of the SSIM work depends on several objects at once.
        const nlohmann::json& groups = result["window_groups"];
        const double windows = jsonNumber(groups, "ssim_windows", NAN);
        const double shared = jsonNumber(groups, "multi_object_ssim_windows", NAN);
        rows.push_back({"window groups, SSIM windows depending on 2+ objects (share), scores kept",
                        jsonText(groups, "groups", "–") + ", " + jsonText(groups, "multi_object_ssim_windows", "–") +
                            " (" + fixed(windows > 0 ? 100.0 * shared / windows : NAN, 1) + " %), " +
                            jsonText(groups, "kept_scores", "–")});
    }
    if (baseline.image.width > 0) {
        rows.push_back({"baseline " + baselineName + ": fitness, judge, predicted ms",
                        fixed(baseline.fitness, 4) + ", " + fixed(baseline.judge.distance, 3) + ", " +
                            fixed(baseline.predictedMs, 2)});
    }
    context.html.table({"", "value"}, rows);
}

void addImages(ReportContext& context, const fs::path& folder, const nlohmann::json& result, const Baseline& baseline,
               const std::string& baselineName) {
    const fs::path referencePath = folder / "reference.png", optimizedPath = folder / "optimized.png";
    if (!fs::exists(referencePath) || !fs::exists(optimizedPath)) {
        context.html.note("No images: " + folder.string() + " lacks reference.png or optimized.png.");
        return;
    }
    const renderer::Frame reference = loadRgbaImage(referencePath.string());
    const renderer::Frame optimized = loadRgbaImage(optimizedPath.string());
    const DifferenceMaps maps = differenceMaps(optimized, reference, optimizedPath.string());
    const fs::path dir(context.plotter.directory());
    const std::string ssimPath = (dir / (context.prefix + "ssim_map.png")).string();
    const std::string differencePath = (dir / (context.prefix + "difference.png")).string();
    renderer::writeColorImage(ssimPath, maps.ssimMap);
    renderer::writeColorImage(differencePath, maps.difference);
    // Three renders fit side by side on the page; small ones are scaled up without smoothing.
    const int display = reference.width < kSmallImage ? kSmallImage : std::min(reference.width, kLargeImage);
    std::vector<ReportImage> pictures = {
        makeImage(referencePath.string(), "Reference: every object at its finest level", "", display),
        makeImage(optimizedPath.string(),
                  "Optimized (" + jsonText(result, "algorithm", "?") + "): fitness " +
                      fixed(jsonNumber(result, "fitness", NAN), 4) + ", " +
                      fixed(jsonNumber(result, "predicted_ms", NAN), 2) + " ms predicted",
                  "", display),
    };
    if (baseline.image.width > 0) {
        const std::string baselinePath = (dir / (context.prefix + "baseline.png")).string();
        renderer::writeColorImage(baselinePath, baseline.image);
        pictures.push_back(makeImage(baselinePath,
                                     "Baseline (" + baselineName + ", same budget and time model): fitness " +
                                         fixed(baseline.fitness, 4) + ", " + fixed(baseline.predictedMs, 2) +
                                         " ms predicted",
                                     "", display));
    } else if (!baseline.note.empty()) {
        pictures.push_back(makeImage("", "Baseline (" + baselineName + ")", baseline.note));
    }
    ReportImage ssimImage = makeImage(
        ssimPath,
        "SSIM map, optimized vs reference (mean " + fixed(maps.meanSsim, 4) + "; the gray border has no full window)",
        "", display);
    ssimImage.legendGradient = magmaCss();
    ssimImage.legendLow = fixed(maps.ssimLow, 2);
    ssimImage.legendHigh = "1";
    ReportImage differenceImage =
        makeImage(differencePath,
                  "Difference heat map: largest |optimized − reference| over R, G, B; " +
                      formatNumber(100.0 * maps.changedShare, 2) + "% of pixels differ, at most " +
                      std::to_string(maps.largestDifference) + " levels",
                  "", display);
    differenceImage.legendGradient = infernoCss();
    differenceImage.legendLow = "0";
    differenceImage.legendHigh = std::to_string(maps.differenceHigh);
    context.html.images(pictures);
    context.html.images({ssimImage, differenceImage});

    // Where the judge sees the answer, and the baseline, differ from the reference.
    const metrics::JudgeParameters judgeParameters = judgeParametersOf(result);
    std::vector<ReportImage> judged;
    auto addJudgeMap = [&](const JudgeMap& map, const std::string& name, const std::string& label) {
        const std::string path = (dir / (context.prefix + name)).string();
        renderer::writeColorImage(path, map.heat);
        ReportImage picture = makeImage(path,
                                        "Judge's map, " + label + " vs reference: butteraugli " +
                                            fixed(judgeParameters.pnorm, 0) + "-norm " + fixed(map.distance, 3) +
                                            ", max " + fixed(map.maxDistance, 3) + " (about 1 = just noticeable)",
                                        "", display);
        picture.legendGradient = infernoCss();
        picture.legendLow = "0";
        picture.legendHigh = fixed(map.high, 0);
        judged.push_back(picture);
    };
    addJudgeMap(judgeMap(optimized, reference, judgeParameters, "optimized"), "judge_map.png", "optimized");
    if (baseline.image.width > 0) addJudgeMap(baseline.judge, "judge_map_baseline.png", "baseline " + baselineName);
    context.html.images(judged);
}

// The result's object names and chosen levels (-1 where a level is not an integer): from
// "combination" when it names every object of the scene, else from "levels".
void chosenLevels(const nlohmann::json& result, const SceneFacts& facts, std::vector<std::string>& names,
                  std::vector<int>& chosen) {
    if (result.contains("combination") && result["combination"].is_array() &&
        result["combination"].size() == facts.names.size()) {
        names = facts.names;
        for (const nlohmann::json& level : result["combination"])
            chosen.push_back(level.is_number_integer() ? level.get<int>() : -1);
    } else if (result.contains("levels") && result["levels"].is_object()) {
        for (auto it = result["levels"].begin(); it != result["levels"].end(); ++it) {
            names.push_back(it.key());
            chosen.push_back(it.value().is_number_integer() ? it.value().get<int>() : -1);
        }
    }
}

// The chosen levels drawn per object (few objects) or as objects per level (many).
void plotLevels(ReportContext& context, const std::vector<std::string>& names, const std::vector<int>& chosen,
                const Baseline& baseline, const std::string& baselineName, bool withBaseline, int maxLevel,
                const std::string& data) {
    PlotSpec spec;
    spec.name = context.prefix + "levels";
    spec.data = {{spec.name + ".dat", data}};
    std::ostringstream script;
    if (names.size() <= kLevelsPlottedPerObject) {
        spec.title = "Chosen level per object (0 = finest)";
        script << "set ylabel 'level (0 = finest, -1 = not drawn)'\nset yrange [" << maxLevel + 0.6 << ":-1.4]\n"
               << "set ytics 1\nset xrange [-0.6:" << names.size() - 0.4 << "]\nset xtics rotate by -35\n"
               << "set key outside right top\n"
               << "plot '" << spec.name << ".dat' using 1:(0):(0):($5-1):xtic(2) with yerrorbars lc rgb '#b8b8b8' "
               << "lw 6 pt -1 title 'available levels'";
        script << ", '' using 1:3 with points pt 7 ps 1.6 lc rgb '" << seriesColor(0) << "' title 'optimized'";
        if (withBaseline) {
            script << ", '' using 1:4 with points pt 6 ps 2.4 lw 2 lc rgb '" << seriesColor(1) << "' title '"
                   << baselineName << "'";
        }
        spec.height = 400;
    } else {
        // Many objects: how many sit at each level.
        std::ostringstream histogram;
        histogram << "# level, objects at it (optimized), (" << baselineName << ")\n";
        for (int level = -1; level <= maxLevel; ++level) {
            const auto count = [&](const std::vector<int>& values) {
                return std::count(values.begin(), values.end(), level);
            };
            histogram << level << ' ' << count(chosen) << ' ' << (withBaseline ? count(baseline.levels) : 0) << '\n';
        }
        spec.data.push_back({spec.name + "_histogram.dat", histogram.str()});
        spec.title = "Objects per level (" + std::to_string(names.size()) + " objects; -1 = not drawn)";
        script << "set style data histogram\nset style histogram clustered gap 1\n"
               << "set style fill solid 0.85 border -1\nset xlabel 'level (0 = finest)'\nset ylabel 'objects'\n"
               << "set yrange [0:*]\nset key top left\n"
               << "plot '" << spec.name << "_histogram.dat' using 2:xtic(1) lc rgb '" << seriesColor(0)
               << "' title 'optimized'";
        if (withBaseline) script << ", '' using 3 lc rgb '" << seriesColor(1) << "' title '" << baselineName << "'";
    }
    script << "\n";
    spec.script = script.str();
    context.plot(spec, "Levels chosen by the optimizer" + std::string(withBaseline ? " and by " + baselineName : "") +
                           ". Data: " + spec.name + ".dat");
}

void addLevels(ReportContext& context, const nlohmann::json& result, const SceneFacts& facts, const Baseline& baseline,
               const std::string& baselineName) {
    std::vector<std::string> names;
    std::vector<int> chosen;
    chosenLevels(result, facts, names, chosen);
    if (names.empty()) return;
    const bool withBaseline = baseline.levels.size() == names.size();
    const bool withCounts = facts.levelCounts.size() == names.size();
    context.html.heading(3, "Chosen levels per object");
    std::vector<std::vector<std::string>> rows;
    std::ostringstream data;
    data << "# object index, name, optimized level, " << (withBaseline ? baselineName : "-") << " level, levels\n";
    int maxLevel = 0;
    for (std::size_t o = 0; o < names.size(); ++o) {
        const int levels = withCounts ? facts.levelCounts[o] : 0;
        std::vector<std::string> row = {names[o], std::to_string(chosen[o])};
        if (withBaseline) row.push_back(std::to_string(baseline.levels[o]));
        if (withCounts) row.push_back(std::to_string(levels));
        rows.push_back(row);
        maxLevel = std::max({maxLevel, chosen[o], withBaseline ? baseline.levels[o] : 0, levels - 1});
        data << o << ' ' << gnuplotDataField(names[o]) << ' ' << chosen[o] << ' '
             << (withBaseline ? std::to_string(baseline.levels[o]) : "NaN") << ' ' << (withCounts ? levels : 0) << '\n';
    }
    std::vector<std::string> header = {"object", "optimized level"};
    if (withBaseline) header.push_back(baselineName + " level");
    if (withCounts) header.push_back("levels available");
    plotLevels(context, names, chosen, baseline, baselineName, withBaseline, maxLevel, data.str());
    if (rows.size() <= 24) {
        context.html.table(header, rows);
    } else {
        std::ostringstream text;
        for (const auto& row : rows) {
            for (std::size_t c = 0; c < row.size(); ++c) text << (c ? "\t" : "") << row[c];
            text << "\n";
        }
        context.html.details("All " + std::to_string(rows.size()) + " objects (name, level, ...)", text.str());
    }
}

void addCurve(ReportContext& context, const fs::path& curvePath) {
    if (!fs::exists(curvePath)) return;
    const CsvTable curve = readCsv(curvePath.string());
    for (const char* column : {"evaluations", "best_fitness", "mean_fitness"}) {
        if (!curve.has(column)) throw UsageError(curvePath.string() + ": no column '" + column + "'");
    }
    if (curve.rows.empty()) return;
    context.html.heading(3, "Fitness curve");
    std::ostringstream data;
    data << "# evaluations best_fitness mean_fitness best_predicted_ms\n";
    const bool predicted = curve.has("best_predicted_ms");
    for (std::size_t r = 0; r < curve.rows.size(); ++r) {
        data << curve.number(r, "evaluations") << ' ' << curve.number(r, "best_fitness") << ' '
             << curve.number(r, "mean_fitness") << ' ' << (predicted ? curve.number(r, "best_predicted_ms") : NAN)
             << '\n';
    }
    PlotSpec spec;
    spec.name = context.prefix + "curve";
    spec.title = "Fitness against evaluations";
    spec.data = {{spec.name + ".dat", data.str()}};
    std::ostringstream script;
    script << "set xlabel 'evaluations (renders)'\nset ylabel 'fitness'\n"
           << "set key outside top center horizontal maxrows 1 samplen 2\n";
    if (predicted) script << "set y2label 'predicted ms of the best'\nset y2tics\nset ytics nomirror\n";
    script << "plot '" << spec.name << ".dat' using 1:2 with steps lw 2 lc rgb '" << seriesColor(0)
           << "' title 'best so far', '' using 1:3 with linespoints pt 7 ps 0.6 lc rgb '" << seriesColor(4)
           << "' title 'iteration mean'";
    if (predicted) {
        script << ", '' using 1:4 axes x1y2 with steps dt 2 lc rgb '" << seriesColor(2)
               << "' title 'predicted ms (right axis)'";
    }
    script << "\n";
    spec.script = script.str();
    context.plot(spec, "Best fitness so far and each iteration's mean, from " + curvePath.filename().string() + ".");
}

}  // namespace

void addOptimizeSection(ReportContext& context, const fs::path& folder) {
    const nlohmann::json result = readJsonFile((folder / "result.json").string());
    if (!result.is_object()) throw UsageError((folder / "result.json").string() + ": expected a JSON object");
    context.html.heading(2, "optimize: " + jsonText(result, "scene", "?") + " / " + jsonText(result, "view", "?") +
                                " — " + jsonText(result, "algorithm", "?"));
    context.html.paragraph("From " + folder.string() + ".");
    SceneFacts facts;
    Baseline baseline;
    const std::string baselineName = context.options.baseline;
    if (baselineName != "none") {
        baseline = runBaseline(result, folder, context.options, facts);
        if (!baseline.note.empty()) std::cerr << "lodopt: report: " << baseline.note << "\n";
    }
    if (facts.names.empty()) facts = loadSceneFacts(result);
    addFacts(context, result, baseline, baselineName);
    addImages(context, folder, result, baseline, baselineName);
    addLevels(context, result, facts, baseline, baselineName);
    addCurve(context, folder / "curve.csv");
}

}  // namespace lodopt::cli
