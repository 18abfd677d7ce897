// Image metrics that score a candidate rendering against the reference rendering
// (GAPSO15 §2, see docs/metrics.md for every definition and the reason behind it).
//
// Components, each computed on the gray image `Y = wR R + wG G + wB B` (paper weights
// 0.30/0.59/0.11 by default):
// - SSIM (Wang, Bovik, Sheikh, Simoncelli 2004): 11x11 Gaussian window, sigma 1.5,
//   K1 = 0.01, K2 = 0.03, L = 255, population covariance; the map holds one value per window
//   lying fully inside the image ("valid" windows, no padding, no downsampling), the score is
//   the map's mean. Equals scikit-image's structural_similarity(gaussian_weights=True,
//   sigma=1.5, use_sample_covariance=False, data_range=255) to ~1e-15. Computed in float64
//   from exact integer gray; windows whose pixels equal the reference's are exactly 1 and
//   are not recomputed.
// - Boundary entropy: Sobel 3x3 gradient magnitude on interior pixels, a histogram over the
//   fixed range [0, 255 sqrt(20)] (the largest possible Sobel magnitude of 8-bit data), and
//   its Shannon entropy in bits. `EntropyMode::Paper`: the paper's literal Roberts-cross sum
//   -sum g log2 g over raw magnitudes (not an entropy: can be negative; kept for comparison).
// - Information entropy: Shannon entropy in bits of the 256-bin histogram of the gray image
//   rounded to integers. `EntropyMode::Paper`: the literal -sum p log2 p with p = each
//   pixel's share of the total intensity (0 for an all-black image).
// - Precision and recall of covered pixels (HYBRID14 §6.4, VMI20): a pixel is covered when
//   it differs from the background color; TP = covered in both and equal within a tolerance.
// - Fidelities in [0, 1]: SSIM clamped; an entropy e becomes
//   1 - |e(cand) - e(ref)| / max(|e(ref)|, epsilon), clamped. Fitness = weighted mean of the
//   three fidelities; a component with weight 0 is not computed at all.
//
// Images are 8-bit, display-referred as stored in the framebuffer or PNG (no linearisation);
// float images are quantized first by convertFloatImage, which rejects NaN and Inf.
// Bad images or parameters (they may come from files and command lines) throw MetricError.
// Results are never NaN: every value stays inside the range stated next to it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace lodopt::metrics {

// An image, parameter set or rectangle the metrics cannot use; the message names it.
class MetricError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// A read-only 8-bit image: rows top to bottom, `channels` interleaved bytes per pixel
// (1 = gray, 3 = RGB, 4 = RGBA), values 0..255 as stored (sRGB-encoded for renders).
struct ImageView {
    const std::uint8_t* pixels = nullptr;  // first byte of the top row
    int width = 0;                         // pixels, >= 1
    int height = 0;                        // pixels, >= 1
    int channels = 0;                      // 1, 3 or 4
    std::size_t rowStride = 0;             // bytes from one row to the next, >= width * channels
};

// Tightly packed view over `pixels` (rowStride = width * channels).
ImageView makeImageView(const std::uint8_t* pixels, int width, int height, int channels);

// A read-only float image, nominal range [0, 1] in the same encoding as ImageView.
struct FloatImageView {
    const float* pixels = nullptr;
    int width = 0;
    int height = 0;
    int channels = 0;           // 1, 3 or 4
    std::size_t rowStride = 0;  // floats (not bytes) from one row to the next
};

// Quantizes `image` to 8 bits: round(255 * clamp(v, 0, 1)). Throws MetricError naming the
// first pixel and channel that is NaN or infinite. `storage` is resized (reused if large
// enough); the returned view points into it.
ImageView convertFloatImage(const FloatImageView& image, std::vector<std::uint8_t>& storage);

// Gray conversion weights; all three are exact integers over a power of ten, so gray values
// are computed exactly in integers (see docs/metrics.md).
enum class GrayWeights {
    Paper,  // 0.30 R + 0.59 G + 0.11 B (GAPSO15 §2), the default
    Bt601,  // 0.299 R + 0.587 G + 0.114 B
    Bt709,  // 0.2126 R + 0.7152 G + 0.0722 B
};

enum class EntropyMode {
    Histogram,  // Shannon entropy of a histogram, in bits (the default)
    Paper,      // the paper's literal per-pixel formula, for comparison
};

struct MetricParameters {
    GrayWeights grayWeights = GrayWeights::Paper;
    // SSIM (Wang et al. 2004). The window shrinks to the largest odd size that fits when the
    // image is smaller than it (a 1x1 image has a 1x1 window).
    int ssimWindow = 11;          // odd, 1..63, pixels per side
    double ssimSigma = 1.5;       // > 0, pixels, Gaussian weights renormalised over the window
    double ssimK1 = 0.01;         // > 0, C1 = (K1 L)^2
    double ssimK2 = 0.03;         // > 0, C2 = (K2 L)^2, C3 = C2 / 2
    double ssimDynamicRange = 255;  // L > 0, gray levels
    EntropyMode boundaryEntropyMode = EntropyMode::Histogram;
    int boundaryHistogramBins = 256;  // 2..65536 bins over [0, 255 sqrt(20)]
    EntropyMode informationEntropyMode = EntropyMode::Histogram;
    double entropyEpsilon = 1e-6;  // > 0, bits: floor of the reference entropy in a fidelity
    // Precision/recall: a pixel is covered when any channel differs from this color (RGBA;
    // RGB images compare R, G, B; gray images compare with the color's rounded gray value).
    // Default: the renderer's clear color (0.62, 0.76, 0.90) as bytes round(255 c).
    std::array<std::uint8_t, 4> background{158, 194, 230, 255};
    int matchTolerance = 8;  // 0..255: equal when the largest channel difference is <= this
    bool computePrecisionRecall = true;
    // Fusion weights, finite and >= 0, at least one > 0; only their ratios matter (1, 1, 1 =
    // equal thirds). Weight 0 = that component is not computed.
    double ssimWeight = 1.0;
    double boundaryEntropyWeight = 1.0;
    double informationEntropyWeight = 1.0;
};

// Throws MetricError naming the first field out of its stated range.
void validateParameters(const MetricParameters& parameters);

// One entropy component: raw values of both images and the fidelity derived from them.
struct EntropyComponent {
    bool computed = false;  // false when its weight is 0 (then all values are 0)
    double candidate = 0;   // bits; Histogram mode [0, log2 bins], Paper mode see docs
    double reference = 0;
    double fidelity = 0;    // [0, 1]
};

struct MetricResult {
    bool ssimComputed = false;
    double ssim = 0;          // mean SSIM of candidate vs reference, [-1, 1]
    double ssimFidelity = 0;  // ssim clamped to [0, 1]
    EntropyComponent boundaryEntropy;
    EntropyComponent informationEntropy;
    bool precisionRecallComputed = false;
    std::uint64_t truePositives = 0;   // covered in both and matching
    std::uint64_t falsePositives = 0;  // covered in the candidate, not matching
    std::uint64_t falseNegatives = 0;  // covered in the reference, not matching
    double precision = 0;              // TP / (TP + FP), 1 when both are 0; [0, 1]
    double recall = 0;                 // TP / (TP + FN), 1 when both are 0; [0, 1]
    double fitness = 0;                // weighted mean of the computed fidelities, [0, 1]
};

// --- SSIM -------------------------------------------------------------------------------

// Size of the SSIM map of a width x height image: one value per valid window position.
struct SsimMapSize {
    int width = 0;   // image width - window + 1, >= 1
    int height = 0;  // image height - window + 1, >= 1
    int window = 0;  // effective window side (odd); map (x, y) is the window centred on
                     // image pixel (x + window / 2, y + window / 2)
};
SsimMapSize ssimMapSize(int width, int height, const MetricParameters& parameters);

// Per-window SSIM of `candidate` against `reference` (same size and channel count) into
// `map` (ssimMapSize(...).width columns and .height rows, `mapStride` doubles apart), each in
// [-1, 1] (rounding beyond it is clamped).
void ssimMap(const ImageView& candidate, const ImageView& reference, const MetricParameters& parameters,
             double* map, std::size_t mapStride);

// Mean of an SSIM map (values in [-1, 1]) as every function here pools it: each value in
// fixed point (the integer nearest to v * 2^40), summed exactly, so any partition of the map
// pools to the same bits; the mean moves by at most 2^-41 from an exact sum of the doubles.
double poolMean(const double* map, int width, int height, std::size_t mapStride);

// Mean SSIM, [-1, 1]: ssimMap then poolMean.
double ssim(const ImageView& candidate, const ImageView& reference, const MetricParameters& parameters);

// --- Entropies ----------------------------------------------------------------------------

// Boundary entropy of one image in bits (parameters.boundaryEntropyMode).
double boundaryEntropy(const ImageView& image, const MetricParameters& parameters);
// Information entropy of one image in bits (parameters.informationEntropyMode).
double informationEntropy(const ImageView& image, const MetricParameters& parameters);
// 1 - |candidate - reference| / max(|reference|, epsilon), clamped to [0, 1]; epsilon > 0.
double entropyFidelity(double candidate, double reference, double epsilon);

// --- Precision / recall -------------------------------------------------------------------

struct PrecisionRecall {
    std::uint64_t truePositives = 0;
    std::uint64_t falsePositives = 0;
    std::uint64_t falseNegatives = 0;
    double precision = 1;  // [0, 1], 1 when nothing is covered in the candidate
    double recall = 1;     // [0, 1], 1 when nothing is covered in the reference
};
PrecisionRecall precisionRecall(const ImageView& candidate, const ImageView& reference,
                                const MetricParameters& parameters);
// Precision and recall from counts (0 / 0 = 1).
PrecisionRecall precisionRecallFromCounts(std::uint64_t truePositives, std::uint64_t falsePositives,
                                          std::uint64_t falseNegatives);

// --- Fusion -------------------------------------------------------------------------------

// Every component with a positive weight, their fidelities and the fused fitness, computed
// from scratch. For repeated candidates of one reference use IncrementalEvaluator.
MetricResult evaluate(const ImageView& candidate, const ImageView& reference, const MetricParameters& parameters);

// Fills the fidelities and fitness of `result` from its raw values (used by evaluate and by
// IncrementalEvaluator, so both fuse identically).
void fuse(MetricResult& result, const MetricParameters& parameters);

}  // namespace lodopt::metrics
