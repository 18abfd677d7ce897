// lodopt calibrate: render sampled combinations from sampled viewpoints, time them robustly,
// fit every render-time model and write a device profile (method.md §4; timemodel/).
//
// Timing on a shared, noisy machine: every sample is timed in interleaved passes (a fresh
// shuffled order per pass, so a burst of load from elsewhere spreads over many samples
// instead of ruining one): at least `rounds` passes, then more (up to `maxRounds`) while the
// command's wall time stays within `timeBudget` seconds, so a fast scene gets more draws per
// sample and a slow one still finishes. Each pass `warmup` untimed draws then `repeats` timed
// draws of draw + glFinish (renderer::Renderer::drawAndFinish), each on the steady clock and
// on the process CPU clock (all of llvmpipe's threads). The fitted time is the statistic that
// --clock names (timemodel::TimingSettings); all four are kept in the profile. The default,
// --clock auto, fits the wall clock whose split-half repeatability over the fitting samples
// was best in this run (timemodel/timing.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "progress.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "time_profile.hpp"
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
    int jitter = 3;
    int rounds = 6;
    int maxRounds = 25;
    double timeBudget = 110.0;
    int repeats = 3;
    int warmup = 1;
    std::string clock = timemodel::kAutoClock;
    std::string out = "device.json";
    OutputOptions output;
};

void timePass(renderer::Renderer& renderer, const scenes::Combination& combination, const scenes::Camera& camera,
              int repeats, int warmup, timemodel::PassTimes& out) {
    const DrawTimes times = timeDraws(renderer, combination, camera, repeats, warmup);
    out.leastWall.push_back(times.wallMin);
    out.medianWall.push_back(times.wallMedian);
    out.medianCpu.push_back(times.cpuMedian);
}

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

void runCalibrate(const CalibrateOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    renderer::RenderSettings settings;
    parseSize(options.size, settings.width, settings.height);
    settings.shading = renderer::parseShading(options.shading);
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

    std::vector<timemodel::FeatureTable> tables;
    tables.reserve(plan.viewpoints.size());
    for (const timemodel::Viewpoint& viewpoint : plan.viewpoints) {
        tables.emplace_back(scene, viewpoint.camera, settings.width, settings.height);
    }

    renderer::Renderer renderer(scene, settings);
    const std::size_t count = plan.samples.size();
    std::vector<timemodel::PassTimes> timings(count);
    timemodel::SplitMix64 shuffle(options.seed ^ 0xC0FFEEull);
    std::vector<std::size_t> order(count);
    for (std::size_t i = 0; i < count; ++i) order[i] = i;
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    int passes = 0;
    double slowestPass = 0.0;
    while (passes < options.rounds ||
           (passes < std::max(options.rounds, options.maxRounds) && elapsed() + slowestPass <= options.timeBudget)) {
        const double passStart = elapsed();
        Progress progress("calibrate pass " + std::to_string(passes + 1), count,
                          options.output.quiet || options.output.json);
        for (std::size_t i = count; i > 1; --i) std::swap(order[i - 1], order[std::size_t(shuffle.below(int(i)))]);
        for (std::size_t index : order) {
            const timemodel::PlannedSample& planned = plan.samples[index];
            timePass(renderer, planned.combination, plan.viewpoints[planned.viewpoint].camera, options.repeats,
                     options.warmup, timings[index]);
            progress.step();
        }
        progress.finish();
        slowestPass = std::max(slowestPass, elapsed() - passStart);
        ++passes;
    }

    std::vector<bool> heldOut(count);
    for (std::size_t i = 0; i < count; ++i) heldOut[i] = plan.viewpoints[plan.samples[i].viewpoint].heldOut;
    std::vector<bool> fitting = heldOut;
    fitting.flip();
    const bool autoClock = options.clock == timemodel::kAutoClock;
    const timemodel::ClockChoice choice = timemodel::chooseMostRepeatableClock(timings, fitting);
    const std::string clock = autoClock ? choice.clock : options.clock;

    timemodel::DeviceProfile profile;
    std::vector<timemodel::Sample> fitSamples, heldOutSamples;
    std::vector<double> spreads;
    for (std::size_t i = 0; i < count; ++i) {
        const timemodel::PlannedSample& planned = plan.samples[i];
        const timemodel::PassTimes& t = timings[i];
        timemodel::ProfileSample recorded;
        recorded.wallMinMs = timemodel::timeFromPasses("wall-min", t);
        recorded.wallMinMedianMs = timemodel::timeFromPasses("wall-min-median", t);
        recorded.wallMedianMs = timemodel::timeFromPasses("wall-median", t);
        recorded.cpuMs = timemodel::timeFromPasses("cpu", t);
        timemodel::Sample& sample = recorded.sample;
        sample.features = tables[planned.viewpoint].features(planned.combination);
        sample.measuredMs = timemodel::timeOnClock(recorded, clock);
        sample.viewpoint = planned.viewpoint;
        if (sample.measuredMs > 0.0) spreads.push_back(timemodel::passSpread(timemodel::perPassValues(clock, t)));
        recorded.heldOut = heldOut[i];
        (recorded.heldOut ? heldOutSamples : fitSamples).push_back(sample);
        profile.samples.push_back(recorded);
    }
    profile.models = timemodel::fitAllModels(fitSamples, heldOutSamples);
    {  // every viewpoint held out once, from the same draws
        std::vector<timemodel::Sample> all;
        std::vector<int> folds;
        for (std::size_t i = 0; i < count; ++i) {
            all.push_back(profile.samples[i].sample);
            folds.push_back(plan.viewpoints[plan.samples[i].viewpoint].fold);
        }
        const std::vector<timemodel::ErrorStats> rotated = timemodel::rotatedHeldOutErrors(all, folds);
        for (std::size_t m = 0; m < profile.models.size() && m < rotated.size(); ++m) {
            profile.models[m].rotatedErrors = rotated[m];
        }
    }
    const bool anyFitted = std::any_of(profile.models.begin(), profile.models.end(),
                                       [](const timemodel::ModelResult& r) { return r.fitted; });
    if (!anyFitted) {
        std::string reasons;
        for (const auto& r : profile.models) reasons += "\n  " + r.name + ": " + r.failure;
        throw std::runtime_error("no time model could be fitted:" + reasons);
    }

    // The same draws judged by the other clocks: one run shows how much of the error is the
    // model and how much the timing.
    struct OtherClock {
        std::string clock;
        std::vector<timemodel::ModelResult> models;
        timemodel::ErrorStats repeatability;
    };
    std::vector<OtherClock> otherClocks;
    for (const std::string& other : timemodel::timingClockNames()) {
        if (other == clock) continue;
        std::vector<timemodel::Sample> fitOther, heldOutOther;
        for (const timemodel::ProfileSample& recorded : profile.samples) {
            timemodel::Sample sample = recorded.sample;
            sample.measuredMs = timemodel::timeOnClock(recorded, other);
            (recorded.heldOut ? heldOutOther : fitOther).push_back(sample);
        }
        otherClocks.push_back({other, timemodel::fitAllModels(fitOther, heldOutOther),
                               timemodel::splitHalfRepeatability(other, timings, heldOut)});
    }

    profile.created = timemodel::currentDateUtc();
    profile.machine = timemodel::describeMachine();
    profile.glRenderer = renderer.glRendererString();
    profile.glVersion = renderer.glVersionString();
    profile.width = settings.width;
    profile.shading = options.shading;
    profile.height = settings.height;
    profile.scene = scene.name;
    profile.sceneSeed = options.sceneSeed;
    profile.seed = options.seed;
    profile.viewpoints = static_cast<int>(plan.viewpoints.size());
    profile.heldOutViewpoints = static_cast<int>(std::count_if(
        plan.viewpoints.begin(), plan.viewpoints.end(), [](const timemodel::Viewpoint& v) { return v.heldOut; }));
    const timemodel::ErrorStats spread = timemodel::summarizeErrors(spreads);
    const timemodel::ErrorStats repeatability = timemodel::splitHalfRepeatability(clock, timings, heldOut);
    profile.timing.clock = clock;
    profile.timing.clockRequest = options.clock;
    profile.timing.rounds = passes;
    profile.timing.repeatsPerRound = options.repeats;
    profile.timing.warmup = options.warmup;
    profile.timing.medianSpread = spread.median;
    profile.timing.p90Spread = spread.p90;
    profile.timing.splitHalfMedian = repeatability.median;
    profile.timing.splitHalfP90 = repeatability.p90;
    profile.timing.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    timemodel::saveProfile(options.out, profile);

    if (options.output.json) {
        nlohmann::json models = nlohmann::json::array();
        for (const timemodel::ModelResult& r : profile.models) {
            nlohmann::json entry = {{"name", r.name}, {"fitted", r.fitted}};
            if (!r.fitted) entry["failure"] = r.failure;
            nlohmann::json coefficients = nlohmann::json::object();
            for (std::size_t c = 0; c < r.coefficients.size(); ++c)
                coefficients[r.coefficientNames[c]] = r.coefficients[c];
            entry["coefficients"] = coefficients;
            entry["held_out_errors"] = errorsJson(r.heldOutErrors);
            entry["rotated_held_out_errors"] = errorsJson(r.rotatedErrors);
            entry["fit_errors"] = errorsJson(r.fitErrors);
            entry["notes"] = r.fit.notes;
            models.push_back(entry);
        }
        nlohmann::json clockChoiceJson = {{"judged_on", "fitting samples"}, {"measured", choice.measured}};
        for (const timemodel::ClockCandidate& candidate : choice.candidates) {
            clockChoiceJson["split_half"][candidate.clock] = errorsJson(candidate.repeatability);
        }
        nlohmann::json otherJson = nlohmann::json::object();
        for (const OtherClock& other : otherClocks) {
            nlohmann::json entries = nlohmann::json::array();
            for (const timemodel::ModelResult& r : other.models) {
                entries.push_back({{"name", r.name},
                                   {"fitted", r.fitted},
                                   {"held_out_errors", errorsJson(r.heldOutErrors)},
                                   {"fit_errors", errorsJson(r.fitErrors)}});
            }
            otherJson[other.clock] = {{"models", entries},
                                      {"split_half_median", other.repeatability.median},
                                      {"split_half_p90", other.repeatability.p90}};
        }
        printJson({{"out", options.out},
                   {"scene", scene.name},
                   {"width", settings.width},
                   {"height", settings.height},
                   {"shading", options.shading},
                   {"renderer", profile.glRenderer},
                   {"cpu_model", profile.machine.cpuModel},
                   {"cores", profile.machine.cores},
                   {"samples", count},
                   {"fit_samples", fitSamples.size()},
                   {"held_out_samples", heldOutSamples.size()},
                   {"viewpoints", profile.viewpoints},
                   {"held_out_viewpoints", profile.heldOutViewpoints},
                   {"clock", clock},
                   {"clock_request", options.clock},
                   {"clock_choice", clockChoiceJson},
                   {"timing_spread_median", spread.median},
                   {"timing_spread_p90", spread.p90},
                   {"split_half_median", repeatability.median},
                   {"split_half_p90", repeatability.p90},
                   {"seconds", profile.timing.seconds},
                   {"default_model", profile.defaultModel},
                   {"models", models},
                   {"other_clocks", otherJson}});
        return;
    }
    std::cout << "calibrated '" << scene.name << "' at " << settings.width << "x" << settings.height << " on "
              << profile.machine.cpuModel << " (" << profile.machine.cores << " threads), " << profile.glRenderer
              << "\n";
    char line[512];
    std::snprintf(line, sizeof line,
                  "%zu samples: %zu fitted on %d viewpoints, %zu held out on %d viewpoints\n"
                  "timing: clock %s, %d passes x %d draws (+%d warm-up); spread between passes: median %.1f%%, "
                  "p90 %.1f%%\n"
                  "repeatability: a held-out sample's time from the even passes against the odd ones differs by "
                  "median %.1f%%, p90 %.1f%%\n",
                  count, fitSamples.size(), profile.viewpoints - profile.heldOutViewpoints, heldOutSamples.size(),
                  profile.heldOutViewpoints, clock.c_str(), passes, options.repeats, options.warmup,
                  100.0 * spread.median, 100.0 * spread.p90, 100.0 * repeatability.median, 100.0 * repeatability.p90);
    std::cout << line;
    if (autoClock && !choice.measured) {
        std::cout << "clock auto: " << clock << ", the default: one pass leaves no repeatability to judge\n";
    } else if (autoClock) {
        std::cout << "clock auto: " << clock
                  << ", the wall clock that repeated best on the fitting samples (split-half median ";
        for (std::size_t c = 0; c < choice.candidates.size(); ++c) {
            std::snprintf(line, sizeof line, "%s%s %.1f%%", c ? ", " : "", choice.candidates[c].clock.c_str(),
                          100.0 * choice.candidates[c].repeatability.median);
            std::cout << line;
        }
        std::cout << ")\n";
    }
    std::cout << timemodel::formatErrorTable(profile.models);
    std::snprintf(line, sizeof line, "every viewpoint held out once (%d folds, %zu samples):", plan.folds, count);
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
    for (const OtherClock& other : otherClocks) {
        std::snprintf(line, sizeof line, "same draws, clock %s (repeatability %.1f%% / %.1f%%):", other.clock.c_str(),
                      100.0 * other.repeatability.median, 100.0 * other.repeatability.p90);
        std::cout << line;
        for (const timemodel::ModelResult& r : other.models) {
            if (!r.fitted) continue;
            std::snprintf(line, sizeof line, "  %s mean %.1f%% p90 %.1f%%", r.name.c_str(),
                          100.0 * r.heldOutErrors.mean, 100.0 * r.heldOutErrors.p90);
            std::cout << line;
        }
        std::cout << "\n";
    }
    std::snprintf(line, sizeof line, "wrote %s (%.1f s)\n", options.out.c_str(), profile.timing.seconds);
    std::cout << line;
}

std::vector<std::string> clockChoices() {
    std::vector<std::string> names = timemodel::timingClockNames();
    names.insert(names.begin(), timemodel::kAutoClock);
    return names;
}

}  // namespace

void addCalibrateCommand(CLI::App& app) {
    auto options = std::make_shared<CalibrateOptions>();
    CLI::App* command =
        app.add_subcommand("calibrate", "Time sampled frames, fit every render-time model, write a device profile");
    command->add_option("--scene", options->scene, "Built-in scene name or glTF/GLB path")->capture_default_str();
    command->add_option("--views", options->views, "Named views to calibrate from, comma-separated (default all)");
    command->add_option("--samples", options->samples, "Frames to time in all (>= 4)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000));
    command->add_option("--seed", options->seed, "Seed of the sampled combinations and viewpoints")
        ->capture_default_str();
    addSceneSeedOption(*command, options->sceneSeed);
    command->add_option("--size", options->size, "WIDTHxHEIGHT of the timed frames")->capture_default_str();
    addShadingOption(*command, options->shading);
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
        ->add_option("--clock", options->clock,
                     "Fitted time: auto (the wall clock that repeats best in this run), wall-min (least wall "
                     "time), wall-min-median (median of each pass's least), wall-median, or cpu (process CPU time)")
        ->capture_default_str()
        ->check(CLI::IsMember(clockChoices()));
    command->add_option("--out", options->out, "Device profile to write (JSON)")->capture_default_str();
    addOutputOptions(*command, options->output);
    command->callback([options] { runCalibrate(*options); });
}

}  // namespace lodopt::cli
