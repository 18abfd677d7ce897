// lodopt tune: fits the scheduler's importance coefficients and distance thresholds so that its
// per-frame choices score close to the optimizer's on sampled viewpoints (or camera-path frames).
//
// Per view: the optimizer's answer (any algorithm, default gapso) under the budget, scored with
// the view's fast evaluator; the scheduler's choice on the same view is scored with the same
// evaluator (its scene levels mapped by ViewSetup::fromScene), so "the scheduler's fitness as a
// fraction of the optimizer's" compares like with like. Each finished view is checkpointed to
// <out stem>_views/view_NNN.json; --resume skips views whose checkpoint has the same settings,
// and without it an existing checkpoint is refused rather than overwritten. Each view is one
// unit of work: an interrupt (SIGINT/SIGTERM) stops after the view in progress is saved. The
// checkpoints stay after the run (the report names the folder), so a later run can reuse them.
// Views are split into tuning and held-out ones; the compass search (scheduler/tuning.hpp)
// maximises the mean fraction on the tuning views, and both the tuned coefficients and the
// published defaults are reported on the held-out views. The written set is the form with the
// better tuning score (--select tuning, the default), or the defaults or a tuned form chosen by
// k-fold cross-validation over the tuning views (--select cv), a guard against a search that
// over-fits its views; the held-out views play no part in either choice. At 12–24 tuning views
// cross-validation chose worse than the tuning score (docs/scheduler.md), hence not the default.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "cli_common.hpp"
#include "evaluation/evaluation.hpp"
#include "evaluation/scheduler_tuning.hpp"
#include "evaluation/time_cost.hpp"
#include "interrupt.hpp"
#include "optimize_run.hpp"
#include "progress.hpp"
#include "schedule_common.hpp"
#include "sweep_files.hpp"
#include "scheduler/coefficients.hpp"
#include "scheduler/tuning.hpp"
#include "time_profile.hpp"
#include "timemodel/calibration.hpp"

namespace lodopt::cli {
namespace {

struct TuneOptions {
    OptimizeOptions optimize;
    int views = 16;
    std::string path;
    int holdout = 0;  // 0 = automatic
    std::string out = "coeffs.json";
    std::string form = "auto";
    int searchEvaluations = 150;
    std::string features = "bounds";
    std::string organisation = "flat";
    std::string select = "tuning";
    int folds = 3;
    bool resume = false;
    std::string from;  // a sweep folder whose answers replace the per-view searches
};

// The options that change a view's optimizer answer, keyed by option name (checkIdentity).
nlohmann::json settingsSignature(const TuneOptions& o) {
    const OptimizeOptions& p = o.optimize;
    return {{"scene", p.scene},
            {"scene-seed", p.sceneSeed},
            {"seed", p.seed},
            {"size", p.size},
            {"shading", p.shading},
            {"budget-ms", p.budgetMs},
            {"algo", p.algorithm},
            {"evals", p.maxEvaluations},
            {"max-iterations", p.maxIterations},
            {"weights", p.weights},
            {"profile", p.profile},
            {"model", p.model},
            {"path", o.path},
            {"view-count", o.views},
            {"fill", effectiveFillProbability(p)}};
}

std::filesystem::path checkpointDir(const std::string& out) {
    const std::filesystem::path file(out);
    return file.parent_path() / (file.stem().string() + "_views");
}

// Without --resume, view files of an interrupted tune are refused (they would be lost); those
// of a finished one (the coefficients file is at least as new as every view file) are cleared,
// so that running the same tune again just works.
void refuseExistingCheckpoints(const TuneOptions& options) {
    const std::filesystem::path dir = checkpointDir(options.out);
    if (options.resume || !std::filesystem::is_directory(dir)) return;
    std::vector<std::filesystem::path> saved;
    std::filesystem::file_time_type newest = std::filesystem::file_time_type::min();
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("view_", 0) != 0 || entry.path().extension() != ".json") continue;
        saved.push_back(entry.path());
        newest = std::max(newest, entry.last_write_time());
    }
    if (saved.empty()) return;
    std::error_code error;
    const auto finished = std::filesystem::last_write_time(options.out, error);
    if (!error && finished >= newest) {
        for (const std::filesystem::path& file : saved) std::filesystem::remove(file);
        return;
    }
    throw UsageError(dir.string() + " holds " + std::to_string(saved.size()) +
                     " view checkpoint(s) of an unfinished tune: add --resume to reuse them, or delete the "
                     "folder to start over");
}

std::vector<scenes::Camera> sampleCameras(const scenes::Scene& scene, const TuneOptions& options) {
    std::vector<scenes::Camera> cameras;
    const int n = options.views;
    if (!options.path.empty()) {
        const scenes::CameraPath path = loadCameraPath(scene, options.path);
        const int frames = int(path.frames.size());
        for (int k = 0; k < n; ++k) {
            const int f = n == 1 ? 0 : int(std::lround(double(k) * double(frames - 1) / double(n - 1)));
            cameras.push_back(path.frames[std::size_t(f)]);
        }
        return cameras;
    }
    if (scene.views.empty()) throw UsageError("scene '" + scene.name + "' has no views to sample around");
    timemodel::SplitMix64 rng(options.optimize.seed);
    for (int k = 0; k < n; ++k) {
        const scenes::Camera& around = scene.views[std::size_t(k) % scene.views.size()];
        scenes::Camera camera = timemodel::jitterCamera(around, rng);
        camera.name = "tune_" + std::to_string(k) + "_" + around.name;
        cameras.push_back(camera);
    }
    return cameras;
}

nlohmann::json coefficientsJson(const scheduler::SchedulerCoefficients& c) {
    return nlohmann::json::parse(scheduler::coefficientsToJson(c));
}

// Each view's optimizer answer: given (a sweep's, `given` non-empty), from its checkpoint with
// --resume (`resumed`), or searched and checkpointed; then its cost and the answer's fitness by
// the view's evaluator.
void prepareViews(const TuneOptions& options, PreparedScene& prepared, std::vector<evaluation::TuningView>& views,
                  const std::vector<scenes::Combination>& given, std::vector<bool>& resumed,
                  const OutputOptions& output) {
    const std::filesystem::path dir = checkpointDir(options.out);
    const nlohmann::json signature = settingsSignature(options);
    Progress progress("tune: optimizer per view", views.size(), output.quiet);
    InterruptGuard interruptGuard;
    for (std::size_t k = 0; k < views.size(); ++k) {
        evaluation::TuningView& view = views[k];
        std::ostringstream name;
        name << "view_" << std::setw(3) << std::setfill('0') << k << ".json";
        const std::filesystem::path checkpoint = dir / name.str();
        prepared.scene.views.push_back(view.camera);
        const int viewIndex = int(prepared.scene.views.size()) - 1;
        if (!given.empty()) {
            view.optimizerLevels = given[k];
            scenes::validateCombination(prepared.scene, view.optimizerLevels);
            view.setup = std::make_unique<evaluation::ViewSetup>(prepared.scene, view.camera, *prepared.renderer);
            view.evaluator = std::make_unique<evaluation::LayerEvaluator>(
                *view.setup, evaluation::searchParameters(prepared.metrics), options.optimize.threads,
                evaluation::DirtyRegions::ChangedPixels, options.optimize.evalStates);
        } else if (options.resume && std::filesystem::exists(checkpoint)) {
            std::ifstream file(checkpoint);
            std::ostringstream text;
            text << file.rdbuf();
            const nlohmann::json saved = nlohmann::json::parse(text.str(), nullptr, false);
            if (saved.is_discarded() || !saved.contains("settings") || !saved.contains("camera") ||
                !saved.contains("combination")) {
                throw UsageError(checkpoint.string() + ": not a tune checkpoint (delete it or drop --resume)");
            }
            checkIdentity(checkpoint.string(), saved["settings"], signature);
            if (saved["camera"] != cameraToJson(view.camera)) {
                throw UsageError(checkpoint.string() +
                                 ": made from another viewpoint; delete the folder or drop --resume");
            }
            view.optimizerLevels = saved["combination"].get<scenes::Combination>();
            view.optimizerSeconds = saved.value("seconds", 0.0);
            resumed[k] = true;
            scenes::validateCombination(prepared.scene, view.optimizerLevels);
            view.setup = std::make_unique<evaluation::ViewSetup>(prepared.scene, view.camera, *prepared.renderer);
            view.evaluator = std::make_unique<evaluation::LayerEvaluator>(
                *view.setup, evaluation::searchParameters(prepared.metrics), options.optimize.threads,
                evaluation::DirtyRegions::ChangedPixels, options.optimize.evalStates);
        } else {
            const auto start = std::chrono::steady_clock::now();
            evaluation::SearchView context = prepareView(prepared, viewIndex, options.optimize);
            const optimizer::Result result =
                runAlgorithm(context, options.optimize, options.optimize.algorithm, options.optimize.seed);
            view.optimizerSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            view.optimizerLevels = context.setup->toScene(result.best);
            view.setup = std::move(context.setup);
            view.evaluator = std::move(context.evaluator);
            nlohmann::json saved = {{"format", "lodopt-tune-view"},
                                    {"version", 2},
                                    {"settings", signature},
                                    {"index", k},
                                    {"held_out", view.heldOut},
                                    {"camera", cameraToJson(view.camera)},
                                    {"combination", view.optimizerLevels},
                                    {"search_fitness", result.bestScore.fitness},
                                    {"predicted_ms", result.predictedMs},
                                    {"evaluations", result.evaluations},
                                    {"seconds", view.optimizerSeconds}};
            writeJsonFile(checkpoint.string(), saved);
        }
        view.cost = std::make_unique<evaluation::TimeModelCost>(*view.setup, prepared.estimator, prepared.readFeatures);
        // Scored here with the same evaluator as every scheduler choice, resumed or not.
        view.optimizerFitness = view.evaluator->evaluate(view.setup->fromScene(view.optimizerLevels)).fitness;
        progress.step(view.camera.name + (resumed[k] ? " (resumed)" : ""));
        // After the last view only the coefficient search is left: finish it rather than stop.
        try {
            if (k + 1 < views.size()) pollInterrupt("tune", k + 1, views.size(), "view", dir.string());
        } catch (const Interrupted&) {
            progress.finish();  // the message starts on a clean line
            throw;
        }
    }
    progress.finish();
}

// What one tune run decided and measured, for the report and the text summary.
struct TuneRun {
    explicit TuneRun(const TuneOptions& tuneOptions) : options(tuneOptions) {}
    const TuneOptions& options;
    int holdout = 1;
    int folds = 0;  // >= 2 when choosing by cross-validation
    std::string sceneName;
    std::string timeModel;
    scheduler::FeatureMode mode = scheduler::FeatureMode::Bounds;
    scheduler::Organisation organisation = scheduler::Organisation::Flat;
    evaluation::TuningSettings settings;
    evaluation::TuningOutcome outcome;
    double seconds = 0.0;
    bool crossValidated() const { return outcome.crossValidated; }
    bool keptDefaults() const { return outcome.chosen < 0; }
    std::string writtenName() const {
        return keptDefaults() ? std::string("defaults")
                              : scheduler::toString(outcome.forms[std::size_t(outcome.chosen)].form);
    }
};

// --view-count views with their held-out flags and cross-validation folds (--holdout, --folds).
std::vector<evaluation::TuningView> assignViews(const std::vector<scenes::Camera>& cameras, const TuneRun& run) {
    const int count = int(cameras.size());
    const std::vector<bool> heldOut = scheduler::heldOutViews(count, run.holdout);
    const std::vector<int> foldOf = scheduler::tuningFolds(heldOut, std::max(run.folds, 1));
    std::vector<evaluation::TuningView> views(cameras.size());
    for (std::size_t k = 0; k < views.size(); ++k) {
        views[k].camera = cameras[k];
        views[k].heldOut = heldOut[k];
        views[k].fold = foldOf[k];
    }
    return views;
}

evaluation::TuningSettings tuningSettings(const TuneRun& run, const scheduler::SceneIndex& index,
                                          const std::vector<evaluation::TuningView>& views) {
    std::vector<scenes::Camera> tuningCameras;
    for (const evaluation::TuningView& view : views) {
        if (!view.heldOut) tuningCameras.push_back(view.camera);
    }
    evaluation::TuningSettings settings;
    settings.scales = scheduler::measureTermScales(index, tuningCameras);
    settings.thresholdCount = std::max(1, index.maxLevelCount() - 1);
    const std::string& form = run.options.form;
    if (form == "published" || form == "auto") settings.forms.push_back(scheduler::ImportanceForm::Published);
    if (form == "extended" || form == "auto") settings.forms.push_back(scheduler::ImportanceForm::Extended);
    settings.search.maxEvaluations = run.options.searchEvaluations;
    settings.search.seed = run.options.optimize.seed;
    settings.folds = run.folds;
    return settings;
}

nlohmann::json perViewJson(std::vector<evaluation::TuningView>& views, const std::vector<bool>& resumed,
                           scheduler::FrameScheduler& frameScheduler, const scheduler::SchedulerCoefficients& written) {
    const scheduler::SchedulerCoefficients defaults;
    nlohmann::json perView = nlohmann::json::array();
    for (std::size_t k = 0; k < views.size(); ++k) {
        evaluation::TuningView& view = views[k];
        const evaluation::SchedulerScore byDefaults = evaluation::scoreScheduler(view, frameScheduler, defaults);
        const evaluation::SchedulerScore tuned = evaluation::scoreScheduler(view, frameScheduler, written);
        perView.push_back({{"view", view.camera.name},
                           {"held_out", view.heldOut},
                           {"resumed", bool(resumed[k])},
                           {"optimizer_fitness", view.optimizerFitness},
                           {"optimizer_predicted_ms", view.cost->predictSceneMs(view.optimizerLevels)},
                           {"optimizer_seconds", view.optimizerSeconds},
                           {"default_fitness", byDefaults.fitness},
                           {"default_fraction", byDefaults.fraction},
                           {"default_predicted_ms", byDefaults.predictedMs},
                           {"tuned_fitness", tuned.fitness},
                           {"tuned_fraction", tuned.fraction},
                           {"tuned_predicted_ms", tuned.predictedMs}});
    }
    return perView;
}

nlohmann::json tuneReport(const TuneRun& run, nlohmann::json perView) {
    const TuneOptions& options = run.options;
    const evaluation::TuningOutcome& outcome = run.outcome;
    nlohmann::json formsJson = nlohmann::json::object();
    for (const evaluation::FormTuning& r : outcome.forms) {
        nlohmann::json& form = formsJson[scheduler::toString(r.form)];
        form = {{"tuning_fraction", r.search.bestValue},
                {"held_out_fraction", r.heldOutFraction},
                {"search_evaluations", r.search.evaluations},
                {"coefficients", coefficientsJson(r.coefficients)}};
        if (run.crossValidated()) form["cross_validated_fraction"] = r.crossValidatedFraction;
    }
    nlohmann::json selection = {{"rule", run.crossValidated() ? "cv" : "tuning"}, {"written", run.writtenName()}};
    if (run.crossValidated()) {
        selection["folds"] = run.folds;
        selection["defaults_cross_validated_fraction"] = outcome.defaultTuningFraction;
    }
    const scheduler::TermScales& scales = run.settings.scales;
    return {
        {"scene", run.sceneName},
        {"scene_seed", options.optimize.sceneSeed},
        {"budget_ms", options.optimize.budgetMs},
        {"size", options.optimize.size},
        {"shading", options.optimize.shading},
        {"views", options.views},
        {"held_out_views", run.holdout},
        {"path", options.path},
        {"from", options.from},
        {"algorithm", options.optimize.algorithm},
        {"optimizer_evals", options.optimize.maxEvaluations},
        {"time_model", run.timeModel},
        {"features", scheduler::toString(run.mode)},
        {"organisation", scheduler::toString(run.organisation)},
        {"form", run.keptDefaults() ? std::string("published") : run.writtenName()},
        {"selection", selection},
        {"term_scales",
         {{"distance", scales.distance}, {"area", scales.area}, {"pixels", scales.pixels}, {"center", scales.center}}},
        {"defaults",
         {{"tuning_fraction", outcome.defaultTuningFraction}, {"held_out_fraction", outcome.defaultHeldOutFraction}}},
        {"tuned",
         {{"tuning_fraction", outcome.writtenTuningFraction}, {"held_out_fraction", outcome.writtenHeldOutFraction}}},
        {"forms", formsJson},
        {"per_view", std::move(perView)},
        {"checkpoints", checkpointDir(options.out).string()},
        {"seconds", run.seconds},
    };
}

void printTune(const TuneRun& run) {
    const TuneOptions& options = run.options;
    const evaluation::TuningOutcome& outcome = run.outcome;
    const bool crossValidate = run.crossValidated();
    std::cout << std::fixed << std::setprecision(4);
    std::cout << run.sceneName << ": " << options.views << " views (" << run.holdout << " held out), budget "
              << options.optimize.budgetMs << " ms, optimizer " << options.optimize.algorithm << "\n";
    // Cross-validated: the mean out-of-fold fraction over the tuning views (the choice's score).
    auto crossValidatedText = [&](double value) {
        std::ostringstream text;
        text << std::fixed << std::setprecision(4) << value;
        return crossValidate ? text.str() : std::string("     -");
    };
    std::cout << "scheduler fitness / optimizer fitness      tuning   " << (crossValidate ? "cross-val" : "         ")
              << "   held-out\n";
    std::cout << "  published defaults (a1 0.6, a2 0.4)      " << outcome.defaultTuningFraction << "   "
              << crossValidatedText(outcome.defaultTuningFraction) << "      " << outcome.defaultHeldOutFraction
              << (run.keptDefaults() ? "  <- written" : "") << "\n";
    for (std::size_t i = 0; i < outcome.forms.size(); ++i) {
        const evaluation::FormTuning& r = outcome.forms[i];
        std::cout << "  tuned, " << std::left << std::setw(34) << scheduler::toString(r.form) << std::right
                  << r.search.bestValue << "   " << crossValidatedText(r.crossValidatedFraction) << "      "
                  << r.heldOutFraction << (int(i) == outcome.chosen ? "  <- written" : "") << "\n";
    }
    if (crossValidate) {
        std::cout << "  (written: the best " << run.folds << "-fold cross-validated fraction over the tuning views)\n";
    }
    const scheduler::SchedulerCoefficients& written = outcome.written;
    const scheduler::ImportanceCoefficients& a = written.importance;
    std::cout << "  alpha " << a.alpha1 << ", " << a.alpha2 << ", " << a.alpha3 << ", " << a.alpha4
              << "; thresholds (radii)";
    std::cout << std::setprecision(2);
    for (double t : written.thresholds.values) std::cout << " " << t;
    std::cout << "; benchmark scale " << written.benchmark.scale << "\n";
    std::cout << "wrote " << options.out << " (" << std::setprecision(1) << run.seconds << " s)\n";
    std::cout.unsetf(std::ios::floatfield);
}

// The cameras and answers of a sweep (--from), its feasible views only (where even the coarsest
// combination is over the budget there is nothing to trade). The sweep must have been made with
// the options that change a view's evaluator and cost.
std::vector<scenes::Camera> sweepAnswers(const TuneOptions& options, std::vector<scenes::Combination>& given) {
    const SweepTable table = readSweepTable(options.from);
    const OptimizeOptions& o = options.optimize;
    checkSweepSettings(options.from, table,
                       {{"scene", o.scene}, {"scene-seed", o.sceneSeed}, {"size", o.size}, {"shading", o.shading},
                        {"budget-ms", o.budgetMs}, {"weights", o.weights}, {"profile", o.profile}, {"model", o.model}});
    std::vector<scenes::Camera> cameras;
    for (const SweepTableView& view : table.views) {
        if (!view.feasible) continue;
        cameras.push_back(view.camera);
        given.push_back(view.levels);
    }
    return cameras;
}

void runTune(TuneOptions options, const OutputOptions& output) {
    checkAlgorithmName(options.optimize.algorithm);
    std::vector<scenes::Combination> given;
    std::vector<scenes::Camera> sweepCameras;
    if (!options.from.empty()) {
        if (!options.path.empty()) throw UsageError("tune: --from takes the sweep's views; drop --path");
        sweepCameras = sweepAnswers(options, given);
        options.views = int(sweepCameras.size());
        if (options.views < 2) {
            throw UsageError("--from " + options.from + ": " + std::to_string(options.views) +
                             " feasible view(s); tuning needs at least 2");
        }
    }
    if (options.views < 2) throw UsageError("--view-count: at least 2 (tuning and held-out views)");
    TuneRun run(options);
    run.holdout = options.holdout > 0 ? options.holdout : std::max(1, options.views / 4);
    if (run.holdout >= options.views) {
        throw UsageError("--holdout " + std::to_string(run.holdout) + ": must leave at least one of the " +
                         std::to_string(options.views) + " views for tuning");
    }
    // Cross-validation needs two folds of at least one tuning view each.
    const int folds = std::min(options.folds, options.views - run.holdout);
    run.folds = options.select == "cv" && folds >= 2 ? folds : 0;
    if (options.select == "cv" && run.folds == 0) {
        std::cerr << "lodopt: warning: --select cv needs at least 2 tuning views (this run has "
                  << options.views - run.holdout << "); choosing by the tuning score\n";
    }
    if (options.from.empty()) refuseExistingCheckpoints(options);
    const auto start = std::chrono::steady_clock::now();
    options.optimize.view = "0";
    // One evaluator per view stays alive for the whole run: one state per thread, not the
    // optimizer's default four (memory grows with the view count).
    options.optimize.evalStates = 1;
    PreparedScene prepared = prepareScene(options.optimize);
    run.sceneName = prepared.scene.name;
    run.timeModel = prepared.timeModelName;
    std::vector<evaluation::TuningView> views =
        assignViews(options.from.empty() ? sampleCameras(prepared.scene, options) : sweepCameras, run);
    std::vector<bool> resumed(views.size(), false);
    prepareViews(options, prepared, views, given, resumed, output);

    run.mode = parseFeatureMode(options.features);
    run.organisation = parseOrganisation(options.organisation);
    const scheduler::SceneIndex index(prepared.scene, prepared.settings.width, prepared.settings.height, run.mode, 0,
                                      prepared.readFeatures);
    scheduler::SchedulerParameters parameters;
    parameters.budgetMs = options.optimize.budgetMs;
    parameters.switchControl.enabled = false;  // single views: nothing to hold
    parameters.organisation = run.organisation;
    // The model the optimizer's cost used, without feedback (its warnings were printed once
    // already by prepareScene).
    std::ostringstream repeatedWarnings;
    const TimeEstimator estimator =
        loadTimeEstimator(options.optimize.profile, options.optimize.model, prepared.scene.name, prepared.settings,
                          prepared.renderer.get(), repeatedWarnings);
    scheduler::FrameScheduler frameScheduler(index, estimator.model->clone(), parameters);

    run.settings = tuningSettings(run, index, views);
    run.outcome = evaluation::tuneSchedulerCoefficients(views, frameScheduler, run.settings);
    nlohmann::json perView = perViewJson(views, resumed, frameScheduler, run.outcome.written);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    nlohmann::json report = tuneReport(run, std::move(perView));
    nlohmann::json document = coefficientsJson(run.outcome.written);
    document["tuning"] = report;
    writeJsonFile(options.out, document);
    if (output.json) {
        report["out"] = options.out;
        report["coefficients"] = coefficientsJson(run.outcome.written);
        printJson(report);
        return;
    }
    printTune(run);
}

}  // namespace

void addTuneCommand(CLI::App& app) {
    auto options = std::make_shared<TuneOptions>();
    auto output = std::make_shared<OutputOptions>();
    options->optimize.size = "256x256";
    options->optimize.maxEvaluations = 150;
    CLI::App* command =
        app.add_subcommand("tune", "Fit the scheduler's importance coefficients to the optimizer's answers");
    OptimizeOptions& o = options->optimize;
    addSceneOption(*command, o.scene);
    command->add_option("--view-count", options->views, "Viewpoints to sample (or path frames to take)")
        ->check(CLI::Range(2, 100000))
        ->capture_default_str();
    command->add_option("--path", options->path, "Take the views from a camera path (name or JSON file)");
    command->add_option("--from", options->from,
                        "Take the views and the optimizer's answers from a sweep folder (lodopt sweep)");
    command->add_option("--budget-ms", o.budgetMs, "Predicted render-time budget in milliseconds")
        ->required()
        ->check(CLI::PositiveNumber);
    command->add_option("--out", options->out, "Coefficients file to write (JSON)")->capture_default_str();
    command->add_option("--algo", o.algorithm, "Optimizer per view: " + algorithmList())->capture_default_str();
    command->add_option("--evals", o.maxEvaluations, "Optimizer evaluation budget per view")
        ->check(CLI::Range(std::int64_t(1), std::int64_t(1) << 40))
        ->capture_default_str();
    addFillOption(*command, o);
    command->add_option("--max-iterations", o.maxIterations, "Optimizer iterations per view")
        ->check(CLI::Range(0, 1000000))
        ->capture_default_str();
    command->add_option("--search-evals", options->searchEvaluations, "Coefficient-search evaluations per form")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    command->add_option("--holdout", options->holdout, "Held-out views (default: a quarter, at least 1)")
        ->check(CLI::Range(1, 100000));
    command->add_option("--form", options->form, "Importance form: published, extended, or auto (tuning chooses)")
        ->check(CLI::IsMember({"auto", "published", "extended"}))
        ->capture_default_str();
    command->add_option("--features", options->features, "Scheduler features: bounds or exact")
        ->check(CLI::IsMember({"bounds", "exact"}))
        ->capture_default_str();
    command->add_option("--organisation", options->organisation, "Scheduler: flat or tiles")
        ->check(CLI::IsMember({"flat", "tiles"}))
        ->capture_default_str();
    command->add_option("--seed", o.seed, "Seed of the viewpoints, the optimizer and the search")
        ->capture_default_str();
    addSceneSeedOption(*command, o.sceneSeed);
    addSizeOption(*command, o.size, "Render size WIDTHxHEIGHT");
    addShadingOption(*command, o.shading);
    command->add_option("--threads", o.threads, "Evaluation threads")->check(CLI::Range(1, 256));
    addWeightsOption(*command, o.weights);
    addProfileOptions(*command, o.profile, o.model);
    command
        ->add_option("--select", options->select,
                     "Written set: tuning (the form with the best tuning score) or cv (the defaults or a tuned "
                     "form, by cross-validation over the tuning views)")
        ->check(CLI::IsMember({"cv", "tuning"}))
        ->capture_default_str();
    command->add_option("--folds", options->folds, "Cross-validation folds (--select cv)")
        ->check(CLI::Range(2, 1000))
        ->capture_default_str();
    addResumeFlag(*command, options->resume,
                  "the views in <out stem>_views/ (same settings; without --resume they are refused)");
    addOutputOptions(*command, *output);
    command->callback([options, output] { runTune(*options, *output); });
}

}  // namespace lodopt::cli
