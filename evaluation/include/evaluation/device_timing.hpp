// Timing frames on the device and calibrating its profile: what `lodopt calibrate` runs, and how
// `lodopt bench` times a frame for the time models' error.
//
// A batch of timed draws: `warmup` untimed draws, then `repeats` timed draw + glFinish
// (renderer::Renderer::drawAndFinish), each on the steady clock and on the process CPU clock
// (all of llvmpipe's threads). A calibration times every planned sample (timemodel::
// planCalibration) in interleaved passes, a fresh shuffled order per pass, so that a burst of
// load from elsewhere spreads over many samples instead of ruining one: at least `rounds`
// passes, then more (up to `maxRounds`) while the wall time since `start` plus the slowest pass
// so far stays within `timeBudgetSeconds`. It then fits every time model on the clock asked for
// (or, with timemodel::kAutoClock, the wall clock whose split-half repeatability on the fitting
// samples was best), holds every viewpoint out once, and refits on the other clocks from the
// same draws so that one run shows how much of the error is the model and how much the timing.
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

// One batch of timed draws of a frame, milliseconds.
struct DrawTimes {
    double wallMin = 0.0, wallMedian = 0.0, cpuMedian = 0.0;
};
// `repeats` >= 1, `warmup` >= 0.
DrawTimes timeDraws(renderer::Renderer& renderer, const scenes::Combination& combination, const scenes::Camera& camera,
                    int repeats, int warmup);
// What `clock` (timemodel::timingClockNames) takes from one batch: the least wall time for
// wall-min and wall-min-median (which then take the least, or the median, over the passes),
// the median wall time for wall-median, the median CPU time for cpu.
double batchTime(const DrawTimes& times, const std::string& clock);

struct CalibrationSettings {
    int rounds = 6;                   // passes at least, >= 1
    int maxRounds = 25;               // passes at most while time is left
    double timeBudgetSeconds = 110.0;
    int repeats = 3;                  // timed draws per sample and pass, >= 1
    int warmup = 1;
    std::string clock = timemodel::kAutoClock;  // a timing clock's name, or kAutoClock
    std::uint64_t seed = 1;                     // the passes' shuffles
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();  // the budget's
};

// The same draws fitted on a clock other than the profile's.
struct OtherClockFit {
    std::string clock;
    std::vector<timemodel::ModelResult> models;
    timemodel::ErrorStats repeatability;  // split-half, held-out samples
};

struct CalibrationResult {
    // Every field but `sceneSeed`, which only the caller knows; `seed` is the plan's as given.
    timemodel::DeviceProfile profile;
    timemodel::ClockChoice choice;  // what kAutoClock judged (computed whatever was asked)
    std::vector<OtherClockFit> otherClocks;
    timemodel::ErrorStats spread;         // between passes, per sample, on the fitted clock
    timemodel::ErrorStats repeatability;  // split-half, held-out samples, on the fitted clock
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
