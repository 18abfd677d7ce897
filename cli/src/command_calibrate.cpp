// lodopt calibrate: render sampled combinations from sampled viewpoints, time them robustly,
// fit every render-time model and write a device profile (method.md §4; timemodel/). The plan
// is timemodel::planCalibration's; the timing passes and the fits are
// evaluation::calibrateDevice's (evaluation/device_timing.hpp, which says how a noisy machine is
// timed); this file parses, reports progress, writes the profile and prints.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "evaluation/device_timing.hpp"
#include "progress.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "timemodel/calibration.hpp"
#include "timemodel/features.hpp"
#include "timemodel/profile.hpp"
#include "timemodel/timing.hpp"

namespace lodopt::cli {
namespace {

struct CalibrateOptions {
    std::string scene = scenes::kDefaultSceneName;
    std::string views;  // comma-separated names or indices; empty = all
    int samples = 240;
    std::uint64_t seed = 1;
    std::uint32_t sceneSeed = 1;
    std::string size = "512x512";
    std::string shading = renderer::shadingName(renderer::kDefaultShading);
    BackendOptions backend;
    int jitter = 3;
    int rounds = 6;
    int maxRounds = 25;
    double timeBudget = 110.0;
    int repeats = 3;
    int warmup = 1;
    std::string learnFrom = timemodel::kAutoStatistic;
    std::string refit;  // a profile to refit from its own samples, nothing timed
    std::string out = "device.json";
    OutputOptions output;
};

std::vector<int> parseViews(const scenes::Scene& scene, const std::string& text) {
    std::vector<int> views;
    if (text.empty()) return views;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        if (item.empty()) throw UsageError("--views: empty view name in '" + text + "'");
        views.push_back(scenes::findView(scene, item));
    }
    return views;
}

nlohmann::json errorsJson(const timemodel::ErrorStats& e) {
    return {{"count", e.count}, {"mean", e.mean}, {"median", e.median}, {"p90", e.p90}, {"max", e.max}};
}

nlohmann::json modelsJson(const std::vector<timemodel::ModelResult>& models) {
    nlohmann::json entries = nlohmann::json::array();
    for (const timemodel::ModelResult& r : models) {
        nlohmann::json entry = {{"name", r.name}, {"fitted", r.fitted}};
        if (!r.fitted) entry["failure"] = r.failure;
        nlohmann::json coefficients = nlohmann::json::object();
        for (std::size_t c = 0; c < r.coefficients.size(); ++c) coefficients[r.coefficientNames[c]] = r.coefficients[c];
        entry["coefficients"] = coefficients;
        entry["held_out_errors"] = errorsJson(r.heldOutErrors);
        entry["rotated_held_out_errors"] = errorsJson(r.rotatedErrors);
        entry["fit_errors"] = errorsJson(r.fitErrors);
        entry["notes"] = r.fit.notes;
        entries.push_back(entry);
    }
    return entries;
}

std::vector<std::string> calibrationWarnings(const evaluation::CalibrationResult& run) {
    std::vector<std::string> warnings;
    if (run.profile.timing.passDrift > timemodel::kPassDriftWarning) {
        warnings.push_back(timemodel::calibrationDriftWarning(run.profile.timing.passDrift));
    }
    return warnings;
}

nlohmann::json calibrationJson(const CalibrateOptions& options, const evaluation::CalibrationResult& run) {
    const timemodel::DeviceProfile& profile = run.profile;
    nlohmann::json choiceJson = {{"judged_on", "fitting samples, every fitting viewpoint held out once"},
                                 {"model", profile.defaultModel},
                                 {"measured", run.choice.measured}};
    for (const timemodel::LearnCandidate& candidate : run.choice.candidates) {
        choiceJson["candidates"][candidate.statistic] = {{"scale", candidate.scale},
                                                         {"errors", errorsJson(candidate.crossValidated)}};
    }
    nlohmann::json otherJson = nlohmann::json::object();
    for (const evaluation::OtherStatisticFit& other : run.otherStatistics) {
        nlohmann::json entries = nlohmann::json::array();
        for (const timemodel::ModelResult& r : other.models) {
            entries.push_back({{"name", r.name},
                               {"fitted", r.fitted},
                               {"held_out_errors", errorsJson(r.heldOutErrors)},
                               {"fit_errors", errorsJson(r.fitErrors)}});
        }
        otherJson[other.statistic] = {{"scale", other.scale},
                                      {"models", entries},
                                      {"split_half_median", other.repeatability.median},
                                      {"split_half_p90", other.repeatability.p90}};
    }
    const timemodel::TimingSettings& timing = profile.timing;
    return {{"out", options.out},
            {"scene", profile.scene},
            {"width", profile.width},
            {"height", profile.height},
            {"shading", options.shading},
            {"renderer", profile.glRenderer},
            {"cpu_model", profile.machine.cpuModel},
            {"cores", profile.machine.cores},
            {"samples", profile.samples.size()},
            {"fit_samples", run.fitSamples},
            {"held_out_samples", run.heldOutSamples},
            {"viewpoints", profile.viewpoints},
            {"held_out_viewpoints", profile.heldOutViewpoints},
            {"predicts", timing.predicts},
            {"frame_clock", timing.frameClock},
            {"learned_from", timing.learnedFrom},
            {"learned_scale", timing.learnedScale},
            {"learn_request", timing.learnRequest},
            {"learn_choice", choiceJson},
            {"timing_spread_median", run.spread.median},
            {"timing_spread_p90", run.spread.p90},
            {"split_half_median", run.repeatability.median},
            {"split_half_p90", run.repeatability.p90},
            {"pass_time_factors", run.passTimeFactors},
            {"pass_drift", timing.passDrift},
            {"anchor_view", timing.anchorView},
            {"anchor_ms", timing.anchorMs},
            {"warnings", calibrationWarnings(run)},
            {"seconds", timing.seconds},
            {"default_model", profile.defaultModel},
            {"models", modelsJson(profile.models)},
            {"other_statistics", otherJson}};
}

void printCalibration(const CalibrateOptions& options, const evaluation::CalibrationResult& run) {
    const timemodel::DeviceProfile& profile = run.profile;
    const timemodel::TimingSettings& timing = profile.timing;
    std::cout << "calibrated '" << profile.scene << "' at " << profile.width << "x" << profile.height << " on "
              << profile.machine.cpuModel << " (" << profile.machine.cores << " threads), " << profile.glRenderer
              << "\n";
    char line[512];
    std::snprintf(line, sizeof line,
                  "%zu samples: %zu fitted on %d viewpoints, %zu held out on %d viewpoints\n"
                  "timing: %s clock, %d passes x %d draws (+%d warm-up); spread of the median between passes: "
                  "median %.1f%%, p90 %.1f%%\n"
                  "repeatability: a held-out sample's median from the even passes against the odd ones differs by "
                  "median %.1f%%, p90 %.1f%%\n",
                  profile.samples.size(), run.fitSamples, profile.viewpoints - profile.heldOutViewpoints,
                  run.heldOutSamples, profile.heldOutViewpoints, timing.frameClock.c_str(), timing.rounds,
                  timing.repeatsPerRound, timing.warmup, 100.0 * run.spread.median, 100.0 * run.spread.p90,
                  100.0 * run.repeatability.median, 100.0 * run.repeatability.p90);
    std::cout << line;
    if (!run.passTimeFactors.empty()) {
        std::cout << "each pass's frame times against the run's:";
        for (double factor : run.passTimeFactors) {
            std::snprintf(line, sizeof line, " %.2f", factor);
            std::cout << line;
        }
        std::snprintf(line, sizeof line, " (drift %.1f%%)\n", 100.0 * timing.passDrift);
        std::cout << line;
    }
    if (timing.anchorMs > 0.0) {
        std::snprintf(line, sizeof line,
                      "speed anchor: view '%s' at the finest levels, %.3f ms (median over the passes; "
                      "estimate --speed-probe times it again)\n",
                      timing.anchorView.c_str(), timing.anchorMs);
        std::cout << line;
    }
    std::snprintf(line, sizeof line, "predicts: the median of a frame's draws; learned from %s x %.3f",
                  timing.learnedFrom.c_str(), timing.learnedScale);
    std::cout << line;
    if (options.learnFrom == timemodel::kAutoStatistic && !run.choice.measured) {
        std::cout << " (auto: one fitting viewpoint leaves nothing to judge)";
    } else if (options.learnFrom == timemodel::kAutoStatistic) {
        std::cout << " (auto: least error against the median, every fitting viewpoint held out once:";
        for (std::size_t c = 0; c < run.choice.candidates.size(); ++c) {
            std::snprintf(line, sizeof line, "%s %s %.1f%%", c ? "," : "", run.choice.candidates[c].statistic.c_str(),
                          100.0 * run.choice.candidates[c].crossValidated.mean);
            std::cout << line;
        }
        std::cout << ")";
    }
    std::cout << "\n";
    std::cout << timemodel::formatErrorTable(profile.models);
    std::snprintf(line, sizeof line, "every viewpoint held out once (%d folds, %zu samples):", run.folds,
                  profile.samples.size());
    std::cout << line;
    for (const timemodel::ModelResult& r : profile.models) {
        if (r.rotatedErrors.count == 0) continue;
        std::snprintf(line, sizeof line, "  %s mean %.1f%% p90 %.1f%%", r.name.c_str(), 100.0 * r.rotatedErrors.mean,
                      100.0 * r.rotatedErrors.p90);
        std::cout << line;
    }
    std::cout << "\n";
    for (const timemodel::ModelResult& r : profile.models) {
        for (const std::string& note : r.fit.notes) std::cout << "  note (" << r.name << "): " << note << "\n";
    }
    for (const evaluation::OtherStatisticFit& other : run.otherStatistics) {
        if (other.repeatability.count > 0) {
            std::snprintf(line, sizeof line, "same draws, learned from %s x %.3f (repeatability %.1f%% / %.1f%%):",
                          other.statistic.c_str(), other.scale, 100.0 * other.repeatability.median,
                          100.0 * other.repeatability.p90);
        } else {  // --refit: no passes to compare
            std::snprintf(line, sizeof line, "same draws, learned from %s x %.3f:", other.statistic.c_str(),
                          other.scale);
        }
        std::cout << line;
        for (const timemodel::ModelResult& r : other.models) {
            if (!r.fitted) continue;
            std::snprintf(line, sizeof line, "  %s mean %.1f%% p90 %.1f%%", r.name.c_str(),
                          100.0 * r.heldOutErrors.mean, 100.0 * r.heldOutErrors.p90);
            std::cout << line;
        }
        std::cout << "\n";
    }
    std::snprintf(line, sizeof line, "wrote %s (timing took %.1f s)\n", options.out.c_str(), timing.seconds);
    std::cout << line;
}

// --refit: the profile's samples fitted again to predict the median (timemodel::refitProfile).
void runRefit(const CalibrateOptions& options) {
    evaluation::CalibrationResult run;
    timemodel::ProfileFit fit;
    try {
        run.profile = timemodel::loadProfile(options.refit);
        fit = timemodel::refitProfile(run.profile, options.learnFrom);
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }
    run.choice = fit.choice;
    for (timemodel::StatisticFit& other : fit.others) {
        run.otherStatistics.push_back({other.statistic, other.scale, std::move(other.models), {}});
    }
    for (const timemodel::ProfileSample& s : run.profile.samples) (s.heldOut ? run.heldOutSamples : run.fitSamples)++;
    run.spread = {0, 0.0, run.profile.timing.medianSpread, run.profile.timing.p90Spread, 0.0};
    run.repeatability = {0, 0.0, run.profile.timing.splitHalfMedian, run.profile.timing.splitHalfP90, 0.0};
    const std::vector<int> folds = timemodel::profileFolds(run.profile);
    run.folds = folds.empty() ? 0 : *std::max_element(folds.begin(), folds.end()) + 1;
    timemodel::saveProfile(options.out, run.profile);
    if (options.output.json) {
        nlohmann::json report = calibrationJson(options, run);
        report["refit"] = options.refit;
        printJson(report);
        return;
    }
    std::cout << "refitted " << options.refit << " from its " << run.profile.samples.size()
              << " samples (nothing timed)\n";
    printCalibration(options, run);
}

void runCalibrate(const CalibrateOptions& options) {
    if (!options.refit.empty()) {
        runRefit(options);
        return;
    }
    evaluation::CalibrationSettings settings;  // its start: the time budget counts from here
    settings.rounds = options.rounds;
    settings.maxRounds = options.maxRounds;
    settings.timeBudgetSeconds = options.timeBudget;
    settings.repeats = options.repeats;
    settings.warmup = options.warmup;
    settings.learnFrom = options.learnFrom;
    settings.seed = options.seed;
    renderer::RenderSettings renderSettings;
    parseSize(options.size, renderSettings.width, renderSettings.height);
    renderSettings.shading = renderer::parseShading(options.shading);
    options.backend.applyTo(renderSettings);
    const scenes::Scene scene = scenes::loadScene(options.scene, options.sceneSeed);

    timemodel::CalibrationOptions planOptions;
    planOptions.samples = options.samples;
    planOptions.jitteredPerView = options.jitter;
    planOptions.views = parseViews(scene, options.views);
    planOptions.seed = options.seed;
    timemodel::CalibrationPlan plan;
    try {
        plan = timemodel::planCalibration(scene, planOptions);
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }

    renderer::Renderer renderer(scene, renderSettings);
    std::unique_ptr<Progress> progress;
    const bool quiet = options.output.quiet || options.output.json;
    auto onSample = [&](int pass, std::size_t done, std::size_t total) {
        if (done == 1) progress = std::make_unique<Progress>("calibrate pass " + std::to_string(pass + 1), total, quiet);
        progress->step();
        if (done == total) progress->finish();
    };
    evaluation::CalibrationResult run = evaluation::calibrateDevice(scene, renderer, plan, options.seed, settings, onSample);
    run.profile.sceneSeed = options.sceneSeed;
    timemodel::saveProfile(options.out, run.profile);
    for (const std::string& warning : calibrationWarnings(run)) std::cerr << "lodopt: warning: " << warning << "\n";
    if (options.output.json) {
        printJson(calibrationJson(options, run));
        return;
    }
    printCalibration(options, run);
}

std::vector<std::string> learnChoices() {
    std::vector<std::string> names = timemodel::timingStatisticNames();
    names.insert(names.begin(), timemodel::kAutoStatistic);
    return names;
}

}  // namespace

void addCalibrateCommand(CLI::App& app) {
    auto options = std::make_shared<CalibrateOptions>();
    CLI::App* command =
        app.add_subcommand("calibrate", "Time sampled frames, fit every render-time model, write a device profile");
    addSceneOption(*command, options->scene);
    command->add_option("--views", options->views, "Named views to calibrate from, comma-separated (default all)");
    command->add_option("--samples", options->samples, "Frames to time in all (>= 4)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    command->add_option("--seed", options->seed, "Seed of the sampled combinations and viewpoints")
        ->capture_default_str();
    addSceneSeedOption(*command, options->sceneSeed);
    addSizeOption(*command, options->size, "WIDTHxHEIGHT of the timed frames");
    addShadingOption(*command, options->shading);
    addBackendOptions(*command, options->backend);
    command->add_option("--jitter", options->jitter, "Extra viewpoints around each named view")
        ->capture_default_str()
        ->check(CLI::Range(0, 100));
    command->add_option("--rounds", options->rounds, "Least interleaved timing passes over all samples")
        ->capture_default_str()
        ->check(CLI::Range(1, 100));
    command->add_option("--max-rounds", options->maxRounds, "Most passes while within --time-budget")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    command
        ->add_option("--time-budget", options->timeBudget,
                     "Seconds after which no further pass starts (beyond --rounds)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 86400.0));
    command->add_option("--repeats", options->repeats, "Timed draws per sample per pass (median)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    command->add_option("--warmup", options->warmup, "Untimed draws before each timed batch")
        ->capture_default_str()
        ->check(CLI::Range(0, 100));
    command
        ->add_option("--learn-from", options->learnFrom,
                     "What the models are fitted on (they always predict the median of a frame's draws): auto (what "
                     "predicts the median best on the fitting viewpoints), median, least-median (median of each "
                     "pass's least), least, or cpu (process CPU time)")
        ->capture_default_str()
        ->check(CLI::IsMember(learnChoices()));
    command
        ->add_option("--refit", options->refit,
                     "Refit this profile's recorded samples (no frame is timed): a profile written before every "
                     "profile predicted the median of a frame's draws comes to predict it")
        ->check(CLI::ExistingFile);
    command->add_option("--out", options->out, "Device profile to write (JSON)")->capture_default_str();
    addOutputOptions(*command, options->output);
    command->callback([options] { runCalibrate(*options); });
}

}  // namespace lodopt::cli
