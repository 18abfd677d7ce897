// Pinned values from scripts/metrics_reference.py (scikit-image 0.19.3, scipy 1.10.1,
// numpy 1.24.2 on Debian 12), on images generated identically here and there.
//
// Tolerances: SSIM 1e-6 is the requirement (we observe ~1e-15: scikit-image filters
// in float64 too; only summation order differs). Entropies 1e-9: both sides are float64
// sums of the same terms in different orders. Counts are exact.
#include <gtest/gtest.h>

#include "metrics/metrics.hpp"
#include "metrics/reference.hpp"
#include "test_images.hpp"

namespace lodopt::metrics {
namespace {

using testing::generateNoise;
using testing::generateScene;
using testing::TestImage;

// Output of: /usr/bin/python3 scripts/metrics_reference.py
constexpr double kSceneSsimPaper = 0.7537395273613943;
constexpr double kSceneSsimBt601 = 0.7531088931877816;
constexpr double kSceneSsimBt709 = 0.7518136795455516;
constexpr double kSceneSsimSigma1 = 0.8022457679732637;
constexpr double kGraySsim = 0.6689150355537646;
constexpr double kNoiseSsim = -0.014864954589447098;
constexpr double kRgbaSsim = 0.4179163120258852;
constexpr double kSceneBoundaryReference = 2.2408004412034095;
constexpr double kSceneBoundaryCandidate = 2.1071782279417803;
constexpr double kSceneBoundary64Bins = 1.1076732757669707;
constexpr double kSceneBoundaryBt709 = 2.1438218139187266;
constexpr double kNoiseBoundary = 6.511129354653652;
constexpr double kGrayBoundary = 2.406799265571519;
constexpr double kSceneInformationReference = 2.203563034649889;
constexpr double kSceneInformationCandidate = 2.058000153072606;
constexpr double kSceneInformationBt601 = 2.057525005681837;
constexpr double kNoiseInformation = 7.4816535080543245;
constexpr double kGrayInformation = 2.174451690183306;
constexpr double kSceneBoundaryPaper = -131860.08584844045;
constexpr double kSceneInformationPaper = 11.54343764909715;
constexpr std::uint64_t kSceneCounts[3] = {629, 47, 104};
constexpr std::uint64_t kGrayCounts[3] = {408, 33, 88};
constexpr std::uint64_t kRgbaCounts[3] = {147, 27, 60};

constexpr double kSsimTolerance = 1e-6;
constexpr double kEntropyTolerance = 1e-9;

struct Images {
    TestImage ref = generateScene(64, 48, 3, 1, 0);
    TestImage cand = generateScene(64, 48, 3, 2, 2);
    TestImage grayRef = generateScene(50, 40, 1, 3, 0);
    TestImage grayCand = generateScene(50, 40, 1, 4, 2);
    TestImage noiseRef = generateNoise(40, 33, 3, 5);
    TestImage noiseCand = generateNoise(40, 33, 3, 6);
    TestImage rgbaRef = generateScene(31, 27, 4, 7, 0);
    TestImage rgbaCand = generateScene(31, 27, 4, 8, 2);
};

TEST(MetricsReferenceValues, GeneratorMatchesTheScript) {
    // Spot checks of the generator itself, printed by the script's scene(): background, box, disk.
    Images images;
    EXPECT_EQ(images.ref.at(0, 0)[0], 158);
    EXPECT_EQ(images.ref.at(0, 0)[2], 230);
    EXPECT_EQ(images.grayRef.at(0, 0)[0], 187);  // the paper's gray of the sky, rounded
    EXPECT_NE(images.ref.at(20, 20)[2], 230);    // inside the box
}

TEST(MetricsReferenceValues, SsimMatchesScikitImage) {
    Images images;
    MetricParameters p;
    EXPECT_NEAR(ssim(images.cand.view(), images.ref.view(), p), kSceneSsimPaper, kSsimTolerance);
    EXPECT_NEAR(ssim(images.grayCand.view(), images.grayRef.view(), p), kGraySsim, kSsimTolerance);
    EXPECT_NEAR(ssim(images.noiseCand.view(), images.noiseRef.view(), p), kNoiseSsim, kSsimTolerance);
    EXPECT_NEAR(ssim(images.rgbaCand.view(), images.rgbaRef.view(), p), kRgbaSsim, kSsimTolerance);
    p.grayWeights = GrayWeights::Bt601;
    EXPECT_NEAR(ssim(images.cand.view(), images.ref.view(), p), kSceneSsimBt601, kSsimTolerance);
    p.grayWeights = GrayWeights::Bt709;
    EXPECT_NEAR(ssim(images.cand.view(), images.ref.view(), p), kSceneSsimBt709, kSsimTolerance);
}

TEST(MetricsReferenceValues, SsimOtherWindowMatchesScikitImage) {
    // scikit-image with sigma 1.0 truncates at 3.5 sigma: a 9x9 window (the generic path).
    Images images;
    MetricParameters p;
    p.ssimSigma = 1.0;
    p.ssimWindow = 9;
    EXPECT_NEAR(ssim(images.cand.view(), images.ref.view(), p), kSceneSsimSigma1, kSsimTolerance);
}

TEST(MetricsReferenceValues, SsimMatchesScikitImageToFloat64Rounding) {
    // Not required by the issue, but it shows the computation is the same, not just close.
    Images images;
    EXPECT_NEAR(ssim(images.cand.view(), images.ref.view(), {}), kSceneSsimPaper, 1e-13);
}

TEST(MetricsReferenceValues, BoundaryEntropyMatchesScript) {
    Images images;
    MetricParameters p;
    EXPECT_NEAR(boundaryEntropy(images.ref.view(), p), kSceneBoundaryReference, kEntropyTolerance);
    EXPECT_NEAR(boundaryEntropy(images.cand.view(), p), kSceneBoundaryCandidate, kEntropyTolerance);
    EXPECT_NEAR(boundaryEntropy(images.noiseRef.view(), p), kNoiseBoundary, kEntropyTolerance);
    EXPECT_NEAR(boundaryEntropy(images.grayRef.view(), p), kGrayBoundary, kEntropyTolerance);
    p.boundaryHistogramBins = 64;
    EXPECT_NEAR(boundaryEntropy(images.cand.view(), p), kSceneBoundary64Bins, kEntropyTolerance);
    p.boundaryHistogramBins = 256;
    p.grayWeights = GrayWeights::Bt709;
    EXPECT_NEAR(boundaryEntropy(images.cand.view(), p), kSceneBoundaryBt709, kEntropyTolerance);
}

TEST(MetricsReferenceValues, InformationEntropyMatchesScikitImageShannonEntropy) {
    Images images;
    MetricParameters p;
    EXPECT_NEAR(informationEntropy(images.ref.view(), p), kSceneInformationReference, kEntropyTolerance);
    EXPECT_NEAR(informationEntropy(images.cand.view(), p), kSceneInformationCandidate, kEntropyTolerance);
    EXPECT_NEAR(informationEntropy(images.noiseRef.view(), p), kNoiseInformation, kEntropyTolerance);
    EXPECT_NEAR(informationEntropy(images.grayRef.view(), p), kGrayInformation, kEntropyTolerance);
    p.grayWeights = GrayWeights::Bt601;
    EXPECT_NEAR(informationEntropy(images.cand.view(), p), kSceneInformationBt601, kEntropyTolerance);
}

// The float64 references (metrics/reference.hpp) that `lodopt bench` and bench/metrics_bench
// measure the metrics against agree with scikit-image and the script too, at the defaults.
TEST(MetricsReferenceValues, Float64ReferencesMatchScikitImageAndTheScript) {
    Images images;
    EXPECT_NEAR(reference::ssim(images.cand.view(), images.ref.view()), kSceneSsimPaper, kSsimTolerance);
    EXPECT_NEAR(reference::ssim(images.grayCand.view(), images.grayRef.view()), kGraySsim, kSsimTolerance);
    EXPECT_NEAR(reference::ssim(images.noiseCand.view(), images.noiseRef.view()), kNoiseSsim, kSsimTolerance);
    EXPECT_NEAR(reference::ssim(images.rgbaCand.view(), images.rgbaRef.view()), kRgbaSsim, kSsimTolerance);
    EXPECT_NEAR(reference::boundaryEntropy(images.ref.view()), kSceneBoundaryReference, kEntropyTolerance);
    EXPECT_NEAR(reference::boundaryEntropy(images.cand.view()), kSceneBoundaryCandidate, kEntropyTolerance);
    EXPECT_NEAR(reference::boundaryEntropy(images.noiseRef.view()), kNoiseBoundary, kEntropyTolerance);
    EXPECT_NEAR(reference::boundaryEntropy(images.grayRef.view()), kGrayBoundary, kEntropyTolerance);
    EXPECT_NEAR(reference::informationEntropy(images.ref.view()), kSceneInformationReference, kEntropyTolerance);
    EXPECT_NEAR(reference::informationEntropy(images.cand.view()), kSceneInformationCandidate, kEntropyTolerance);
    EXPECT_NEAR(reference::informationEntropy(images.noiseRef.view()), kNoiseInformation, kEntropyTolerance);
    EXPECT_NEAR(reference::informationEntropy(images.grayRef.view()), kGrayInformation, kEntropyTolerance);
    // The fused reference is the metrics' fused fitness at equal weights.
    EXPECT_NEAR(reference::fitness(images.cand.view(), images.ref.view()),
                evaluate(images.cand.view(), images.ref.view(), {}).fitness, kSsimTolerance);
    EXPECT_THROW(reference::ssim(images.cand.view(), images.grayRef.view()), std::invalid_argument);
}

TEST(MetricsReferenceValues, PaperModesMatchScript) {
    Images images;
    MetricParameters p;
    p.boundaryEntropyMode = EntropyMode::Paper;
    p.informationEntropyMode = EntropyMode::Paper;
    // The literal boundary form is a large negative sum: compare relatively.
    EXPECT_NEAR(boundaryEntropy(images.ref.view(), p), kSceneBoundaryPaper, 1e-9 * std::abs(kSceneBoundaryPaper));
    EXPECT_NEAR(informationEntropy(images.ref.view(), p), kSceneInformationPaper, kEntropyTolerance);
}

TEST(MetricsReferenceValues, PrecisionRecallCountsMatchScript) {
    Images images;
    MetricParameters p;
    const struct {
        const TestImage& cand;
        const TestImage& ref;
        const std::uint64_t* counts;
    } cases[] = {{images.cand, images.ref, kSceneCounts},
                 {images.grayCand, images.grayRef, kGrayCounts},
                 {images.rgbaCand, images.rgbaRef, kRgbaCounts}};
    for (const auto& c : cases) {
        const PrecisionRecall pr = precisionRecall(c.cand.view(), c.ref.view(), p);
        EXPECT_EQ(pr.truePositives, c.counts[0]);
        EXPECT_EQ(pr.falsePositives, c.counts[1]);
        EXPECT_EQ(pr.falseNegatives, c.counts[2]);
        EXPECT_DOUBLE_EQ(pr.precision, double(c.counts[0]) / double(c.counts[0] + c.counts[1]));
        EXPECT_DOUBLE_EQ(pr.recall, double(c.counts[0]) / double(c.counts[0] + c.counts[2]));
    }
}

}  // namespace
}  // namespace lodopt::metrics
