// Precision and recall of covered pixels (Zhou et al. 2014, HYBRID14 §6.4; VMI20):
// a pixel is covered when it differs from the background color; TP = covered in both and
// equal within the tolerance, FP = covered in the candidate but not TP, FN = covered in the
// reference but not TP. P = TP / (TP + FP), R = TP / (TP + FN), 0 / 0 = 1 (nothing covered
// means nothing was drawn wrongly).
#include "kernels.hpp"

namespace lodopt::metrics {

PrecisionRecall precisionRecallFromCounts(std::uint64_t truePositives, std::uint64_t falsePositives,
                                          std::uint64_t falseNegatives) {
    PrecisionRecall result;
    result.truePositives = truePositives;
    result.falsePositives = falsePositives;
    result.falseNegatives = falseNegatives;
    const std::uint64_t candidateCovered = truePositives + falsePositives;
    const std::uint64_t referenceCovered = truePositives + falseNegatives;
    result.precision = candidateCovered == 0 ? 1.0 : double(truePositives) / double(candidateCovered);
    result.recall = referenceCovered == 0 ? 1.0 : double(truePositives) / double(referenceCovered);
    return result;
}

PrecisionRecall precisionRecall(const ImageView& candidate, const ImageView& reference,
                                const MetricParameters& parameters) {
    validateParameters(parameters);
    detail::validatePair(candidate, reference);
    const detail::CoverageRule rule =
        detail::makeCoverageRule(parameters, candidate.channels, detail::grayScale(parameters.grayWeights));
    // Counting bits rather than indexing counters[class]: no store-to-load chain on runs of
    // background pixels, and the loop vectorises.
    std::vector<std::uint8_t> classes(std::size_t(candidate.width));
    std::uint64_t tp = 0, fp = 0, fn = 0;
    for (int y = 0; y < candidate.height; ++y) {
        detail::classifyRow(candidate.pixels + y * candidate.rowStride, reference.pixels + y * reference.rowStride,
                            candidate.width, rule, classes.data());
        for (const std::uint8_t c : classes) {
            tp += c & detail::kTruePositive;
            fp += (c & detail::kFalsePositive) >> 1;
            fn += (c & detail::kFalseNegative) >> 2;
        }
    }
    return precisionRecallFromCounts(tp, fp, fn);
}

}  // namespace lodopt::metrics
