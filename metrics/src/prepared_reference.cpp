#include "prepared_reference.hpp"

namespace lodopt::metrics::detail {

void prepareReference(const ImageView& reference, const MetricParameters& parameters, PreparedReference& prepared,
                      SsimScratch& scratch) {
    validateParameters(parameters);
    validateView(reference, "reference image");
    PreparedReference& p = prepared;
    p.parameters = parameters;
    p.width = reference.width;
    p.height = reference.height;
    p.channels = reference.channels;
    p.grayScale = grayScale(parameters.grayWeights);
    p.ssimOn = parameters.ssimWeight > 0;
    p.boundaryOn = parameters.boundaryEntropyWeight > 0;
    p.informationOn = parameters.informationEntropyWeight > 0;
    if (p.ssimOn) {
        p.kernel = makeSsimKernel(parameters, p.width, p.height, p.grayScale);
        grayImage(reference, p.grayScale, p.referenceGray);
        const std::size_t mapSize = std::size_t(p.kernel.mapWidth) * p.kernel.mapHeight;
        p.referenceMean.assign(mapSize, 0.0);
        p.referenceVariance.assign(mapSize, 0.0);
        scratch.reserve(p.kernel);
        ssimReferenceStatistics(p.referenceGray.data(), std::size_t(p.width), p.kernel, 0, 0, p.kernel.mapWidth,
                                p.kernel.mapHeight, scratch, p.referenceMean.data(), p.referenceVariance.data(),
                                std::size_t(p.kernel.mapWidth));
    }
    if (p.boundaryOn) {
        p.boundaryReference = boundaryEntropy(reference, parameters);
        if (parameters.boundaryEntropyMode == EntropyMode::Histogram) {
            p.sobel = makeSobelBinning(parameters.boundaryHistogramBins, p.grayScale);
        }
    }
    if (p.informationOn) p.informationReference = informationEntropy(reference, parameters);
}

void setPrecisionRecall(MetricResult& result, const PrecisionRecall& counts) {
    result.precisionRecallComputed = true;
    result.truePositives = counts.truePositives;
    result.falsePositives = counts.falsePositives;
    result.falseNegatives = counts.falseNegatives;
    result.precision = counts.precision;
    result.recall = counts.recall;
}

}  // namespace lodopt::metrics::detail
