// Numerical stability: a battery of degenerate, extreme and tiny images through every mode,
// both evaluation paths; nothing is ever NaN or outside its documented range, identical
// images give exactly 1, bad input is rejected with a message.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "metrics/incremental_evaluator.hpp"
#include "metrics/metrics.hpp"
#include "test_images.hpp"

namespace lodopt::metrics {
namespace {

using testing::generateNoise;
using testing::generateScene;
using testing::TestImage;

void expectInRange(const MetricResult& r, const MetricParameters& p, std::uint64_t pixels, const std::string& what) {
    SCOPED_TRACE(what);
    for (double v : {r.ssim, r.ssimFidelity, r.boundaryEntropy.candidate, r.boundaryEntropy.reference,
                     r.boundaryEntropy.fidelity, r.informationEntropy.candidate, r.informationEntropy.reference,
                     r.informationEntropy.fidelity, r.precision, r.recall, r.fitness}) {
        EXPECT_TRUE(std::isfinite(v));
    }
    EXPECT_GE(r.ssim, -1.0);
    EXPECT_LE(r.ssim, 1.0);
    for (double v : {r.ssimFidelity, r.boundaryEntropy.fidelity, r.informationEntropy.fidelity, r.precision, r.recall,
                     r.fitness}) {
        EXPECT_GE(v, 0.0);
        EXPECT_LE(v, 1.0);
    }
    if (p.boundaryEntropyMode == EntropyMode::Histogram) {
        for (double e : {r.boundaryEntropy.candidate, r.boundaryEntropy.reference}) {
            EXPECT_GE(e, 0.0);
            EXPECT_LE(e, std::log2(double(p.boundaryHistogramBins)));
        }
    }
    const double informationMax = p.informationEntropyMode == EntropyMode::Histogram ? 8.0 : std::log2(double(pixels));
    for (double e : {r.informationEntropy.candidate, r.informationEntropy.reference}) {
        EXPECT_GE(e, 0.0);
        EXPECT_LE(e, informationMax);
    }
}

void expectAllOne(const MetricResult& r, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(r.ssim, r.ssimComputed ? 1.0 : 0.0);
    EXPECT_EQ(r.ssimFidelity, r.ssimComputed ? 1.0 : 0.0);
    EXPECT_EQ(r.boundaryEntropy.fidelity, r.boundaryEntropy.computed ? 1.0 : 0.0);
    EXPECT_EQ(r.informationEntropy.fidelity, r.informationEntropy.computed ? 1.0 : 0.0);
    EXPECT_EQ(r.precision, 1.0);
    EXPECT_EQ(r.recall, 1.0);
    EXPECT_EQ(r.fitness, 1.0);
}

TestImage checkerboard(int width, int height, int channels, int cell) {
    TestImage image(width, height, channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            std::fill_n(image.at(x, y), channels, ((x / cell + y / cell) % 2) ? 255 : 0);
        }
    }
    return image;
}

std::vector<std::pair<std::string, TestImage>> battery(int width, int height, int channels) {
    std::vector<std::pair<std::string, TestImage>> images;
    images.emplace_back("black", TestImage(width, height, channels, 0));
    images.emplace_back("white", TestImage(width, height, channels, 255));
    images.emplace_back("mid gray", TestImage(width, height, channels, 128));
    images.emplace_back("checkerboard", checkerboard(width, height, channels, 1));
    images.emplace_back("coarse checkerboard", checkerboard(width, height, channels, 4));
    images.emplace_back("noise", generateNoise(width, height, channels, 17));
    images.emplace_back("scene", generateScene(width, height, channels, 3, 0));
    return images;
}

std::vector<MetricParameters> parameterSets() {
    std::vector<MetricParameters> sets(4);
    sets[1].boundaryEntropyMode = EntropyMode::Paper;
    sets[1].informationEntropyMode = EntropyMode::Paper;
    sets[2].grayWeights = GrayWeights::Bt709;
    sets[2].boundaryHistogramBins = 2;
    sets[2].matchTolerance = 255;
    sets[3].grayWeights = GrayWeights::Bt601;
    sets[3].ssimWindow = 3;
    sets[3].ssimSigma = 0.5;
    sets[3].ssimWeight = 0.1;
    sets[3].informationEntropyWeight = 0;
    return sets;
}

TEST(MetricStability, EveryPairOfDegenerateImagesStaysInRange) {
    const std::pair<int, int> sizes[] = {{1, 1}, {1, 2}, {2, 1}, {2, 2}, {3, 3}, {10, 10}, {11, 11}, {12, 11}, {40, 23}};
    for (auto [width, height] : sizes) {
        for (int channels : {1, 3, 4}) {
            const auto images = battery(width, height, channels);
            for (const MetricParameters& p : parameterSets()) {
                for (const auto& [nameA, a] : images) {
                    IncrementalEvaluator evaluator(a.view(), p);
                    const std::string size = std::to_string(width) + "x" + std::to_string(height) + "x" +
                                             std::to_string(channels) + " ";
                    expectAllOne(evaluate(a.view(), a.view(), p), size + nameA + " vs itself");
                    expectAllOne(evaluator.result(), size + nameA + " vs itself, evaluator");
                    for (const auto& [nameB, b] : images) {
                        const std::string what = size + nameB + " vs " + nameA;
                        const MetricResult oneShot = evaluate(b.view(), a.view(), p);
                        expectInRange(oneShot, p, std::uint64_t(width) * height, what);
                        evaluator.setCandidate(b.view());
                        const MetricResult incremental = evaluator.result();
                        expectInRange(incremental, p, std::uint64_t(width) * height, what + ", evaluator");
                        EXPECT_EQ(incremental.fitness, oneShot.fitness) << what;
                    }
                }
            }
        }
    }
}

TEST(MetricStability, LargeImage4096) {
    // 4096 x 4096 RGB, one-shot path (the evaluator would hold ~0.7 GB): in range, and
    // identical images still give exactly 1.
    const TestImage reference = generateScene(4096, 4096, 3, 1, 0);
    TestImage candidate = reference;
    std::mt19937 rng(4);
    testing::scribble(candidate, 1000, 1200, 1900, 2100, rng);
    const MetricParameters p;
    const MetricResult same = evaluate(reference.view(), reference.view(), p);
    expectAllOne(same, "4096 identical");
    const MetricResult different = evaluate(candidate.view(), reference.view(), p);
    expectInRange(different, p, 4096ull * 4096, "4096 different");
    EXPECT_LT(different.ssim, 1.0);
    EXPECT_GT(different.ssim, 0.9);  // 5% of the area changed
}

TEST(MetricStability, FloatImagesWithNanOrInfinityAreRejected) {
    std::vector<float> pixels(5 * 4 * 3, 0.5f);
    FloatImageView view{pixels.data(), 5, 4, 3, 15};
    std::vector<std::uint8_t> storage;
    const ImageView converted = convertFloatImage(view, storage);
    EXPECT_EQ(converted.pixels[0], 128);  // round(127.5) half up
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                      -std::numeric_limits<float>::infinity()}) {
        pixels[std::size_t(2 * 15 + 3 * 3 + 1)] = bad;  // pixel (3, 2), channel 1
        try {
            convertFloatImage(view, storage);
            ADD_FAILURE() << "accepted " << bad;
        } catch (const MetricError& error) {
            EXPECT_NE(std::string(error.what()).find("pixel (3, 2) channel 1"), std::string::npos) << error.what();
        }
    }
}

TEST(MetricStability, FloatImagesOutsideTheRangeAreClamped) {
    const float values[] = {-3.0f, 0.0f, 0.002f, 0.998f, 1.0f, 7.5f, 1e30f, -1e-30f};
    FloatImageView view{values, 8, 1, 1, 8};
    std::vector<std::uint8_t> storage;
    const ImageView converted = convertFloatImage(view, storage);
    const std::uint8_t expected[] = {0, 0, 1, 254, 255, 255, 255, 0};
    for (int i = 0; i < 8; ++i) EXPECT_EQ(converted.pixels[i], expected[i]) << values[i];
    FloatImageView bad = view;
    bad.channels = 2;
    EXPECT_THROW(convertFloatImage(bad, storage), MetricError);
}

TEST(MetricStability, InvalidParametersAreRejectedByName) {
    const TestImage image = generateScene(20, 20, 3, 1, 0);
    const std::pair<const char*, void (*)(MetricParameters&)> cases[] = {
        {"ssimWindow", [](MetricParameters& p) { p.ssimWindow = 10; }},
        {"ssimWindow", [](MetricParameters& p) { p.ssimWindow = 65; }},
        {"ssimSigma", [](MetricParameters& p) { p.ssimSigma = 0; }},
        {"ssimSigma", [](MetricParameters& p) { p.ssimSigma = std::nan(""); }},
        {"ssimK1", [](MetricParameters& p) { p.ssimK1 = -0.01; }},
        {"ssimK2", [](MetricParameters& p) { p.ssimK2 = std::numeric_limits<double>::infinity(); }},
        {"ssimDynamicRange", [](MetricParameters& p) { p.ssimDynamicRange = 0; }},
        {"boundaryHistogramBins", [](MetricParameters& p) { p.boundaryHistogramBins = 1; }},
        {"boundaryHistogramBins", [](MetricParameters& p) { p.boundaryHistogramBins = 65537; }},
        {"entropyEpsilon", [](MetricParameters& p) { p.entropyEpsilon = 0; }},
        {"matchTolerance", [](MetricParameters& p) { p.matchTolerance = 256; }},
        {"ssimWeight", [](MetricParameters& p) { p.ssimWeight = -1; }},
        {"informationEntropyWeight", [](MetricParameters& p) { p.informationEntropyWeight = std::nan(""); }},
        {"at least one", [](MetricParameters& p) { p.ssimWeight = p.boundaryEntropyWeight = p.informationEntropyWeight = 0; }},
        {"grayWeights", [](MetricParameters& p) { p.grayWeights = GrayWeights(7); }},
    };
    for (const auto& [name, change] : cases) {
        MetricParameters p;
        change(p);
        try {
            evaluate(image.view(), image.view(), p);
            ADD_FAILURE() << name << " accepted";
        } catch (const MetricError& error) {
            EXPECT_NE(std::string(error.what()).find(name), std::string::npos) << error.what();
        }
        EXPECT_THROW(IncrementalEvaluator(image.view(), p), MetricError) << name;
    }
}

TEST(MetricStability, InvalidImagesAreRejected) {
    const TestImage image = generateScene(20, 20, 3, 1, 0);
    const TestImage other = generateScene(21, 20, 3, 1, 0);
    const TestImage rgba = generateScene(20, 20, 4, 1, 0);
    EXPECT_THROW(evaluate(image.view(), other.view(), {}), MetricError);
    EXPECT_THROW(ssim(image.view(), rgba.view(), {}), MetricError);
    ImageView broken = image.view();
    broken.channels = 2;
    EXPECT_THROW(boundaryEntropy(broken, {}), MetricError);
    broken = image.view();
    broken.rowStride = 59;
    EXPECT_THROW(informationEntropy(broken, {}), MetricError);
    broken = image.view();
    broken.pixels = nullptr;
    EXPECT_THROW(precisionRecall(broken, image.view(), {}), MetricError);
    broken = image.view();
    broken.width = 0;
    EXPECT_THROW(IncrementalEvaluator(broken, {}), MetricError);
    try {
        evaluate(image.view(), other.view(), {});
    } catch (const MetricError& error) {
        EXPECT_NE(std::string(error.what()).find("20x20"), std::string::npos) << error.what();
        EXPECT_NE(std::string(error.what()).find("21x20"), std::string::npos) << error.what();
    }
}

TEST(MetricStability, ZeroWeightComponentsAreNotComputed) {
    const TestImage a = generateScene(30, 30, 3, 1, 0), b = generateScene(30, 30, 3, 2, 2);
    MetricParameters p;
    p.ssimWeight = 0;
    p.informationEntropyWeight = 0;
    p.computePrecisionRecall = false;
    for (const MetricResult& r : {evaluate(b.view(), a.view(), p), [&] {
             IncrementalEvaluator e(a.view(), p);
             e.setCandidate(b.view());
             return e.result();
         }()}) {
        EXPECT_FALSE(r.ssimComputed);
        EXPECT_EQ(r.ssim, 0.0);
        EXPECT_FALSE(r.informationEntropy.computed);
        EXPECT_FALSE(r.precisionRecallComputed);
        EXPECT_TRUE(r.boundaryEntropy.computed);
        EXPECT_EQ(r.fitness, r.boundaryEntropy.fidelity);  // the only weighted component
        EXPECT_LT(r.fitness, 1.0);
    }
    IncrementalEvaluator e(a.view(), p);
    EXPECT_EQ(e.ssimMap(), nullptr);
}

TEST(MetricStability, FitnessIsTheWeightedMean) {
    const TestImage a = generateScene(50, 40, 3, 1, 0), b = generateScene(50, 40, 3, 2, 2);
    MetricParameters p;
    p.ssimWeight = 2;
    p.boundaryEntropyWeight = 1;
    p.informationEntropyWeight = 0.5;
    const MetricResult r = evaluate(b.view(), a.view(), p);
    EXPECT_NEAR(r.fitness,
                (2 * r.ssimFidelity + 1 * r.boundaryEntropy.fidelity + 0.5 * r.informationEntropy.fidelity) / 3.5,
                1e-15);
    EXPECT_NEAR(r.boundaryEntropy.fidelity,
                1 - std::abs(r.boundaryEntropy.candidate - r.boundaryEntropy.reference) / r.boundaryEntropy.reference,
                1e-15);
    // Only ratios matter.
    MetricParameters scaled = p;
    scaled.ssimWeight *= 10;
    scaled.boundaryEntropyWeight *= 10;
    scaled.informationEntropyWeight *= 10;
    EXPECT_NEAR(evaluate(b.view(), a.view(), scaled).fitness, r.fitness, 1e-15);
}

}  // namespace
}  // namespace lodopt::metrics
