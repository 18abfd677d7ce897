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

#include "cli_common.hpp"
#include "interrupt.hpp"
#include "metrics/metrics.hpp"
#include "progress.hpp"
#include "renderer/renderer.hpp"
#include "scenes/atomic_file.hpp"
#include "scenes/builtin.hpp"
#include "schedule_checkpoint.hpp"
#include "schedule_common.hpp"
#include "schedule_rows.hpp"
#include "scheduler/coefficients.hpp"
#include "scheduler/measurement.hpp"
#include "scheduler/scheduler.hpp"
#include "time_profile.hpp"
#include "timemodel/features.hpp"

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
    double beta = 0.3;
    int frames = 0;
    int stride = 1;
    // A frame's measured time: the least of 5 timed draws, what the calibration's default clock
    // (wall-min-median) fits. The median of 3 moved by more than 10% between repeated
    // measurements of one frame a third of the time on an idle machine (docs/scheduler.md).
    int repeats = 5;
    std::string frameTime = "min";
    // After the path, the first, middle and last frames' decisions are each timed this often back to
    // back: how far one frame's measurement scatters here bounds what any scheduler can put
    // within ±10% of the budget (scheduler/measurement.hpp). Not part of a frame's row.
    int noiseProbe = 20;
    int batch = 25;
    bool resume = false;
    std::string outDir = "out/schedule";
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
            {"repeats", o.repeats},
            {"frame-time", o.frameTime}};
}

// Fused fitness of `frame` against `reference` (both RGBA renders of one size).
double fitnessOf(const renderer::Frame& frame, const renderer::Frame& reference, const metrics::MetricParameters& p) {
    const metrics::ImageView candidate = metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4);
    const metrics::ImageView truth =
        metrics::makeImageView(reference.rgba.data(), reference.width, reference.height, 4);
    return metrics::evaluate(candidate, truth, p).fitness;
}

// The measurement ceiling (scheduler/measurement.hpp): the first, middle and last rows'
// decisions, each timed `measurements` times back to back as a frame is timed.
struct MeasurementCeiling {
    nlohmann::json json;  // null when nothing was probed
    double mean = NAN;    // of the probes' ceilings
    std::vector<int> frames;
};

MeasurementCeiling probeMeasurementCeiling(renderer::Renderer& renderer, const scenes::CameraPath& path,
                                           const std::vector<FrameRow>& rows, int measurements, int repeats,
                                           renderer::Renderer::Statistic statistic) {
    MeasurementCeiling result;
    if (rows.empty() || measurements <= 0) return result;
    std::vector<std::size_t> probed = {0};
    if (rows.size() > 2) probed.push_back(rows.size() / 2);
    if (rows.size() > 1) probed.push_back(rows.size() - 1);
    nlohmann::json probes = nlohmann::json::array();
    double sum = 0.0;
    for (std::size_t r : probed) {
        const scenes::Camera& camera = path.frames[std::size_t(rows[r].frame)];
        std::vector<double> times;
        for (int k = 0; k < measurements; ++k) {
            times.push_back(renderer.timeRender(rows[r].decision.levels, camera, repeats, 1, statistic));
        }
        const double ceiling = scheduler::bandCeiling(times, 0.1);
        std::vector<double> sorted = times;
        std::sort(sorted.begin(), sorted.end());
        const double median = spreadOf(times).median;
        auto ratioAt = [&](double q) { return sorted[std::size_t(q * double(sorted.size() - 1) + 0.5)] / median; };
        probes.push_back({{"frame", rows[r].frame},
                          {"measurements", times.size()},
                          {"median_ms", median},
                          {"p10_ratio", ratioAt(0.1)},
                          {"p90_ratio", ratioAt(0.9)},
                          {"ceiling", ceiling}});
        sum += ceiling;
        result.frames.push_back(rows[r].frame);
    }
    result.mean = sum / double(probed.size());
    result.json = {{"tolerance", 0.1}, {"ceiling", result.mean}, {"probes", probes}};
    return result;
}

void runSchedule(const ScheduleOptions& options, const OutputOptions& output) {
    renderer::RenderSettings settings;
    parseSize(options.size, settings.width, settings.height);
    settings.shading = renderer::parseShading(options.shading);
    const scenes::Scene scene = scenes::loadScene(options.scene, options.sceneSeed);
    if (scene.objects.empty()) throw UsageError("scene '" + scene.name + "' has no objects");
    scenes::CameraPath path = options.path.empty() ? defaultCameraPath(scene) : loadCameraPath(scene, options.path);
    std::vector<int> frameIndices;
    for (int f = 0; f < int(path.frames.size()); f += options.stride) {
        if (options.frames > 0 && int(frameIndices.size()) >= options.frames) break;
        frameIndices.push_back(f);
    }

    std::unique_ptr<renderer::Renderer> renderer;
    std::string glRenderer;
    const renderer::Renderer::Statistic statistic =
        options.frameTime == "min" ? renderer::Renderer::Statistic::Min : renderer::Renderer::Statistic::Median;
    if (options.render) {
        renderer = std::make_unique<renderer::Renderer>(scene, settings);
        glRenderer = renderer->glRendererString();
    }
    const TimeEstimator estimator =
        loadTimeEstimator(options.profile, options.model, scene.name, settings, glRenderer, std::cerr);

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
    const scheduler::FeatureMode mode = parseFeatureMode(options.features);

    const std::filesystem::path dir(options.outDir);
    const std::string checkpoint = (dir / "schedule.checkpoint.json").string();
    const nlohmann::json identity = checkpointIdentity(options, parameters);
    std::vector<SavedFrame> restored;
    if (std::filesystem::exists(checkpoint)) {
        if (!options.resume) {
            throw UsageError(checkpoint +
                             " holds the frames of an interrupted schedule: add --resume to continue "
                             "it, or delete the file to start over");
        }
        restored = loadScheduleCheckpoint(checkpoint, identity);
    } else if (options.resume && !output.quiet && !output.json) {
        std::cerr << "lodopt: schedule: no checkpoint in " << dir.string() << ", starting from the first frame\n";
    }

    const auto setupStart = std::chrono::steady_clock::now();
    const scheduler::SceneIndex index(scene, settings.width, settings.height, mode, 0, estimator.model->readFeatures());
    scheduler::FrameScheduler frameScheduler(index, estimator.model->clone(), parameters);
    const double setupSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - setupStart).count();

    metrics::MetricParameters metricParameters;
    const scenes::Combination reference = scenes::referenceCombination(scene);
    renderer::Frame referenceFrame, frame;
    scenes::Combination finest, baseline;
    std::vector<FrameRow> rows;
    rows.reserve(frameIndices.size());
    std::vector<SavedFrame> savedFrames = std::move(restored);
    if (savedFrames.size() > frameIndices.size()) {
        throw UsageError(checkpoint + ": holds more frames than this run has; delete it to start over");
    }
    const std::size_t total = frameIndices.size();
    InterruptGuard interruptGuard;
    if (savedFrames.size() < total) pollInterrupt("schedule", savedFrames.size(), total, "frame", checkpoint);
    Progress progress("schedule", total - savedFrames.size(), output.quiet || output.json);
    const int maxLevels = index.maxLevelCount();
    for (std::size_t i = 0; i < total; ++i) {
        const int f = frameIndices[i];
        const scenes::Camera& camera = path.frames[std::size_t(f)];
        const SavedFrame* saved = i < savedFrames.size() ? &savedFrames[i] : nullptr;
        FrameRow row;
        row.frame = f;
        row.timeSeconds = double(f) / double(path.framesPerSecond);
        const auto start = std::chrono::steady_clock::now();
        const scheduler::FrameDecision& decision = frameScheduler.decide(camera, row.timeSeconds);
        row.decisionMicroseconds =
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
        row.decision = decision;
        row.predictedMs = decision.predictedMs;
        finestVisible(frameScheduler, finest);
        row.finestPredictedMs = predictInLastFrame(frameScheduler, finest);
        // The unscheduled baseline: the distance thresholds' levels of the visible objects.
        baseline = frameScheduler.initialLevels();
        row.baselinePredictedMs = predictInLastFrame(frameScheduler, baseline);
        row.histogram.assign(std::size_t(maxLevels), 0);
        for (int level : decision.levels) {
            if (level != scenes::kNotDrawn) ++row.histogram[std::size_t(level)];
        }
        if (saved) {
            // A replayed frame: the decision above restores the switch-control state; what was
            // measured comes from the checkpoint, and its feedback restores the model's.
            if (saved->frame != f || saved->predictedMs != row.predictedMs ||
                saved->levelsHash != levelsHash(decision.levels)) {
                throw UsageError(checkpoint + ": frame " + std::to_string(f) +
                                 " does not replay to the saved decision (scene, path or profile changed?); "
                                 "delete it to start over");
            }
            row.decisionMicroseconds = saved->decisionMicroseconds;
            row.exactPredictedMs = saved->exactPredictedMs;
            row.measuredMs = saved->measuredMs;
            row.baselineMeasuredMs = saved->baselineMeasuredMs;
            row.fitness = saved->fitness;
            row.baselineFitness = saved->baselineFitness;
            if (renderer && !options.noFeedback) frameScheduler.reportMeasuredMs(row.measuredMs);
            row.feedbackScale = frameScheduler.model().feedbackScale();
            if (row.feedbackScale != saved->feedbackScale) {
                throw UsageError(checkpoint + ": frame " + std::to_string(f) +
                                 " replays to another feedback scale; delete it to start over");
            }
            rows.push_back(std::move(row));
            continue;
        }
        if (options.checkFeatures) {
            // The same levels with the time model's exact features (walks the geometry).
            const timemodel::FeatureTable table(scene, camera, settings.width, settings.height);
            row.exactPredictedMs = frameScheduler.model().estimateMs(table.features(decision.levels));
        }
        if (renderer) {
            if (!options.noFitness) {
                renderer->render(reference, camera, referenceFrame);
                renderer->render(row.decision.levels, camera, frame);
                row.fitness = fitnessOf(frame, referenceFrame, metricParameters);
                if (!options.noBaseline) {
                    renderer->render(baseline, camera, frame);
                    row.baselineFitness = fitnessOf(frame, referenceFrame, metricParameters);
                }
            }
            row.measuredMs = renderer->timeRender(row.decision.levels, camera, options.repeats, 1, statistic);
            if (!options.noBaseline)
                row.baselineMeasuredMs = renderer->timeRender(baseline, camera, options.repeats, 1, statistic);
            if (!options.noFeedback) frameScheduler.reportMeasuredMs(row.measuredMs);
        }
        row.feedbackScale = frameScheduler.model().feedbackScale();
        savedFrames.push_back({f, row.decisionMicroseconds, row.measuredMs, row.baselineMeasuredMs, row.fitness,
                               row.baselineFitness, row.exactPredictedMs, row.predictedMs, row.feedbackScale,
                               levelsHash(decision.levels)});
        rows.push_back(std::move(row));
        progress.step(camera.name);
        const std::size_t done = i + 1;
        if (done % std::size_t(options.batch) == 0 || done == total) {
            saveScheduleCheckpoint(checkpoint, identity, savedFrames);
            // After the last batch only the outputs are left: finish them rather than stop.
            try {
                if (done < total) pollInterrupt("schedule", done, total, "frame", checkpoint);
            } catch (const Interrupted&) {
                progress.finish();  // the message starts on a clean line
                throw;
            }
        }
    }
    progress.finish();

    // The measurement ceiling: the first, middle and last frames' decisions, timed again and again.
    const MeasurementCeiling ceiling =
        renderer && options.noiseProbe > 0
            ? probeMeasurementCeiling(*renderer, path, rows, options.noiseProbe, options.repeats, statistic)
            : MeasurementCeiling{};

    // Summary.
    std::vector<double> decisionUs, predicted, measured, baselineMeasured, fitness, baselineFitness, error,
        featureError;
    int switches = 0, forced = 0, protectedFrames = 0, unreachable = 0, overPredicted = 0, dropped = 0;
    for (const FrameRow& r : rows) {
        decisionUs.push_back(r.decisionMicroseconds);
        predicted.push_back(r.predictedMs);
        if (!std::isnan(r.measuredMs)) {
            measured.push_back(r.measuredMs);
            error.push_back(std::abs(r.measuredMs - r.predictedMs) / r.measuredMs);
        }
        if (!std::isnan(r.baselineMeasuredMs)) baselineMeasured.push_back(r.baselineMeasuredMs);
        if (!std::isnan(r.exactPredictedMs) && r.exactPredictedMs > 0.0) {
            featureError.push_back(std::abs(r.predictedMs - r.exactPredictedMs) / r.exactPredictedMs);
        }
        if (!std::isnan(r.fitness)) fitness.push_back(r.fitness);
        if (!std::isnan(r.baselineFitness)) baselineFitness.push_back(r.baselineFitness);
        switches += r.decision.switches;
        forced += r.decision.forcedSwitches;
        if (r.decision.protectedLowered > 0) ++protectedFrames;
        if (!r.decision.budgetReachable) ++unreachable;
        if (!r.decision.budgetMet) ++overPredicted;
        dropped += r.decision.droppedObjects;
    }
    const double budget = options.budgetMs;
    auto reachable = [](const FrameRow& r) { return r.decision.budgetReachable; };
    // Binding: even the finest visible frame is predicted over the budget, so meeting it is
    // the scheduler's doing, not the scene's.
    auto binding = [&](const FrameRow& r) { return r.decision.budgetReachable && r.finestPredictedMs > budget; };
    auto measuredOf = [](const FrameRow& r) { return r.measuredMs; };
    auto baselineOf = [](const FrameRow& r) { return r.baselineMeasuredMs; };
    nlohmann::json summary = {
        {"scene", scene.name},
        {"path", path.name},
        {"frames", rows.size()},
        {"frames_per_second", path.framesPerSecond},
        {"budget_ms", budget},
        {"size", std::to_string(settings.width) + "x" + std::to_string(settings.height)},
        {"shading", options.shading},
        {"organisation", scheduler::toString(parameters.organisation)},
        {"features", scheduler::toString(mode)},
        {"switch_control", parameters.switchControl.enabled},
        {"switch_rule", scheduler::toString(parameters.switchControl.rule)},
        {"switch_margin", parameters.switchControl.raiseMargin},
        {"switch_refill", parameters.switchControl.refillBelow},
        {"feedback", options.render && !options.noFeedback},
        {"frame_time", options.render ? nlohmann::json{{"statistic", options.frameTime}, {"draws", options.repeats}}
                                      : nlohmann::json(nullptr)},
        {"coefficients", options.coefficients.empty() ? "published defaults" : options.coefficients},
        {"time_model", estimator.name},
        {"objects", index.objectCount()},
        {"setup_seconds", setupSeconds},
        {"decision_us", spreadJson(spreadOf(decisionUs))},
        {"predicted_ms", spreadJson(spreadOf(predicted))},
        {"frames_budget_unreachable", unreachable},
        {"frames_predicted_over_budget", overPredicted},
        {"frames_protected_lowered", protectedFrames},
        {"switches",
         {{"total", switches}, {"per_frame", rows.empty() ? 0.0 : double(switches) / rows.size()}, {"forced", forced}}},
        {"dropped_objects_per_frame", rows.empty() ? 0.0 : double(dropped) / rows.size()},
        {"final_feedback_scale", frameScheduler.model().feedbackScale()},
    };
    if (options.checkFeatures) summary["bounds_vs_exact_prediction_error"] = spreadJson(spreadOf(featureError));
    if (options.render) {
        summary["measured_ms"] = spreadJson(spreadOf(measured));
        summary["prediction_error"] = spreadJson(spreadOf(error));
        summary["measured_vs_budget"] = {{"reachable", sharesJson(budgetShares(rows, budget, measuredOf, reachable))},
                                         {"binding", sharesJson(budgetShares(rows, budget, measuredOf, binding))}};
        if (!options.noBaseline) {
            summary["baseline_measured_ms"] = spreadJson(spreadOf(baselineMeasured));
            summary["baseline_vs_budget"] = {
                {"reachable", sharesJson(budgetShares(rows, budget, baselineOf, reachable))},
                {"binding", sharesJson(budgetShares(rows, budget, baselineOf, binding))}};
        }
        if (!ceiling.json.is_null()) summary["measurement_ceiling"] = ceiling.json;
        if (!options.noFitness) {
            summary["fitness"] = spreadJson(spreadOf(fitness));
            if (!options.noBaseline) summary["baseline_fitness"] = spreadJson(spreadOf(baselineFitness));
        }
    }
    scenes::writeTextAtomically((dir / "frames.csv").string(), framesCsv(rows, maxLevels));
    writeJsonFile((dir / "summary.json").string(), summary);
    std::filesystem::remove(checkpoint);  // every frame is now in the outputs
    summary["out"] = options.outDir;
    if (output.json) {
        printJson(summary);
        return;
    }
    const Spread d = spreadOf(decisionUs);
    std::cout << scene.name << " / " << path.name << ": " << rows.size() << " frames, budget " << budget << " ms, "
              << scheduler::toString(parameters.organisation) << ", switch control "
              << (parameters.switchControl.enabled ? "on" : "off") << "\n"
              << std::fixed << std::setprecision(1) << "  decision " << d.median << " us median, " << d.max
              << " us max; predicted " << spreadOf(predicted).mean << " ms mean; " << switches << " switches ("
              << (rows.empty() ? 0.0 : double(switches) / rows.size()) << " per frame)\n";
    if (options.render) {
        const BudgetShares s = budgetShares(rows, budget, measuredOf, reachable);
        std::cout << "  measured " << spreadOf(measured).mean << " ms mean; within ±10% of the budget on "
                  << std::setprecision(0) << 100.0 * s.within10 << "% of " << s.frames
                  << " reachable frames, <= 110% on " << 100.0 * s.atMost110 << "%";
        if (!options.noBaseline) {
            const BudgetShares b = budgetShares(rows, budget, baselineOf, reachable);
            std::cout << " (unscheduled: " << 100.0 * b.within10 << "%, " << 100.0 * b.atMost110 << "%)";
        }
        std::cout << "\n";
        if (!std::isnan(ceiling.mean)) {
            std::cout << "  measurement ceiling " << 100.0 * ceiling.mean << "%: one frame timed " << options.noiseProbe
                      << " times fits a ±10% band at best that often (frames";
            for (int f : ceiling.frames) std::cout << ' ' << f;
            std::cout << ")\n";
        }
        if (!options.noFitness) {
            std::cout << std::setprecision(4) << "  fitness " << spreadOf(fitness).mean << " mean";
            if (!options.noBaseline) std::cout << " (unscheduled " << spreadOf(baselineFitness).mean << ")";
            std::cout << "\n";
        }
    }
    std::cout << "  wrote " << (dir / "frames.csv").string() << " and summary.json\n";
    std::cout.unsetf(std::ios::floatfield);
}

}  // namespace

void addScheduleCommand(CLI::App& app) {
    auto options = std::make_shared<ScheduleOptions>();
    auto output = std::make_shared<OutputOptions>();
    CLI::App* command = app.add_subcommand("schedule", "Real-time LOD scheduling along a camera path");
    command->add_option("--scene", options->scene, "Built-in scene name or glTF/GLB path")->capture_default_str();
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
    command->add_option("--size", options->size, "Render size WIDTHxHEIGHT (as calibrated)")->capture_default_str();
    addShadingOption(*command, options->shading);
    command->add_option("--profile", options->profile, "Device profile from 'lodopt calibrate' (default: shipped)");
    command->add_option("--model", options->model, "Time model in the profile (default: the profile's default)");
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
    command->add_option("--frame-time", options->frameTime,
                        "With --render: a frame's measured time is the median or the least of its timed draws")
        ->check(CLI::IsMember({"median", "min"}))
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
    command->add_flag("--resume", options->resume,
                      "Continue from the frames saved in OUT/schedule.checkpoint.json by an interrupted schedule");
    command->add_option("--out", options->outDir, "Output folder (frames.csv, summary.json)")->capture_default_str();
    addOutputOptions(*command, *output);
    command->callback([options, output] { runSchedule(*options, *output); });
}

}  // namespace lodopt::cli
