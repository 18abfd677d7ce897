// What a device profile predicts, and which statistic of the calibration's draws it learns from.
//
// Every profile predicts one quantity: the **median of a frame's warmed draws** on the
// renderer's frame clock (wall time of draw + glFinish, or a GPU timer's time where the driver's
// timer covers the frame: renderer.hpp FrameClock). It is what `render --time`, `schedule
// --render` and `bench` measure (renderer::FrameTimes::median), so an estimate and a measurement
// mean the same thing whichever calibration made the profile.
//
// `lodopt calibrate` times every sample in several passes, each pass a batch of draws
// (PassTimes). A statistic reduces a sample's passes to one time:
//   median        the median over the passes of each pass's median: the predicted quantity;
//   least-median  the median over the passes of each pass's least;
//   least         the least of all draws (others' load only ever adds time);
//   cpu           the median over the passes of each pass's median process CPU time.
// The models may *learn* from any of them and still predict the median: fitted on the learned
// times multiplied by the learned scale (the median over the fitting samples of median ÷
// learned), then judged against the median. Every model's prediction is proportional to its
// coefficients, so this is the model of the learned statistic with its coefficients scaled.
// Which to learn from depends on the machine and the hour: where the frame speed jumps between
// levels within minutes, a median over passes straddling a jump lands on either level from
// sample to sample while the least stays on the fast one; where the least has a long lower
// tail, the medians repeat better (docs/timemodel.md "What a profile predicts"). With
// kAutoStatistic a calibration learns from the statistic whose error against the median,
// every fitting viewpoint held out once, is least; the held-out viewpoints take no part.
#pragma once

#include <string>
#include <vector>

#include "timemodel/profile.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

inline constexpr const char* kPredictedStatistic = "median";
// `--learn-from auto`: the statistic chosen per run (chooseStatisticToLearn).
inline constexpr const char* kAutoStatistic = "auto";

// "median", "least-median", "least", "cpu".
std::vector<std::string> timingStatisticNames();
// `name` as one of timingStatisticNames(): profiles written before the predicted quantity was
// fixed name them wall-median, wall-min-median, wall-min; "" for an unknown name.
std::string canonicalStatistic(const std::string& name);

// One sample's timings, one entry per pass (all the same length), milliseconds; least, median
// and cpu on the frame clock's draws, wallMedian and gpuMedian recorded beside them (gpuMedian
// empty without timer queries).
struct PassTimes {
    std::vector<double> least;       // each pass's least frame time
    std::vector<double> median;      // each pass's median frame time
    std::vector<double> cpu;         // each pass's median process CPU time
    std::vector<double> wallMedian;  // each pass's median wall time
    std::vector<double> gpuMedian;   // each pass's median GL_TIME_ELAPSED
};

// The middle value, the mean of the two middle ones for an even count; NaN for an empty list
// (JSON null), so that a missing median never reads as a measured 0. The one median of timings
// and of the reports' columns (calibration, the scheduler's walk, the CLI's tables).
double median(std::vector<double> values);

// The per-pass values `statistic` (one of timingStatisticNames()) reduces: least for least and
// least-median, median for median, cpu for cpu.
const std::vector<double>& perPassValues(const std::string& statistic, const PassTimes& times);

// `statistic`'s reduction of `perPass` (non-empty): its least for least, its median otherwise.
double reducePasses(const std::string& statistic, const std::vector<double>& perPass);

// The sample's time by `statistic` from all its passes; 0 with no pass.
double timeFromPasses(const std::string& statistic, const PassTimes& times);

// Spread of `perPass` (non-empty, median > 0): (greatest − least) / median.
double passSpread(const std::vector<double>& perPass);

// How slowly each pass drew against the run as a whole: per pass, the median over the samples
// of that pass's median ÷ the sample's median over all its passes (samples with a time <= 0 in
// any pass are skipped). 1 is the run's typical speed; 1.2, a pass whose frames took 20% longer.
// A machine whose speed moves between passes (another tenant, a clock governor) shows here
// before it shows as model error. One factor per pass (as many as the first sample has; samples
// with another count are skipped); empty when there is no sample, no pass, or a pass no sample
// could judge.
std::vector<double> passTimeFactors(const std::vector<PassTimes>& times);

// (greatest factor ÷ least) − 1: how far the machine's speed moved between a run's passes; 0 for
// fewer than two factors.
double passDrift(const std::vector<double>& factors);

// Split-half repeatability of `statistic` over the samples i with include[i] (include.size() ==
// times.size()): |even − odd| / all per sample, summarized; samples with fewer than two passes
// or a time ≤ 0 are skipped (count 0 when none is left).
ErrorStats splitHalfRepeatability(const std::string& statistic, const std::vector<PassTimes>& times,
                                  const std::vector<bool>& include);

// The median over the pairs with both > 0 of predicted[i] / learned[i]; 1 when there is none.
// learned.size() == predicted.size().
double learnedScale(const std::vector<double>& learned, const std::vector<double>& predicted);

struct LearnCandidate {
    std::string statistic;
    double scale = 1.0;         // learnedScale on every fitting sample
    ErrorStats crossValidated;  // against the median, every fitting viewpoint held out once
};

struct LearnChoice {
    std::string statistic;                   // the chosen one
    std::vector<LearnCandidate> candidates;  // median, least-median, least, in that order
    bool measured = false;  // false: no candidate could be judged (one fitting viewpoint): the median itself
};

// `--learn-from auto`: over the samples that are not held out (features, viewpoint and every
// statistic recorded), the statistic of median, least-median and least whose error against the
// median with every fitting viewpoint held out once (rotatedHeldOutErrors, one fold per
// viewpoint, model `model`) has the least mean; a tie keeps the earlier. cpu is never chosen
// automatically: it is the work, not the frame's time.
LearnChoice chooseStatisticToLearn(const std::vector<ProfileSample>& samples, const std::string& model);

// The models learning from one statistic of a profile's samples, predicting the median.
struct StatisticFit {
    std::string statistic;
    double scale = 1.0;  // learnedScale over the fitting samples
    std::vector<ModelResult> models;
};

struct ProfileFit {
    LearnChoice choice;                // what kAutoStatistic judged (computed whatever was asked)
    std::vector<StatisticFit> others;  // the same samples learned from every other statistic
};

// Fits `profile`'s models from its samples (their features, held-out flags and statistics;
// folds[i]: sample i's fold, 0 = held out) to predict the median of a frame's draws, learning
// from `learnFrom` (a statistic's name or kAutoStatistic): sets profile.models (held-out and
// rotated errors against the median), the samples' measuredMs (the median) and timing.predicts,
// learnedFrom, learnedScale and learnRequest. What `lodopt calibrate` does after timing, and what
// `--refit` does to a profile written earlier. Throws TimeModelError for an unknown statistic,
// samples without a recorded median, or when no model could be fitted.
ProfileFit fitProfile(DeviceProfile& profile, const std::vector<int>& folds, const std::string& learnFrom);

// The folds of a profile's samples: as stored (ProfileSample::fold); for a profile written before
// they were, 0 for the held-out samples and one fold per fitting viewpoint.
std::vector<int> profileFolds(const DeviceProfile& profile);

// fitProfile on the profile's own samples and folds (profileFolds), no frame timed again: how
// `lodopt calibrate --refit` brings a profile written earlier to predict the median.
ProfileFit refitProfile(DeviceProfile& profile, const std::string& learnFrom);

}  // namespace lodopt::timemodel
