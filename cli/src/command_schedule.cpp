// lodopt schedule: the real-time scheduler along a camera path, one decision per frame without
// rendering; with --render each frame is then rendered headless, timed, scored against the
// all-finest reference and its measured time fed back into the time model.
//
// Frames are checkpointed in batches (--batch) to <out>/schedule.checkpoint.json; an interrupt
// (SIGINT/SIGTERM) stops after the current batch and --resume continues from it
// (schedule_checkpoint.hpp): without --render the outputs equal an uninterrupted run's, wall
// times aside. The checkpoint is removed once frames.csv and summary.json are written.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "checkpoint.hpp"
#include "cli_common.hpp"
#include "interrupt.hpp"
#include "evaluation/schedule_walk.hpp"
#include "progress.hpp"
#include "renderer/renderer.hpp"
#include "scenes/atomic_file.hpp"
#include "scenes/builtin.hpp"
#include "schedule_checkpoint.hpp"
#include "schedule_common.hpp"
#include "schedule_rows.hpp"
#include "scheduler/coefficients.hpp"
#include "scheduler/scheduler.hpp"
#include "time_profile.hpp"

namespace lodopt::cli {
namespace {

struct ScheduleOptions {
    std::string scene = "harbor";
    std::uint32_t sceneSeed = 1;
    std::string path;
    double budgetMs = 0.0;
    std::string coefficients;
    bool render = false;
    bool noFitness = false;
    bool noBaseline = false;
    bool checkFeatures = false;
    std::string size = "512x512";
    std::string shading = renderer::shadingName(renderer::kDefaultShading);
    std::string profile;
    std::string model;
    std::string organisation = "flat";
    std::string features = "bounds";
    bool noSwitchControl = false;
    std::string switchControl;
    std::string switchRule = "hysteresis";
    // The library's defaults, so that the CLI cannot drift from them.
    double switchMargin = scheduler::SwitchControlParameters{}.raiseMargin;
    double switchRefill = scheduler::SwitchControlParameters{}.refillBelow;
    bool noFeedback = false;
    double beta = timemodel::FeedbackParameters{}.beta;
    int frames = 0;
    int stride = 1;
    // A frame's measured time: the median of 5 timed draws, what every device profile predicts
    // (docs/scheduler.md "Measured frame time").
    int repeats = 5;
    // After the path, the first, middle and last frames' decisions are each timed this often back to
    // back: how far one frame's measurement scatters here bounds what any scheduler can put
    // within ±10% of the budget (scheduler/measurement.hpp). Not part of a frame's row.
    int noiseProbe = 20;
    int batch = 25;
    bool resume = false;
    std::string outDir = "out/schedule";
    BackendOptions backend;
};

// Everything that changes a frame's row, keyed by option name (--batch does not). The
// coefficients are recorded by value, so a rewritten file does not resume silently.
nlohmann::json checkpointIdentity(const ScheduleOptions& o, const scheduler::SchedulerParameters& parameters) {
    return {{"scene", o.scene},
            {"scene-seed", o.sceneSeed},
            {"path", o.path},
            {"budget-ms", o.budgetMs},
            {"coeffs",
             {{"file", o.coefficients},
              {"values", nlohmann::json::parse(scheduler::coefficientsToJson(parameters.coefficients))}}},
            {"render", o.render},
            {"no-fitness", o.noFitness},
            {"no-baseline", o.noBaseline},
            {"check-features", o.checkFeatures},
            {"size", o.size},
            {"shading", o.shading},
            {"profile", o.profile},
            {"model", o.model},
            {"organisation", o.organisation},
            {"features", o.features},
            {"no-switch-control", o.noSwitchControl},
            {"switch-control", o.switchControl},
            {"switch-rule", o.switchRule},
            {"switch-margin", o.switchMargin},
            {"switch-refill", o.switchRefill},
            {"no-feedback", o.noFeedback},
            {"feedback-beta", o.beta},
            {"frames", o.frames},
            {"stride", o.stride},
            {"repeats", o.repeats}};
}

scheduler::SchedulerParameters schedulerParameters(const ScheduleOptions& options) {
    scheduler::SchedulerParameters parameters;
    parameters.budgetMs = options.budgetMs;
    if (!options.coefficients.empty()) parameters.coefficients = loadCoefficientsOrThrow(options.coefficients);
    parameters.organisation = parseOrganisation(options.organisation);
    parameters.switchControl.enabled = !options.noSwitchControl;
    if (!options.switchControl.empty()) parseSwitchControl(options.switchControl, parameters.switchControl);
    parameters.switchControl.rule = parseSwitchRule(options.switchRule);
    parameters.switchControl.raiseMargin = options.switchMargin;
    parameters.switchControl.refillBelow = options.switchRefill;
    parameters.feedback.beta = options.beta;
    return parameters;
}

evaluation::WalkOptions walkOptions(const ScheduleOptions& options) {
    evaluation::WalkOptions walk;
    walk.render = options.render;
    walk.fitness = !options.noFitness;
    walk.baseline = !options.noBaseline;
    walk.feedback = !options.noFeedback;
    walk.checkFeatures = options.checkFeatures;
    walk.repeats = options.repeats;
    return walk;
}

nlohmann::json ceilingJson(const evaluation::MeasurementCeiling& ceiling) {
    if (ceiling.probes.empty()) return nullptr;
    nlohmann::json probes = nlohmann::json::array();
    for (const evaluation::CeilingProbe& p : ceiling.probes) {
        probes.push_back({{"frame", p.frame},
                          {"measurements", p.measurements},
                          {"median_ms", p.medianMs},
                          {"p10_ratio", p.p10Ratio},
                          {"p90_ratio", p.p90Ratio},
                          {"ceiling", p.ceiling}});
    }
    return {{"tolerance", ceiling.tolerance}, {"ceiling", ceiling.ceiling}, {"probes", probes}};
}

// The frames of the path this run schedules (--stride, --frames).
std::vector<int> scheduledFrames(const ScheduleOptions& options, const scenes::CameraPath& path) {
    std::vector<int> frames;
    for (int f = 0; f < int(path.frames.size()); f += options.stride) {
        if (options.frames > 0 && int(frames.size()) >= options.frames) break;
        frames.push_back(f);
    }
    return frames;
}

// Walks `frames`, replaying the restored ones, checkpointing every --batch frames; an interrupt
// stops after a batch (Interrupted).
std::vector<evaluation::WalkFrame> walkFrames(evaluation::ScheduleWalk& walk, const ScheduleOptions& options,
                                              const OutputOptions& output, const scenes::CameraPath& path,
                                              const std::vector<int>& frames, const CheckpointFile& checkpoint,
                                              const nlohmann::json& identity,
                                              std::vector<evaluation::RecordedFrame> recorded) {
    std::vector<evaluation::WalkFrame> rows;
    rows.reserve(frames.size());
    const std::size_t total = frames.size();
    InterruptGuard interruptGuard;
    if (recorded.size() < total) pollInterrupt("schedule", recorded.size(), total, "frame", checkpoint.path());
    Progress progress("schedule", total - recorded.size(), output.quiet || output.json);
    for (std::size_t i = 0; i < total; ++i) {
        if (i < recorded.size()) {
            try {
                rows.push_back(walk.replay(frames[i], recorded[i]));
            } catch (const evaluation::ReplayMismatch& mismatch) {
                throw UsageError(checkpoint.path() + ": " + mismatch.what() +
                                 " (scene, path or profile changed?); delete it to start over");
            }
            continue;
        }
        rows.push_back(walk.walk(frames[i]));
        recorded.push_back(evaluation::record(rows.back()));
        progress.step(path.frames[std::size_t(frames[i])].name);
        const std::size_t done = i + 1;
        if (done % std::size_t(options.batch) == 0 || done == total) {
            checkpoint.save(identity, framesToCheckpoint(recorded));
            // After the last batch only the outputs are left: finish them rather than stop.
            try {
                if (done < total) pollInterrupt("schedule", done, total, "frame", checkpoint.path());
            } catch (const Interrupted&) {
                progress.finish();  // the message starts on a clean line
                throw;
            }
        }
    }
    progress.finish();
    return rows;
}

// What summary.json holds besides the run's settings.
struct ScheduleTotals {
    std::vector<double> decisionUs, predicted, measured, baselineMeasured, fitness, baselineFitness, error,
        featureError;
    int switches = 0, forced = 0, protectedFrames = 0, unreachable = 0, overPredicted = 0, dropped = 0;
};

ScheduleTotals totalsOf(const std::vector<evaluation::WalkFrame>& rows) {
    ScheduleTotals t;
    for (const evaluation::WalkFrame& r : rows) {
        t.decisionUs.push_back(r.decisionMicroseconds);
        t.predicted.push_back(r.predictedMs);
        if (!std::isnan(r.measuredMs)) {
            t.measured.push_back(r.measuredMs);
            t.error.push_back(std::abs(r.measuredMs - r.predictedMs) / r.measuredMs);
        }
        if (!std::isnan(r.baselineMeasuredMs)) t.baselineMeasured.push_back(r.baselineMeasuredMs);
        if (!std::isnan(r.exactPredictedMs) && r.exactPredictedMs > 0.0) {
            t.featureError.push_back(std::abs(r.predictedMs - r.exactPredictedMs) / r.exactPredictedMs);
        }
        if (!std::isnan(r.fitness)) t.fitness.push_back(r.fitness);
        if (!std::isnan(r.baselineFitness)) t.baselineFitness.push_back(r.baselineFitness);
        t.switches += r.decision.switches;
        t.forced += r.decision.forcedSwitches;
        if (r.decision.protectedLowered > 0) ++t.protectedFrames;
        if (!r.decision.budgetReachable) ++t.unreachable;
        if (!r.decision.budgetMet) ++t.overPredicted;
        t.dropped += r.decision.droppedObjects;
    }
    return t;
}

bool reachable(const evaluation::WalkFrame& r) { return r.decision.budgetReachable; }
// Binding: even the finest visible frame is predicted over the budget, so meeting it is the
// scheduler's doing, not the scene's.
bool bindsBudget(const evaluation::WalkFrame& r, double budget) {
    return r.decision.budgetReachable && r.finestPredictedMs > budget;
}
double measuredOf(const evaluation::WalkFrame& r) { return r.measuredMs; }
double baselineOf(const evaluation::WalkFrame& r) { return r.baselineMeasuredMs; }

// Everything a run reports, for summary.json and the text summary.
struct ScheduleRun {
    const ScheduleOptions& options;
    const scenes::Scene& scene;
    const scenes::CameraPath& path;
    const renderer::RenderSettings& settings;
    const scheduler::SchedulerParameters& parameters;
    scheduler::FeatureMode mode;
    std::string timeModel;
    int objects = 0;
    double setupSeconds = 0.0;
    double finalFeedbackScale = 1.0;
    std::vector<evaluation::WalkFrame> rows;
    evaluation::MeasurementCeiling ceiling;
    std::string frameClock;  // with --render: renderer::frameClockName of the timed frames
};

nlohmann::json summaryJson(const ScheduleRun& run, const ScheduleTotals& t) {
    const ScheduleOptions& options = run.options;
    const std::vector<evaluation::WalkFrame>& rows = run.rows;
    const double budget = options.budgetMs;
    auto binding = [&](const evaluation::WalkFrame& r) { return bindsBudget(r, budget); };
    nlohmann::json summary = {
        {"scene", run.scene.name},
        {"path", run.path.name},
        {"frames", rows.size()},
        {"frames_per_second", run.path.framesPerSecond},
        {"budget_ms", budget},
        {"size", std::to_string(run.settings.width) + "x" + std::to_string(run.settings.height)},
        {"shading", options.shading},
        {"organisation", scheduler::toString(run.parameters.organisation)},
        {"features", scheduler::toString(run.mode)},
        {"switch_control", run.parameters.switchControl.enabled},
        {"switch_rule", scheduler::toString(run.parameters.switchControl.rule)},
        {"switch_margin", run.parameters.switchControl.raiseMargin},
        {"switch_refill", run.parameters.switchControl.refillBelow},
        {"feedback", options.render && !options.noFeedback},
        {"feedback_beta", options.render && !options.noFeedback ? nlohmann::json(options.beta) : nlohmann::json(nullptr)},
        {"frame_time", options.render ? nlohmann::json{{"statistic", "median"},
                                                       {"clock", run.frameClock},
                                                       {"draws", options.repeats}}
                                      : nlohmann::json(nullptr)},
        {"coefficients", options.coefficients.empty() ? "published defaults" : options.coefficients},
        {"time_model", run.timeModel},
        {"objects", run.objects},
        {"setup_seconds", run.setupSeconds},
        {"decision_us", spreadJson(spreadOf(t.decisionUs))},
        {"predicted_ms", spreadJson(spreadOf(t.predicted))},
        {"frames_budget_unreachable", t.unreachable},
        {"frames_predicted_over_budget", t.overPredicted},
        {"frames_protected_lowered", t.protectedFrames},
        {"switches",
         {{"total", t.switches},
          {"per_frame", rows.empty() ? 0.0 : double(t.switches) / rows.size()},
          {"forced", t.forced}}},
        {"dropped_objects_per_frame", rows.empty() ? 0.0 : double(t.dropped) / rows.size()},
        {"final_feedback_scale", run.finalFeedbackScale},
    };
    if (options.checkFeatures) summary["bounds_vs_exact_prediction_error"] = spreadJson(spreadOf(t.featureError));
    if (!options.render) return summary;
    summary["measured_ms"] = spreadJson(spreadOf(t.measured));
    summary["prediction_error"] = spreadJson(spreadOf(t.error));
    summary["measured_vs_budget"] = {{"reachable", sharesJson(budgetShares(rows, budget, measuredOf, reachable))},
                                     {"binding", sharesJson(budgetShares(rows, budget, measuredOf, binding))}};
    if (!options.noBaseline) {
        summary["baseline_measured_ms"] = spreadJson(spreadOf(t.baselineMeasured));
        summary["baseline_vs_budget"] = {{"reachable", sharesJson(budgetShares(rows, budget, baselineOf, reachable))},
                                         {"binding", sharesJson(budgetShares(rows, budget, baselineOf, binding))}};
    }
    const nlohmann::json ceiling = ceilingJson(run.ceiling);
    if (!ceiling.is_null()) summary["measurement_ceiling"] = ceiling;
    // Goal 1 as docs/scheduler.md states it: the binding frames' share in the band over what the
    // machine's clock allows (the ceiling); null when either is missing.
    const BudgetShares bound = budgetShares(rows, budget, measuredOf, binding);
    const bool judged = bound.frames > 0 && !std::isnan(run.ceiling.ceiling) && run.ceiling.ceiling > 0.0;
    summary["goal_1"] = {{"binding_frames", bound.frames},
                         {"within_10_percent", bound.frames > 0 ? nlohmann::json(bound.within10) : nlohmann::json(nullptr)},
                         {"ceiling", std::isnan(run.ceiling.ceiling) ? nlohmann::json(nullptr)
                                                                     : nlohmann::json(run.ceiling.ceiling)},
                         {"of_ceiling", judged ? nlohmann::json(bound.within10 / run.ceiling.ceiling)
                                               : nlohmann::json(nullptr)}};
    if (!options.noFitness) {
        summary["fitness"] = spreadJson(spreadOf(t.fitness));
        if (!options.noBaseline) summary["baseline_fitness"] = spreadJson(spreadOf(t.baselineFitness));
    }
    return summary;
}

void printSummary(const ScheduleRun& run, const ScheduleTotals& t, const std::filesystem::path& dir) {
    const ScheduleOptions& options = run.options;
    const std::vector<evaluation::WalkFrame>& rows = run.rows;
    const double budget = options.budgetMs;
    const Spread d = spreadOf(t.decisionUs);
    std::cout << run.scene.name << " / " << run.path.name << ": " << rows.size() << " frames, budget " << budget
              << " ms, " << scheduler::toString(run.parameters.organisation) << ", switch control "
              << (run.parameters.switchControl.enabled ? "on" : "off") << "\n"
              << std::fixed << std::setprecision(1) << "  decision " << d.median << " us median, " << d.max
              << " us max; predicted " << spreadOf(t.predicted).mean << " ms mean; " << t.switches << " switches ("
              << (rows.empty() ? 0.0 : double(t.switches) / rows.size()) << " per frame)\n";
    if (options.render) {
        const BudgetShares s = budgetShares(rows, budget, measuredOf, reachable);
        std::cout << "  measured " << spreadOf(t.measured).mean << " ms mean; within ±10% of the budget on "
                  << std::setprecision(0) << 100.0 * s.within10 << "% of " << s.frames
                  << " reachable frames, <= 110% on " << 100.0 * s.atMost110 << "%";
        if (!options.noBaseline) {
            const BudgetShares b = budgetShares(rows, budget, baselineOf, reachable);
            std::cout << " (unscheduled: " << 100.0 * b.within10 << "%, " << 100.0 * b.atMost110 << "%)";
        }
        std::cout << "\n";
        if (!std::isnan(run.ceiling.ceiling)) {
            std::cout << "  measurement ceiling " << 100.0 * run.ceiling.ceiling << "%: one frame timed "
                      << options.noiseProbe << " times fits a ±10% band at best that often (frames";
            for (const evaluation::CeilingProbe& p : run.ceiling.probes) std::cout << ' ' << p.frame;
            std::cout << ")\n";
            const BudgetShares bound =
                budgetShares(rows, budget, measuredOf, [&](const evaluation::WalkFrame& r) { return bindsBudget(r, budget); });
            if (bound.frames > 0 && run.ceiling.ceiling > 0.0) {
                std::cout << "  goal 1: " << 100.0 * bound.within10 << "% of " << bound.frames
                          << " binding frames within ±10%, " << std::setprecision(2)
                          << bound.within10 / run.ceiling.ceiling << " of the ceiling (goal >= 0.9)\n"
                          << std::setprecision(0);
            }
        }
        if (!options.noFitness) {
            std::cout << std::setprecision(4) << "  fitness " << spreadOf(t.fitness).mean << " mean";
            if (!options.noBaseline) std::cout << " (unscheduled " << spreadOf(t.baselineFitness).mean << ")";
            std::cout << "\n";
        }
    }
    std::cout << "  wrote " << (dir / "frames.csv").string() << " and summary.json\n";
    std::cout.unsetf(std::ios::floatfield);
}

void runSchedule(const ScheduleOptions& options, const OutputOptions& output) {
    renderer::RenderSettings settings;
    parseSize(options.size, settings.width, settings.height);
    settings.shading = renderer::parseShading(options.shading);
    options.backend.applyTo(settings);
    const scenes::Scene scene = scenes::loadScene(options.scene, options.sceneSeed);
    if (scene.objects.empty()) throw UsageError("scene '" + scene.name + "' has no objects");
    const scenes::CameraPath path =
        options.path.empty() ? defaultCameraPath(scene) : loadCameraPath(scene, options.path);
    const std::vector<int> frames = scheduledFrames(options, path);

    std::unique_ptr<renderer::Renderer> renderer;
    if (options.render) renderer = std::make_unique<renderer::Renderer>(scene, settings);
    const TimeEstimator estimator = loadTimeEstimator(options.profile, options.model, scene.name, settings,
                                                      renderer.get(), std::cerr);
    const scheduler::SchedulerParameters parameters = schedulerParameters(options);
    const scheduler::FeatureMode mode = parseFeatureMode(options.features);

    const std::filesystem::path dir(options.outDir);
    const CheckpointFile checkpoint((dir / "schedule.checkpoint.json").string(), "schedule", "frames");
    const nlohmann::json identity = checkpointIdentity(options, parameters);
    std::vector<evaluation::RecordedFrame> restored;
    checkpoint.restore(options.resume, output.quiet || output.json, identity,
                       [&](const nlohmann::json& saved) { restored = framesFromCheckpoint(saved); });
    if (restored.size() > frames.size()) {
        throw UsageError(checkpoint.path() + ": holds more frames than this run has; delete it to start over");
    }

    const auto setupStart = std::chrono::steady_clock::now();
    const scheduler::SceneIndex index(scene, settings.width, settings.height, mode, 0, estimator.model->readFeatures());
    scheduler::FrameScheduler frameScheduler(index, estimator.model->clone(), parameters);
    ScheduleRun run{options, scene, path, settings, parameters, mode, estimator.name, index.objectCount(), 0.0, 1.0, {}, {}, {}};
    run.setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();
    if (renderer) run.frameClock = renderer::frameClockName(renderer->frameClock());

    const evaluation::WalkOptions walking = walkOptions(options);
    evaluation::ScheduleWalk walk(scene, path, frameScheduler, renderer.get(), walking);
    run.rows = walkFrames(walk, options, output, path, frames, checkpoint, identity, std::move(restored));
    run.finalFeedbackScale = frameScheduler.model().feedbackScale();
    if (renderer && options.noiseProbe > 0) {
        run.ceiling = evaluation::probeMeasurementCeiling(*renderer, path, run.rows, options.noiseProbe,
                                                          walking.repeats);
    }

    const ScheduleTotals totals = totalsOf(run.rows);
    nlohmann::json summary = summaryJson(run, totals);
    scenes::writeTextAtomically((dir / "frames.csv").string(), framesCsv(run.rows, index.maxLevelCount()));
    writeJsonFile((dir / "summary.json").string(), summary);
    checkpoint.remove();  // every frame is now in the outputs
    summary["out"] = options.outDir;
    if (output.json) {
        printJson(summary);
        return;
    }
    printSummary(run, totals, dir);
}

}  // namespace

void addScheduleCommand(CLI::App& app) {
    auto options = std::make_shared<ScheduleOptions>();
    auto output = std::make_shared<OutputOptions>();
    CLI::App* command = app.add_subcommand("schedule", "Real-time LOD scheduling along a camera path");
    addSceneOption(*command, options->scene);
    addSceneSeedOption(*command, options->sceneSeed);
    command->add_option("--path", options->path,
                        "Camera path: a name in the scene or a JSON file (default: the scene's first)");
    command->add_option("--budget-ms", options->budgetMs, "Frame-time budget in milliseconds")
        ->required()
        ->check(CLI::PositiveNumber);
    command->add_option("--coeffs", options->coefficients, "Coefficients from 'lodopt tune' (default: published)");
    command->add_flag("--render", options->render, "Render, time and score every frame; feed the time back");
    command->add_flag("--no-fitness", options->noFitness, "With --render: skip the fitness against the reference");
    command->add_flag("--no-baseline", options->noBaseline, "With --render: skip the unscheduled baseline");
    command->add_flag("--check-features", options->checkFeatures,
                      "Also predict each decision from exact features (exact_predicted_ms; slow)");
    addSizeOption(*command, options->size, "Render size WIDTHxHEIGHT (as calibrated)");
    addShadingOption(*command, options->shading);
    addBackendOptions(*command, options->backend);
    addProfileOptions(*command, options->profile, options->model);
    command->add_option("--organisation", options->organisation, "flat (DONG15) or tiles (CITY17 quadtree)")
        ->check(CLI::IsMember({"flat", "tiles"}))
        ->capture_default_str();
    command->add_option("--features", options->features, "Per-frame features: bounds (fast) or exact")
        ->check(CLI::IsMember({"bounds", "exact"}))
        ->capture_default_str();
    command->add_flag("--no-switch-control", options->noSwitchControl, "Switch levels freely (no hysteresis)");
    command->add_option("--switch-control", options->switchControl,
                        "VMI20 switch control D1,K1,D2,K2,NEAR (default 1,0.5,0.2,1,0)");
    command
        ->add_option("--switch-rule", options->switchRule,
                     "hysteresis (switches cost in the decision) or vmi20 (dwell time by distance, VMI20)")
        ->check(CLI::IsMember({"hysteresis", "vmi20"}))
        ->capture_default_str();
    command
        ->add_option("--switch-margin", options->switchMargin,
                     "Hysteresis: a raise that switches an object only within (1 - M) of the budget")
        ->check(CLI::Range(0.0, 0.99))
        ->capture_default_str();
    command
        ->add_option("--switch-refill", options->switchRefill,
                     "Hysteresis: a frame predicted under (1 - R) of the budget after the margin may switch into "
                     "the whole budget (0: never)")
        ->check(CLI::Range(0.0, 0.99))
        ->capture_default_str();
    command->add_flag("--no-feedback", options->noFeedback, "With --render: do not correct the model");
    command->add_option("--feedback-beta", options->beta, "Feedback gain beta, DONG15 eq. 9")
        ->check(CLI::Range(1e-6, 0.999999))
        ->capture_default_str();
    command->add_option("--frames", options->frames, "Schedule only the first N frames (0 = all)")
        ->check(CLI::Range(0, 10000000));
    command->add_option("--stride", options->stride, "Take every K-th frame of the path")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    command->add_option("--repeats", options->repeats, "With --render: timed draws per frame")
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    command
        ->add_option("--noise-probe", options->noiseProbe,
                     "With --render: after the path, time the first, middle and last frames this often each to report "
                     "the measurement ceiling (0: skip)")
        ->check(CLI::Range(0, 10000))
        ->capture_default_str();
    command->add_option("--batch", options->batch, "Frames per checkpoint (the unit an interrupt waits for)")
        ->check(CLI::Range(1, 1000000))
        ->capture_default_str();
    addResumeFlag(*command, options->resume, "the frames in OUT/schedule.checkpoint.json");
    command->add_option("--out", options->outDir, "Output folder (frames.csv, summary.json)")->capture_default_str();
    addOutputOptions(*command, *output);
    command->callback([options, output] { runSchedule(*options, *output); });
}

}  // namespace lodopt::cli
