// Calibration: which frames to measure, and fitting every model to the measurements.
//
// The plan (no rendering here; the `lodopt calibrate` command renders and times it):
//   viewpoints  each chosen named view plus `jitteredPerView` cameras orbiting its target
//               (yaw ±25°, pitch ±10°, distance ×0.78..1.28, target moved ≤ 4% of the distance);
//   held out    whole viewpoints: one per named view's group, rotating with the seed (with no
//               jitter, every fourth named view); no held-out viewpoint is ever fitted;
//   folds       the same rotation continued: fold k holds out what seed + k would, so that every
//               viewpoint is held out once over the folds (fold 0 = the held-out viewpoints);
//   samples     round-robin over viewpoints; half draw every object's level uniformly with
//               some objects not drawn (probability notDrawnProbability), half are skewed
//               (a per-sample preferred level and drawn fraction, all objects drawn in 40% of
//               them) so that scenes with many objects still spread from coarse to fine frames,
//               the reference included, instead of averaging out.
// Everything is drawn from SplitMix64 with the given seed (std distributions are not portable),
// so a plan is the same on every platform.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes/scene.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

// SplitMix64 (Steele, Lea, Flood 2014): tiny, fast, portable.
class SplitMix64 {
public:
    explicit SplitMix64(std::uint64_t seed) : mState(seed) {}
    std::uint64_t next();
    double uniform();  // [0, 1), 53 random bits
    int below(int n);  // [0, n), n > 0
    double between(double low, double high) { return low + (high - low) * uniform(); }

private:
    std::uint64_t mState;
};

struct CalibrationOptions {
    int samples = 240;                  // >= 4 measured frames in all
    int jitteredPerView = 3;            // >= 0 extra viewpoints around each named view
    std::vector<int> views;             // named view indices to use; empty = all of the scene's
    double notDrawnProbability = 0.15;  // 0..1, per object in the uniform half
    std::uint64_t seed = 1;
};

struct Viewpoint {
    scenes::Camera camera;
    int namedView = -1;  // the scene view it was derived from
    bool jittered = false;
    bool heldOut = false;
    int fold = 0;  // the fold that holds it out: 0 for the held-out viewpoints
};

struct PlannedSample {
    int viewpoint = -1;
    scenes::Combination combination;
};

struct CalibrationPlan {
    std::vector<Viewpoint> viewpoints;
    std::vector<PlannedSample> samples;
    int folds = 1;  // viewpoints' folds are in [0, folds)
};

// Throws TimeModelError for unusable options (too few samples, a view index out of range, a
// scene without views or objects, fewer than two viewpoints).
CalibrationPlan planCalibration(const scenes::Scene& scene, const CalibrationOptions& options);

// A camera orbiting `camera.target` near `camera` (see the file comment); same lens.
scenes::Camera jitterCamera(const scenes::Camera& camera, SplitMix64& rng);

// One model's result from one calibration run.
struct ModelResult {
    std::string name;
    bool fitted = false;
    std::string failure;  // why not, when !fitted
    std::vector<std::string> coefficientNames;
    std::vector<double> coefficients;
    FitReport fit;
    ErrorStats fitErrors;      // on the fitted samples
    ErrorStats heldOutErrors;  // on the held-out viewpoints' samples
    // Every viewpoint held out once (rotatedHeldOutErrors); count 0 when not measured.
    ErrorStats rotatedErrors;
};

// Fits every model of timeModelNames() to `fitSamples` and measures them on `heldOut`; a
// model that cannot be fitted is reported (fitted = false, failure) rather than thrown.
std::vector<ModelResult> fitAllModels(const std::vector<Sample>& fitSamples, const std::vector<Sample>& heldOut);

// Every viewpoint held out once: for each fold, every model fitted on the samples of the other
// folds and measured on that fold's; the errors of all folds pooled, per model of
// timeModelNames() (count 0 for a model that could not be fitted on some fold). `folds[i]` is
// sample i's fold. Less hostage than heldOutErrors to which few viewpoints one seed holds out.
std::vector<ErrorStats> rotatedHeldOutErrors(const std::vector<Sample>& samples, const std::vector<int>& folds);
// The same for models learning from one statistic and predicting another (timing.hpp): per fold
// the training samples' times (`learned[i].measuredMs`) are multiplied by the training samples'
// learnedScale towards `predicted`, and the fold's errors are against `predicted`. One result per
// name of `models`, in that order.
std::vector<ErrorStats> rotatedHeldOutErrors(const std::vector<Sample>& learned, const std::vector<double>& predicted,
                                             const std::vector<int>& folds, const std::vector<std::string>& models);

// The published-style table: per model, mean / median / p90 / max of |t_act − t_est| / t_act
// on the held-out samples (and the fit mean), in percent.
std::string formatErrorTable(const std::vector<ModelResult>& results);

}  // namespace lodopt::timemodel
