// The default model: T = c0 + Σ c_k·feature_k, non-negative least squares (Lawson & Hanson
// 1974) on relative residuals, with constant/collinear features dropped and the condition
// number bounded (method.md §4, Hazard: "use least squares (non-negative, checked
// conditioning) by default").
#include "least_squares.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

std::vector<std::string> LinearModel::coefficientNames() const {
    std::vector<std::string> names = {"intercept_ms"};
    for (Feature feature : allFeatures()) names.push_back(featureName(feature));
    return names;
}

FeatureSet LinearModel::readFeatures() const {
    if (!fitted()) return everyFeature();
    FeatureSet read;
    for (std::size_t k = 0; k < kFeatureCount; ++k) read[k] = mCoefficients[k + 1] != 0.0;
    return read;
}

double LinearModel::estimateCalibratedMs(const FrameFeatures& features) const {
    double total = mCoefficients[0];
    for (std::size_t k = 0; k < kFeatureCount; ++k) total += mCoefficients[k + 1] * features.values[k];
    return total;
}

FitReport LinearModel::fitValidated(const std::vector<Sample>& samples) {
    const std::size_t n = samples.size();
    detail::Matrix design(n, kFeatureCount + 1);
    std::vector<double> target(n), weights(n);
    for (std::size_t r = 0; r < n; ++r) {
        design.at(r, 0) = 1.0;
        for (std::size_t k = 0; k < kFeatureCount; ++k) design.at(r, k + 1) = samples[r].features.values[k];
        target[r] = samples[r].measuredMs;
        weights[r] = 1.0 / samples[r].measuredMs;  // minimise relative, not absolute, error
    }
    // Which of two dependent features survives: the one earlier here. Rasterisation and vertex
    // work first (they dominate llvmpipe), per-object counts last. Every feature is listed.
    auto column = [](Feature feature) { return static_cast<std::size_t>(feature) + 1; };
    const std::vector<std::size_t> order = {0,
                                            column(Feature::kVisibleTriangles),
                                            column(Feature::kShadedPixels),
                                            column(Feature::kTexturedPixels),
                                            column(Feature::kShadedPartialBlocks),
                                            column(Feature::kPartialBlocks),
                                            column(Feature::kShadedEdgePixels),
                                            column(Feature::kEdgePixels),
                                            column(Feature::kRasterPixels),
                                            column(Feature::kTriangles),
                                            column(Feature::kPixels),
                                            column(Feature::kVertices),
                                            column(Feature::kDrawCalls),
                                            column(Feature::kTextureBytes),
                                            column(Feature::kDrawnObjects),
                                            column(Feature::kMatrices),
                                            column(Feature::kBoundingBoxes)};
    detail::CheckedFit fit = detail::fitNonNegative(design, target, weights, order, coefficientNames(), 0);
    mCoefficients = fit.coefficients;
    FitReport report;
    report.notes = fit.notes;
    report.conditionNumber = fit.conditionNumber;
    report.iterations = fit.iterations;
    return report;
}

}  // namespace lodopt::timemodel
