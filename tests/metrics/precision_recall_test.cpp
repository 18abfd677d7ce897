// Precision and recall on a hand-drawn fixture.
#include <gtest/gtest.h>

#include "metrics/metrics.hpp"
#include "test_images.hpp"

namespace lodopt::metrics {
namespace {

using testing::kBackground;
using testing::TestImage;

void paint(TestImage& image, int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
    image.at(x, y)[0] = r;
    image.at(x, y)[1] = g;
    image.at(x, y)[2] = b;
}

TestImage sky(int width, int height, int channels) {
    TestImage image(width, height, channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) std::copy_n(kBackground, channels, image.at(x, y));
    }
    return image;
}

// candidate     reference      . background   A (10,20,30)   B (14,20,30): A within 8
// . A A .       . A B .        C (100,100,100)  D (50,50,50)
// . . C .       . A . .        E (200,0,0)      F (0,0,200)
// E . . .       F . . D
// (1,0) A/A TP, (2,0) A/B TP, (2,1) C/. FP, (1,1) ./A FN, (3,2) ./D FN, (0,2) E/F FP and FN.
struct Fixture {
    TestImage candidate = sky(4, 3, 3), reference = sky(4, 3, 3);
    Fixture() {
        paint(candidate, 1, 0, 10, 20, 30);
        paint(candidate, 2, 0, 10, 20, 30);
        paint(candidate, 2, 1, 100, 100, 100);
        paint(candidate, 0, 2, 200, 0, 0);
        paint(reference, 1, 0, 10, 20, 30);
        paint(reference, 2, 0, 14, 20, 30);
        paint(reference, 1, 1, 10, 20, 30);
        paint(reference, 3, 2, 50, 50, 50);
        paint(reference, 0, 2, 0, 0, 200);
    }
};

TEST(PrecisionRecall, HandDrawnFixture) {
    Fixture f;
    const PrecisionRecall pr = precisionRecall(f.candidate.view(), f.reference.view(), {});
    EXPECT_EQ(pr.truePositives, 2u);
    EXPECT_EQ(pr.falsePositives, 2u);
    EXPECT_EQ(pr.falseNegatives, 3u);
    EXPECT_DOUBLE_EQ(pr.precision, 2.0 / 4.0);
    EXPECT_DOUBLE_EQ(pr.recall, 2.0 / 5.0);
}

TEST(PrecisionRecall, ToleranceZeroSplitsNearMatches) {
    Fixture f;
    MetricParameters p;
    p.matchTolerance = 0;  // (2,0) A/B is now covered in both but different: FP and FN
    const PrecisionRecall pr = precisionRecall(f.candidate.view(), f.reference.view(), p);
    EXPECT_EQ(pr.truePositives, 1u);
    EXPECT_EQ(pr.falsePositives, 3u);
    EXPECT_EQ(pr.falseNegatives, 4u);
    p.matchTolerance = 3;  // 4 > 3: still different
    EXPECT_EQ(precisionRecall(f.candidate.view(), f.reference.view(), p).truePositives, 1u);
    p.matchTolerance = 4;  // 4 <= 4: equal
    EXPECT_EQ(precisionRecall(f.candidate.view(), f.reference.view(), p).truePositives, 2u);
}

TEST(PrecisionRecall, NothingCoveredIsPerfect) {
    const TestImage empty = sky(5, 5, 3);
    const PrecisionRecall pr = precisionRecall(empty.view(), empty.view(), {});
    EXPECT_EQ(pr.truePositives + pr.falsePositives + pr.falseNegatives, 0u);
    EXPECT_EQ(pr.precision, 1.0);
    EXPECT_EQ(pr.recall, 1.0);
    // Candidate empty, reference covered: precision 1 (nothing wrong drawn), recall 0.
    Fixture f;
    const TestImage nothing = sky(4, 3, 3);
    const PrecisionRecall missing = precisionRecall(nothing.view(), f.reference.view(), {});
    EXPECT_EQ(missing.precision, 1.0);
    EXPECT_EQ(missing.recall, 0.0);
}

TEST(PrecisionRecall, BackgroundParameterAndAlpha) {
    // RGBA: alpha takes part. A pixel that differs from the background only in alpha is covered.
    TestImage candidate = sky(3, 1, 4), reference = sky(3, 1, 4);
    candidate.at(0, 0)[3] = 0;
    const PrecisionRecall pr = precisionRecall(candidate.view(), reference.view(), {});
    EXPECT_EQ(pr.falsePositives, 1u);
    // Another background color: now every pixel is covered, and all match.
    MetricParameters black;
    black.background = {0, 0, 0, 255};
    const PrecisionRecall all = precisionRecall(reference.view(), reference.view(), black);
    EXPECT_EQ(all.truePositives, 3u);
}

TEST(PrecisionRecall, GrayImagesUseTheBackgroundsGray) {
    // Paper gray of the background: 0.30*158 + 0.59*194 + 0.11*230 = 187.16, rounded 187.
    TestImage candidate(3, 1, 1, 187), reference(3, 1, 1, 187);
    candidate.at(1, 0)[0] = 188;
    reference.at(2, 0)[0] = 0;
    const PrecisionRecall pr = precisionRecall(candidate.view(), reference.view(), {});
    EXPECT_EQ(pr.truePositives, 0u);
    EXPECT_EQ(pr.falsePositives, 1u);
    EXPECT_EQ(pr.falseNegatives, 1u);
}

TEST(PrecisionRecall, FromCounts) {
    const PrecisionRecall pr = precisionRecallFromCounts(3, 1, 0);
    EXPECT_DOUBLE_EQ(pr.precision, 0.75);
    EXPECT_EQ(pr.recall, 1.0);
    EXPECT_EQ(precisionRecallFromCounts(0, 0, 0).precision, 1.0);
    EXPECT_EQ(precisionRecallFromCounts(0, 5, 5).recall, 0.0);
}

TEST(PrecisionRecall, WideRowsCrossTheChunkBoundary) {
    // Rows longer than the 64-pixel processing chunk: one TP every 7th pixel.
    TestImage candidate = sky(150, 2, 3), reference = sky(150, 2, 3);
    std::uint64_t expected = 0;
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 150; x += 7, ++expected) {
            paint(candidate, x, y, 1, 2, 3);
            paint(reference, x, y, 1, 2, 3);
        }
    }
    const PrecisionRecall pr = precisionRecall(candidate.view(), reference.view(), {});
    EXPECT_EQ(pr.truePositives, expected);
    EXPECT_EQ(pr.falsePositives, 0u);
}

}  // namespace
}  // namespace lodopt::metrics
