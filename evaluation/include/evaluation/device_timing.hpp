// Calibrating a device's profile: what `lodopt calibrate` runs.
//
// Every frame is timed by renderer::Renderer::timeFrames, as `render --time`, `schedule
// --render` and `bench` time theirs: `warmup` untimed draws, then `repeats` timed draw + glFinish
// on the renderer's frame clock (wall, or a GPU timer), with process CPU time beside. A
// calibration times every planned sample (timemodel::planCalibration) in interleaved passes, a
// fresh shuffled order per pass, so that a burst of load from elsewhere spreads over many
// samples instead of ruining one: at least `rounds` passes, then more (up to `maxRounds`) while
// the wall time since `start` plus the slowest pass so far stays within `timeBudgetSeconds`. It
// then fits every time model to predict the median of a frame's draws (timemodel/timing.hpp),
// learning from the statistic asked for (or, with timemodel::kAutoStatistic, the one that
// predicted the median best with every fitting viewpoint held out once), holds every viewpoint
// out once, and refits learning from the other statistics of the same draws, so that one run
// shows how much of the error is the model and how much the clock.
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

}  // namespace lodopt::evaluation
