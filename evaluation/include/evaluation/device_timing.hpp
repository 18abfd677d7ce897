// Calibrating a device's profile: what `lodopt calibrate` runs.
//
// Every frame is timed by renderer::Renderer::timeFrames, as `render --time`, `schedule
// --render` and `bench` time theirs: `warmup` untimed draws, then `repeats` timed draw + glFinish
// on the renderer's frame clock (wall, or a GPU timer), with process CPU time beside. A
// calibration times every planned sample (timemodel::planCalibration) in interleaved passes, a
// fresh shuffled order per pass, so that a burst of load from elsewhere spreads over many
// samples instead of ruining one: at least `rounds` passes, then more (up to `maxRounds`) while
// the wall time since `start` plus the slowest pass so far stays within `timeBudgetSeconds`. Each
// pass opens with the speed anchor (the scene's first view, every object at its finest level),
// timed as a sample is, so that a later run can tell how fast the machine draws then (probeSpeed). It
// then fits every time model to predict the median of a frame's draws (timemodel/timing.hpp),
// learning from the statistic asked for (or, with timemodel::kAutoStatistic, the one that
// predicted the median best with every fitting viewpoint held out once), holds every viewpoint
// out once, and refits learning from the other statistics of the same draws, so that one run
// shows how much of the error is the model and how much the clock. Each pass's speed against the
// run's is recorded (passTimeFactors; their spread in the profile as timing.passDrift), so that a
// calibration during which the machine's speed moved beyond timemodel::kPassDriftWarning can say so.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "renderer/renderer.hpp"
#include "timemodel/calibration.hpp"
#include "timemodel/profile.hpp"
#include "timemodel/timing.hpp"

namespace lodopt::evaluation {

struct CalibrationSettings {
    int rounds = 6;      // passes at least, >= 1
    int maxRounds = 25;  // passes at most while time is left
    double timeBudgetSeconds = 110.0;
    int repeats = 3;  // timed draws per sample and pass, >= 1
    int warmup = 1;
    std::string learnFrom = timemodel::kAutoStatistic;  // a timing statistic's name, or kAutoStatistic
    std::uint64_t seed = 1;                             // the passes' shuffles
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();  // the budget's
};

// The same draws, the models learning from another statistic (still predicting the median).
struct OtherStatisticFit {
    std::string statistic;
    double scale = 1.0;  // timemodel::learnedScale on the fitting samples
    std::vector<timemodel::ModelResult> models;
    timemodel::ErrorStats repeatability;  // split-half, held-out samples
};

struct CalibrationResult {
    // Every field but `sceneSeed`, which only the caller knows; `seed` is the plan's as given.
    timemodel::DeviceProfile profile;
    timemodel::LearnChoice choice;  // what kAutoStatistic judged (computed whatever was asked)
    std::vector<OtherStatisticFit> otherStatistics;
    timemodel::ErrorStats spread;         // between passes' medians, per sample
    timemodel::ErrorStats repeatability;  // split-half of the median, held-out samples
    // Per pass, how slowly it drew against the run (timemodel::passTimeFactors), in pass order;
    // profile.timing.passDrift is their spread. Empty after --refit (no pass timed).
    std::vector<double> passTimeFactors;
    std::size_t fitSamples = 0, heldOutSamples = 0;
    int folds = 1;
};

// Called after each timed sample: pass (0-based), samples done in it, samples per pass.
using CalibrationProgress = std::function<void(int pass, std::size_t done, std::size_t total)>;

// Times `plan` (made for `scene` with seed `planSeed`) on `renderer` and fits the profile.
// Throws std::runtime_error naming every model's failure when none could be fitted.
CalibrationResult calibrateDevice(const scenes::Scene& scene, renderer::Renderer& renderer,
                                  const timemodel::CalibrationPlan& plan, std::uint64_t planSeed,
                                  const CalibrationSettings& settings, const CalibrationProgress& progress = {});

// How much faster or slower the machine draws now than when `profile` was calibrated: its speed
// anchor (timemodel::TimingSettings::anchorView / anchorMs, every object at its finest level)
// timed again by a renderer of `scene` with `settings`, as `render --time` times a frame
// (`repeats` draws after `warmup`, their median). A prediction of the profile times `ratio` is a prediction for the machine as it
// is now: what the scheduler's feedback learns over frames, in one probe. On a shared machine
// whose speed moves by tens of percent within minutes (docs/timemodel.md "Measured agreement"),
// that offset dwarfs the model's error. Throws std::invalid_argument when the profile has no
// anchor, is another scene's, or `settings` ask for another size or shading than the profile's
// (before any renderer is made).
struct SpeedProbe {
    std::string view;
    double anchorMs = 0.0;  // in the calibration
    double probeMs = 0.0;   // now
    double ratio = 1.0;     // probeMs / anchorMs
};
SpeedProbe probeSpeed(const scenes::Scene& scene, const timemodel::DeviceProfile& profile,
                      const renderer::RenderSettings& settings, int repeats = 15, int warmup = 2);

}  // namespace lodopt::evaluation
