// What the metrics' scorers share: the reference image prepared once (IncrementalEvaluator's
// state and RegionScorer's state both start from it; evaluate() computes the same from
// scratch), and how a result takes its precision/recall.
#pragma once

#include <cstdint>
#include <vector>

#include "kernels.hpp"
#include "metrics/metrics.hpp"

namespace lodopt::metrics::detail {

// The reference's size, the parameters and the components they turn on, the reference's gray
// image with its per-window SSIM means and variances (SSIM on), the Sobel binning (histogram
// boundary entropy on) and the reference's entropies (their component on).
struct PreparedReference {
    MetricParameters parameters;
    int width = 0, height = 0, channels = 0;
    GrayScale grayScale;
    bool ssimOn = false, boundaryOn = false, informationOn = false;
    SsimKernel kernel;
    std::vector<std::int32_t> referenceGray;
    std::vector<double> referenceMean, referenceVariance;
    SobelBinning sobel;
    double boundaryReference = 0, informationReference = 0;
};

// Validates `parameters` and `reference` (MetricError) and fills `prepared`; `scratch` is
// reserved for the kernel.
void prepareReference(const ImageView& reference, const MetricParameters& parameters, PreparedReference& prepared,
                      SsimScratch& scratch);

// Copies counts, precision and recall into `result` and marks them computed.
void setPrecisionRecall(MetricResult& result, const PrecisionRecall& counts);

}  // namespace lodopt::metrics::detail
