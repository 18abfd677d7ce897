// The TimeModel base: validation, feedback (Dong et al. 2015, eq. 9), error statistics
// (eq. 10) and the model registry.
#include "timemodel/time_model.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <sstream>

namespace lodopt::timemodel {

namespace {

std::string number(double value) {
    std::ostringstream text;
    text << value;
    return text.str();
}

}  // namespace

double TimeModel::estimateMs(const FrameFeatures& features) const {
    assert(fitted());
    return std::max(0.0, mFeedbackScale * estimateCalibratedMs(features));
}

std::vector<double> TimeModel::coefficients() const {
    std::vector<double> effective = mCoefficients;
    for (double& c : effective) c *= mFeedbackScale;
    return effective;
}

void TimeModel::setCoefficients(const std::vector<double>& coefficients) {
    const std::vector<std::string> names = coefficientNames();
    if (coefficients.size() != names.size()) {
        throw TimeModelError("model '" + name() + "' has " + std::to_string(names.size()) + " coefficients, got " +
                             std::to_string(coefficients.size()));
    }
    for (std::size_t i = 0; i < coefficients.size(); ++i) {
        if (!std::isfinite(coefficients[i])) {
            throw TimeModelError("model '" + name() + "': coefficient '" + names[i] + "' is not finite");
        }
    }
    mCoefficients = coefficients;
    mFeedbackScale = 1.0;
}

FitReport TimeModel::fit(const std::vector<Sample>& samples) {
    if (samples.size() < minimumSamples()) {
        throw TimeModelError("not enough samples: model '" + name() + "' needs at least " +
                             std::to_string(minimumSamples()) + ", got " + std::to_string(samples.size()));
    }
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const double t = samples[i].measuredMs;
        if (!std::isfinite(t) || t <= 0.0) {
            throw TimeModelError("sample " + std::to_string(i) + ": measured time " + number(t) +
                                 " ms is not a positive finite number");
        }
        for (Feature feature : allFeatures()) {
            const double value = samples[i].features[feature];
            if (!std::isfinite(value) || value < 0.0) {
                throw TimeModelError("sample " + std::to_string(i) + ": feature '" + featureName(feature) + "' is " +
                                     number(value) + " (must be finite and >= 0)");
            }
        }
    }
    mFeedbackScale = 1.0;
    FitReport report = fitValidated(samples);
    report.samples = samples.size();
    double sum = 0.0;
    for (const Sample& sample : samples) {
        const double residual = estimateMs(sample.features) - sample.measuredMs;
        sum += residual * residual;
    }
    report.rmsResidualMs = std::sqrt(sum / double(samples.size()));
    return report;
}

FeedbackResult TimeModel::applyFeedback(const FrameFeatures& features, double actualMs,
                                        const FeedbackParameters& parameters) {
    assert(parameters.beta > 0.0 && parameters.beta < 1.0);
    assert(parameters.maxRelativeError > 0.0 && parameters.maxRelativeError <= 1.0);
    assert(parameters.maxDrift >= 1.0);
    FeedbackResult result;
    const double estimate = estimateMs(features);
    if (!std::isfinite(actualMs) || actualMs <= 0.0 || !(estimate > 0.0)) return result;
    result.relativeError = (actualMs - estimate) / estimate;
    const double clamped = std::clamp(result.relativeError, -parameters.maxRelativeError, parameters.maxRelativeError);
    // Every coefficient gets the same factor, so the prediction scales by it too.
    const double scale =
        std::clamp(mFeedbackScale * (1.0 + parameters.beta * clamped), 1.0 / parameters.maxDrift, parameters.maxDrift);
    result.factor = scale / mFeedbackScale;
    result.applied = true;
    mFeedbackScale = scale;
    return result;
}

std::vector<std::string> timeModelNames() {
    return {"linear", "dong", "wimmer"};
}

std::unique_ptr<TimeModel> makeTimeModel(const std::string& name) {
    if (name == "linear") return std::make_unique<LinearModel>();
    if (name == "dong") return std::make_unique<DongModel>();
    if (name == "wimmer") return std::make_unique<WimmerModel>();
    std::string known;
    for (const std::string& n : timeModelNames()) known += (known.empty() ? "" : ", ") + n;
    throw TimeModelError("unknown time model '" + name + "' (models: " + known + ")");
}

ErrorStats summarizeErrors(std::vector<double> errors) {
    ErrorStats stats;
    stats.count = errors.size();
    if (errors.empty()) return stats;
    std::sort(errors.begin(), errors.end());
    double sum = 0.0;
    for (double e : errors) sum += e;
    stats.mean = sum / double(errors.size());
    auto quantile = [&](double q) {
        const double position = q * double(errors.size() - 1);
        const std::size_t below = static_cast<std::size_t>(std::floor(position));
        const std::size_t above = std::min(below + 1, errors.size() - 1);
        return errors[below] + (position - double(below)) * (errors[above] - errors[below]);
    };
    stats.median = quantile(0.5);
    stats.p90 = quantile(0.9);
    stats.max = errors.back();
    return stats;
}

ErrorStats relativeErrors(const TimeModel& model, const std::vector<Sample>& samples) {
    std::vector<double> errors;
    errors.reserve(samples.size());
    for (const Sample& sample : samples) {
        assert(sample.measuredMs > 0.0);
        errors.push_back(std::abs(sample.measuredMs - model.estimateMs(sample.features)) / sample.measuredMs);
    }
    return summarizeErrors(std::move(errors));
}

}  // namespace lodopt::timemodel
