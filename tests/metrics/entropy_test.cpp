// Boundary and information entropy on images whose entropy can be worked out by hand, and
// their invariances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "metrics/metrics.hpp"
#include "test_images.hpp"

namespace lodopt::metrics {
namespace {

using testing::generateNoise;
using testing::generateScene;
using testing::TestImage;

double binaryEntropy(double p) { return -p * std::log2(p) - (1 - p) * std::log2(1 - p); }

TEST(InformationEntropy, HandMadeHistograms) {
    MetricParameters p;
    EXPECT_EQ(informationEntropy(TestImage(7, 5, 3, 90).view(), p), 0.0);  // one level
    TestImage halves(8, 4, 1, 0);
    for (int y = 0; y < 4; ++y) std::fill_n(halves.at(4, y), 4, std::uint8_t(255));
    EXPECT_DOUBLE_EQ(informationEntropy(halves.view(), p), 1.0);
    TestImage ramp(256, 3, 1);  // every gray level equally often: 8 bits
    for (int y = 0; y < 3; ++y) {
        for (int x = 0; x < 256; ++x) ramp.at(x, y)[0] = std::uint8_t(x);
    }
    EXPECT_NEAR(informationEntropy(ramp.view(), p), 8.0, 1e-12);
    // Color: (100, 0, 0) -> gray 30 and (0, 100, 0) -> 59: two levels, one quarter / three quarters.
    TestImage color(4, 1, 3, 0);
    color.at(0, 0)[0] = 100;
    for (int x = 1; x < 4; ++x) color.at(x, 0)[1] = 100;
    EXPECT_NEAR(informationEntropy(color.view(), p), binaryEntropy(0.25), 1e-15);
}

TEST(InformationEntropy, RoundsGrayHalfUp) {
    // (1, 0, 0) has paper gray 0.30 -> level 0; (5, 0, 0) has 1.50 -> level 2 (half up).
    TestImage image(2, 1, 3, 0);
    image.at(0, 0)[0] = 5;  // 1.50 -> 2
    image.at(1, 0)[0] = 7;  // 2.10 -> 2
    EXPECT_EQ(informationEntropy(image.view(), {}), 0.0);  // both in level 2
    image.at(1, 0)[0] = 4;  // 1.20 -> 1
    EXPECT_DOUBLE_EQ(informationEntropy(image.view(), {}), 1.0);
}

TEST(InformationEntropy, InvariantToPixelPermutation) {
    const TestImage image = generateScene(45, 38, 3, 1, 0);
    std::vector<int> order(45 * 38);
    std::iota(order.begin(), order.end(), 0);
    std::mt19937 rng(5);
    std::shuffle(order.begin(), order.end(), rng);
    TestImage shuffled(45, 38, 3);
    for (std::size_t i = 0; i < order.size(); ++i) {
        std::copy_n(image.pixels.data() + std::size_t(order[i]) * 3, 3, shuffled.pixels.data() + i * 3);
    }
    MetricParameters p;
    EXPECT_EQ(informationEntropy(shuffled.view(), p), informationEntropy(image.view(), p));
    p.informationEntropyMode = EntropyMode::Paper;
    EXPECT_NEAR(informationEntropy(shuffled.view(), p), informationEntropy(image.view(), p), 1e-12);
}

TEST(InformationEntropy, PaperFormIsIntensityShares) {
    MetricParameters p;
    p.informationEntropyMode = EntropyMode::Paper;
    TestImage two(2, 1, 1, 0);
    two.at(0, 0)[0] = 1;
    two.at(1, 0)[0] = 3;  // shares 1/4 and 3/4
    EXPECT_NEAR(informationEntropy(two.view(), p), binaryEntropy(0.25), 1e-14);
    EXPECT_EQ(informationEntropy(TestImage(9, 9, 3, 0).view(), p), 0.0);  // all black: no 0 / 0
    EXPECT_NEAR(informationEntropy(TestImage(8, 4, 3, 70).view(), p), 5.0, 1e-12);  // 32 equal shares
    TestImage single(5, 5, 1, 0);
    single.at(2, 2)[0] = 255;  // all intensity in one pixel
    EXPECT_EQ(informationEntropy(single.view(), p), 0.0);
}

TEST(BoundaryEntropy, StepEdge) {
    // 10x10, left half 0, right half 255: interior columns 4 and 5 see |gx| = 4 * 255, the
    // rest nothing. 16 of 64 interior pixels are edges.
    TestImage step(10, 10, 1, 0);
    for (int y = 0; y < 10; ++y) std::fill_n(step.at(5, y), 5, std::uint8_t(255));
    EXPECT_NEAR(boundaryEntropy(step.view(), {}), binaryEntropy(0.25), 1e-15);
    // No edges at all.
    EXPECT_EQ(boundaryEntropy(TestImage(10, 10, 3, 200).view(), {}), 0.0);
    // No interior pixels.
    EXPECT_EQ(boundaryEntropy(generateNoise(2, 50, 3, 1).view(), {}), 0.0);
}

TEST(BoundaryEntropy, StepEdgeFallsIntoTheExpectedBin) {
    // With 2 bins the boundary is at 255 sqrt(20) / 2 = 570.2: a 1020 step is in bin 1, a
    // 4 * 140 = 560 step in bin 0 (so the image looks edge-free).
    MetricParameters p;
    p.boundaryHistogramBins = 2;
    TestImage step(10, 10, 1, 0);
    for (int y = 0; y < 10; ++y) std::fill_n(step.at(5, y), 5, std::uint8_t(140));
    EXPECT_EQ(boundaryEntropy(step.view(), p), 0.0);
    for (int y = 0; y < 10; ++y) std::fill_n(step.at(5, y), 5, std::uint8_t(143));  // 572 > 570.2
    EXPECT_NEAR(boundaryEntropy(step.view(), p), binaryEntropy(0.25), 1e-15);
}

TEST(BoundaryEntropy, InvariantToMirrorsAndTransposition) {
    const TestImage image = generateScene(41, 33, 3, 1, 0);
    TestImage mirrored(41, 33, 3), flipped(41, 33, 3), transposed(33, 41, 3);
    for (int y = 0; y < 33; ++y) {
        for (int x = 0; x < 41; ++x) {
            std::copy_n(image.at(x, y), 3, mirrored.at(40 - x, y));
            std::copy_n(image.at(x, y), 3, flipped.at(x, 32 - y));
            std::copy_n(image.at(x, y), 3, transposed.at(y, x));
        }
    }
    const double value = boundaryEntropy(image.view(), {});
    EXPECT_GT(value, 0.5);
    EXPECT_EQ(boundaryEntropy(mirrored.view(), {}), value);
    EXPECT_EQ(boundaryEntropy(flipped.view(), {}), value);
    EXPECT_EQ(boundaryEntropy(transposed.view(), {}), value);
}

TEST(BoundaryEntropy, PaperFormIsTheRobertsCrossSum) {
    MetricParameters p;
    p.boundaryEntropyMode = EntropyMode::Paper;
    // [0 2]
    // [0 0]   one Roberts term: a = 0 - 0, b = 0 - 2, g = 2, -g log2 g = -2.
    TestImage image(2, 2, 1, 0);
    image.at(1, 0)[0] = 2;
    EXPECT_DOUBLE_EQ(boundaryEntropy(image.view(), p), -2.0);
    // (3, 0, 0) has paper gray 0.9: g = 0.9 < 1, so the term -0.9 log2 0.9 is positive.
    TestImage color(2, 2, 3, 0);
    color.at(0, 0)[0] = 3;
    EXPECT_NEAR(boundaryEntropy(color.view(), p), -0.9 * std::log2(0.9), 1e-15);
    EXPECT_EQ(boundaryEntropy(TestImage(1, 9, 3, 50).view(), p), 0.0);  // no 2x2 neighbourhood
}

TEST(BoundaryEntropy, RangeForAnyBinCount) {
    const TestImage noise = generateNoise(60, 40, 3, 9);
    for (int bins : {2, 3, 256, 1000, 65536}) {
        MetricParameters p;
        p.boundaryHistogramBins = bins;
        const double value = boundaryEntropy(noise.view(), p);
        EXPECT_GT(value, 0.0) << bins;
        EXPECT_LE(value, std::log2(double(bins))) << bins;
    }
}

TEST(EntropyFidelity, Definition) {
    EXPECT_EQ(entropyFidelity(3.0, 3.0, 1e-6), 1.0);
    EXPECT_EQ(entropyFidelity(0.0, 0.0, 1e-6), 1.0);
    EXPECT_EQ(entropyFidelity(0.5, 0.0, 1e-6), 0.0);  // anything against a constant reference
    EXPECT_DOUBLE_EQ(entropyFidelity(1.5, 2.0, 1e-6), 0.75);
    EXPECT_DOUBLE_EQ(entropyFidelity(2.5, 2.0, 1e-6), 0.75);
    EXPECT_EQ(entropyFidelity(5.0, 2.0, 1e-6), 0.0);  // clamped
    EXPECT_DOUBLE_EQ(entropyFidelity(-90.0, -100.0, 1e-6), 0.9);  // paper boundary form: |reference|
    EXPECT_EQ(entropyFidelity(std::nan(""), 2.0, 1e-6), 0.0);
}

}  // namespace
}  // namespace lodopt::metrics
