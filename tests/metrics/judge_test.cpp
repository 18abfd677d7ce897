// The judge (metrics/judge.hpp): butteraugli through libjxl.
#include "metrics/judge.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_images.hpp"

namespace {

using lodopt::metrics::ImageView;
using lodopt::metrics::judge;
using lodopt::metrics::JudgeParameters;
using lodopt::metrics::JudgeResult;
using lodopt::metrics::MetricError;
using lodopt::metrics::testing::generateScene;
using lodopt::metrics::testing::hash32;
using lodopt::metrics::testing::TestImage;

// `image` with every covered channel moved by up to +-amplitude (deterministic noise).
TestImage withNoise(const TestImage& image, int amplitude, std::uint32_t seed) {
    TestImage noisy = image;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < std::min(image.channels, 3); ++c) {
                const int offset = int(hash32(x, y, c, seed) % (2 * amplitude + 1)) - amplitude;
                noisy.at(x, y)[c] = std::uint8_t(std::clamp(int(image.at(x, y)[c]) + offset, 0, 255));
            }
        }
    }
    return noisy;
}

TEST(Judge, IdenticalImagesAreZeroApart) {
    const TestImage image = generateScene(96, 64, 3, 5, 0);
    const JudgeResult result = judge(image.view(), image.view());
    EXPECT_EQ(result.distance, 0.0);
    EXPECT_EQ(result.maxDistance, 0.0);
    EXPECT_TRUE(result.distanceMap.empty());
}

TEST(Judge, DistanceGrowsWithTheDistortion) {
    const TestImage reference = generateScene(96, 96, 3, 5, 0);
    double previous = 0.0;
    for (int amplitude : {2, 8, 32}) {
        const TestImage candidate = withNoise(reference, amplitude, 11);
        const JudgeResult result = judge(candidate.view(), reference.view());
        EXPECT_GT(result.distance, previous) << "noise amplitude " << amplitude;
        EXPECT_GE(result.maxDistance, result.distance);
        previous = result.distance;
    }
    // A moved object is a visible difference: more than one just-noticeable difference.
    const TestImage moved = generateScene(96, 96, 3, 5, 6);
    EXPECT_GT(judge(moved.view(), reference.view()).maxDistance, 1.0);
}

TEST(Judge, DistanceMapMarksWhereTheImagesDiffer) {
    const TestImage reference(64, 64, 4, 128);
    TestImage candidate = reference;
    for (int y = 40; y < 56; ++y) {
        for (int x = 40; x < 56; ++x) candidate.at(x, y)[0] = 240;  // a red patch bottom right
    }
    JudgeParameters parameters;
    parameters.keepDistanceMap = true;
    const JudgeResult result = judge(candidate.view(), reference.view(), parameters);
    ASSERT_EQ(result.distanceMap.size(), 64u * 64u);
    EXPECT_GT(result.distanceMap[48 * 64 + 48], 10.0f * result.distanceMap[8 * 64 + 8]);
    float largest = 0.0f;
    for (float value : result.distanceMap) largest = std::max(largest, value);
    EXPECT_NEAR(largest, result.maxDistance, 1e-4 * result.maxDistance);
}

TEST(Judge, AlphaIsIgnoredAndGrayIsJudgedAsGray) {
    const TestImage rgb = generateScene(48, 48, 3, 1, 0), rgbMoved = generateScene(48, 48, 3, 1, 3);
    const TestImage rgba = generateScene(48, 48, 4, 1, 0), rgbaMoved = generateScene(48, 48, 4, 1, 3);
    TestImage rgbaOtherAlpha = rgbaMoved;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 48; ++x) rgbaOtherAlpha.at(x, y)[3] = 7;
    }
    const double rgbDistance = judge(rgbMoved.view(), rgb.view()).distance;
    EXPECT_EQ(judge(rgbaMoved.view(), rgba.view()).distance, rgbDistance);
    EXPECT_EQ(judge(rgbaOtherAlpha.view(), rgba.view()).distance, rgbDistance);
    TestImage gray(48, 48, 1, 100), grayOther(48, 48, 1, 100);
    for (int x = 10; x < 30; ++x) grayOther.at(x, 20)[0] = 200;
    EXPECT_GT(judge(grayOther.view(), gray.view()).distance, 0.0);
}

// libjxl answers 0 for any image with a side under 8 pixels; the judge enlarges such images.
TEST(Judge, ImagesUnderEightPixelsAreStillJudged) {
    for (auto [width, height] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{7, 16}, std::pair{1, 300}}) {
        TestImage a(width, height, 3, 40), b(width, height, 3, 40);
        b.at(0, 0)[0] = 220;
        const JudgeResult different = judge(b.view(), a.view());
        EXPECT_GT(different.distance, 0.5) << width << "x" << height;
        EXPECT_EQ(judge(a.view(), a.view()).distance, 0.0) << width << "x" << height;
    }
}

TEST(Judge, ViewingConditionsChangeTheDistance) {
    const TestImage reference = generateScene(64, 64, 3, 2, 0);
    const TestImage candidate = withNoise(reference, 6, 3);
    const double base = judge(candidate.view(), reference.view()).distance;
    JudgeParameters brighter;
    brighter.intensityTargetNits = 400.0;
    EXPECT_NE(judge(candidate.view(), reference.view(), brighter).distance, base);
    JudgeParameters enlarged;
    enlarged.displayScale = 2;  // pixel noise seen twice as large: finer noise than the eye resolves no longer
    const JudgeResult larger = judge(candidate.view(), reference.view(), enlarged);
    EXPECT_NE(larger.distance, base);
    EXPECT_EQ(larger.width, 64);
}

TEST(Judge, RefusesImagesItCannotCompare) {
    const TestImage a(32, 32, 3), b(32, 16, 3), c(32, 32, 4);
    EXPECT_THROW(judge(a.view(), b.view()), MetricError);
    EXPECT_THROW(judge(a.view(), c.view()), MetricError);
    ImageView empty;
    EXPECT_THROW(judge(empty, a.view()), MetricError);
    for (auto bad : {0.0, -1.0, std::nan("")}) {
        JudgeParameters parameters;
        parameters.intensityTargetNits = bad;
        EXPECT_THROW(judge(a.view(), a.view(), parameters), MetricError);
    }
    JudgeParameters lowNorm;
    lowNorm.pnorm = 0.5;
    EXPECT_THROW(judge(a.view(), a.view(), lowNorm), MetricError);
    JudgeParameters scale;
    scale.displayScale = 0;
    EXPECT_THROW(judge(a.view(), a.view(), scale), MetricError);
}

}  // namespace
