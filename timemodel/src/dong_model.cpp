// Dong, Liu, Xia, Fan, Zhang 2015 (PLoS ONE 10(2)), eqs. 5, 7–8: T = c1·v_num + c2·t_size,
// c1 and c2 solved by Cramer's rule for every pair of samples and averaged over the pairs.
// "Polygons" are our triangles; "texture amount" our texture bytes.
#include <cassert>
#include <cmath>

#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

DongModel::DongModel(double minimumSine) : mMinimumSine(minimumSine) {
    assert(minimumSine >= 0.0 && minimumSine < 1.0);
}

std::vector<std::string> DongModel::coefficientNames() const {
    return {"triangles", "texture_bytes"};
}

FeatureSet DongModel::readFeatures() const {
    if (!fitted()) return everyFeature();
    FeatureSet read;
    read.set(std::size_t(Feature::kTriangles)).set(std::size_t(Feature::kTextureBytes));
    return read;
}

double DongModel::estimateCalibratedMs(const FrameFeatures& features) const {
    return mCoefficients[0] * features[Feature::kTriangles] + mCoefficients[1] * features[Feature::kTextureBytes];
}

FitReport DongModel::fitValidated(const std::vector<Sample>& samples) {
    FitReport report;
    const std::size_t n = samples.size();
    // Each feature divided by its mean, only to judge how parallel two samples are in a way
    // that does not depend on units; the solve itself uses the raw values, as published.
    double meanPolygons = 0.0, meanTexture = 0.0;
    for (const Sample& s : samples) {
        meanPolygons += s.features[Feature::kTriangles];
        meanTexture += s.features[Feature::kTextureBytes];
    }
    meanPolygons = meanPolygons > 0.0 ? meanPolygons / double(n) : 1.0;
    meanTexture = meanTexture > 0.0 ? meanTexture / double(n) : 1.0;
    double sumC1 = 0.0, sumC2 = 0.0;
    std::size_t used = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double pi = samples[i].features[Feature::kTriangles], ti = samples[i].features[Feature::kTextureBytes];
        const double Ti = samples[i].measuredMs;
        for (std::size_t j = i + 1; j < n; ++j) {
            ++report.pairs;
            const double pj = samples[j].features[Feature::kTriangles];
            const double tj = samples[j].features[Feature::kTextureBytes];
            const double Tj = samples[j].measuredMs;
            const double scaledNorms =
                std::hypot(pi / meanPolygons, ti / meanTexture) * std::hypot(pj / meanPolygons, tj / meanTexture);
            const double scaledDeterminant = (pi * tj - pj * ti) / (meanPolygons * meanTexture);
            if (!(scaledNorms > 0.0) || std::abs(scaledDeterminant) <= mMinimumSine * scaledNorms) {
                ++report.skippedPairs;
                continue;
            }
            // Cramer's rule on [pi ti; pj tj]·[c1 c2]^T = [Ti Tj]^T (DONG15 eqs. 7–8).
            const double determinant = pi * tj - pj * ti;
            sumC1 += (Ti * tj - Tj * ti) / determinant;
            sumC2 += (pi * Tj - pj * Ti) / determinant;
            ++used;
        }
    }
    if (used == 0) {
        throw TimeModelError("model 'dong': all " + std::to_string(report.pairs) +
                             " sample pairs have a near-zero determinant (triangles and texture bytes are "
                             "proportional or zero in every pair); no coefficients by Cramer's rule");
    }
    if (report.skippedPairs > 0) {
        report.notes.push_back("skipped " + std::to_string(report.skippedPairs) + " of " +
                               std::to_string(report.pairs) + " sample pairs with a near-zero determinant");
    }
    mCoefficients = {sumC1 / double(used), sumC2 / double(used)};
    return report;
}

}  // namespace lodopt::timemodel
