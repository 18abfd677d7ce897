// Render-time models: frame features → predicted milliseconds, fitted from measured samples.
//
// Three models, all fitted from the same samples (method.md §4):
//   dong    DONG15 eq. 5: T = c1·triangles + c2·texture_bytes, fitted as published (eqs. 7–8):
//           Cramer's rule on every pair of samples, averaged over all pairs. Pairs whose
//           feature vectors are nearly parallel (determinant ~ 0) are skipped and counted.
//   wimmer  CITY17 after Wimmer & Wonka 2003: RT = RT_sys + max(RT_cpu, RT_gpu),
//           RT_gpu = c1·vertices + c2·pixels, RT_cpu = c3·matrices + c4·bounding_boxes +
//           c5·draw_calls. Fitted by alternating regime assignment (each sample CPU- or
//           GPU-bound under the current fit) and non-negative least squares, from several
//           starting assignments; the best max-model fit wins.
//   linear  (default) T = c0 + Σ c_k·feature_k over every feature (features.hpp), non-negative least
//           squares. Constant, zero or collinear features are dropped with a note and the
//           kept set's condition number is bounded, so the fit never blows up silently.
// linear and wimmer minimise the squared *relative* error Σ((t_est − t_act)/t_act)², the
// quantity the error tables report (DONG15 eq. 10).
//
// Online feedback (DONG15 eq. 9), for any model: c' = (1 + β (t_act − t_est)/t_est)·c, with
// the relative error clamped to ±maxRelativeError (≤ 1, so the factor stays ≥ 1 − β > 0) and
// the accumulated scale kept within [1/maxDrift, maxDrift] of the calibrated coefficients.
#pragma once

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "timemodel/features.hpp"

namespace lodopt::timemodel {

// Bad samples or coefficients from outside (measurements, profile files): a clear message,
// never an assert.
class TimeModelError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// One measurement: a frame's features and its measured render time.
struct Sample {
    FrameFeatures features;
    double measuredMs = 0.0;  // > 0, finite; milliseconds of draw + glFinish
    int viewpoint = -1;       // calibration viewpoint index, for bookkeeping only
};

struct FitReport {
    std::size_t samples = 0;
    std::vector<std::string> notes;  // dropped features, skipped pairs, regimes, ...
    double rmsResidualMs = 0.0;      // sqrt(mean (t_est − t_act)²) over the fitted samples
    double conditionNumber = 0.0;    // of the checked design (linear, wimmer); 0 for dong
    std::size_t pairs = 0;           // dong: pairs considered
    std::size_t skippedPairs = 0;    // dong: pairs with a near-zero determinant
    int iterations = 0;              // wimmer: regime-assignment rounds; linear: NNLS solves
};

struct FeedbackParameters {
    // 0 < beta < 1, DONG15 eq. 9. 0.7: replaying nine recorded schedules (three scenes, three
    // runs) with other gains, 0.7 put more binding frames in the budget's band than 0.3 in each
    // (docs/scheduler.md "Feedback", scripts/feedback_replay.py).
    double beta = 0.7;
    double maxRelativeError = 1.0;  // 0 < x <= 1: clamp of (t_act − t_est)/t_est per frame
    double maxDrift = 4.0;          // >= 1: accumulated scale stays in [1/maxDrift, maxDrift]
};

struct FeedbackResult {
    bool applied = false;        // false when the frame was unusable (time not finite or <= 0)
    double relativeError = 0.0;  // (t_act − t_est)/t_est before clamping
    double factor = 1.0;         // what the coefficients were multiplied by
};

class TimeModel {
public:
    virtual ~TimeModel() = default;

    virtual std::string name() const = 0;
    // One name per coefficient, in coefficients() order; used as profile keys.
    virtual std::vector<std::string> coefficientNames() const = 0;
    // The fewest samples fit() accepts.
    virtual std::size_t minimumSamples() const { return 2; }
    virtual std::unique_ptr<TimeModel> clone() const = 0;

    // Predicted render time in ms (>= 0; negative predictions of a bad fit clamp to 0).
    double estimateMs(const FrameFeatures& features) const;
    // The features estimateMs reads with these coefficients (every one while unfitted): a
    // FeatureTable built for this set predicts the same (FeatureSet). Feedback scales every
    // coefficient alike, so it never changes the set; setCoefficients and fit may.
    virtual FeatureSet readFeatures() const = 0;

    // Effective coefficients: the calibrated ones times the feedback scale.
    std::vector<double> coefficients() const;
    const std::vector<double>& calibratedCoefficients() const { return mCoefficients; }
    // Sets calibrated coefficients (resets feedback). Throws TimeModelError unless there is
    // one finite value per coefficientNames() entry.
    void setCoefficients(const std::vector<double>& coefficients);
    bool fitted() const { return !mCoefficients.empty(); }

    // Fits the coefficients (resets feedback). Throws TimeModelError when there are fewer
    // than minimumSamples() samples, a measured time is not finite or not > 0, a feature is
    // negative or not finite, or the data admit no fit (e.g. every Cramer pair degenerate).
    FitReport fit(const std::vector<Sample>& samples);

    // DONG15 eq. 9 with the bounds above. `actualMs` is a measurement (outside data): an
    // unusable one is ignored and reported, not asserted. `parameters` must be valid.
    FeedbackResult applyFeedback(const FrameFeatures& features, double actualMs,
                                 const FeedbackParameters& parameters = {});
    double feedbackScale() const { return mFeedbackScale; }
    void resetFeedback() { mFeedbackScale = 1.0; }

protected:
    virtual double estimateCalibratedMs(const FrameFeatures& features) const = 0;
    // Called with validated samples; sets mCoefficients.
    virtual FitReport fitValidated(const std::vector<Sample>& samples) = 0;

    std::vector<double> mCoefficients;
    double mFeedbackScale = 1.0;
};

class DongModel final : public TimeModel {
public:
    // Pairs whose unit-free feature vectors (each feature divided by its mean over the
    // samples) meet at an angle with sine below `minimumSine` are skipped. 0 <= x < 1.
    explicit DongModel(double minimumSine = 1e-3);
    std::string name() const override { return "dong"; }
    std::vector<std::string> coefficientNames() const override;
    std::unique_ptr<TimeModel> clone() const override { return std::make_unique<DongModel>(*this); }
    FeatureSet readFeatures() const override;  // triangles, texture bytes

private:
    double estimateCalibratedMs(const FrameFeatures& features) const override;
    FitReport fitValidated(const std::vector<Sample>& samples) override;
    double mMinimumSine;
};

class WimmerModel final : public TimeModel {
public:
    std::string name() const override { return "wimmer"; }
    std::vector<std::string> coefficientNames() const override;
    std::unique_ptr<TimeModel> clone() const override { return std::make_unique<WimmerModel>(*this); }
    FeatureSet readFeatures() const override;  // vertices, pixels, matrices, bounding boxes, draw calls
    // The two terms of the max for a frame (without RT_sys), calibrated coefficients.
    double cpuMs(const FrameFeatures& features) const;
    double gpuMs(const FrameFeatures& features) const;

private:
    double estimateCalibratedMs(const FrameFeatures& features) const override;
    FitReport fitValidated(const std::vector<Sample>& samples) override;
};

class LinearModel final : public TimeModel {
public:
    std::string name() const override { return "linear"; }
    // "intercept_ms", then featureName() of every feature in index order.
    std::vector<std::string> coefficientNames() const override;
    std::unique_ptr<TimeModel> clone() const override { return std::make_unique<LinearModel>(*this); }
    FeatureSet readFeatures() const override;  // the features with a coefficient other than 0

private:
    double estimateCalibratedMs(const FrameFeatures& features) const override;
    FitReport fitValidated(const std::vector<Sample>& samples) override;
};

inline constexpr const char* kDefaultTimeModel = "linear";
// "linear", "dong", "wimmer": the default first.
std::vector<std::string> timeModelNames();
// An unfitted model; throws TimeModelError listing the names for an unknown one.
std::unique_ptr<TimeModel> makeTimeModel(const std::string& name);

// DONG15 eq. 10, |t_act − t_est| / t_act, summarised.
struct ErrorStats {
    std::size_t count = 0;
    double mean = 0.0;
    double median = 0.0;
    double p90 = 0.0;  // 90th percentile, linear interpolation between order statistics
    double max = 0.0;
};
ErrorStats summarizeErrors(std::vector<double> errors);
ErrorStats relativeErrors(const TimeModel& model, const std::vector<Sample>& samples);

}  // namespace lodopt::timemodel
