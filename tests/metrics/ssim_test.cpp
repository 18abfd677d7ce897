// SSIM: the map against a direct evaluation of the definition, exact identities, properties.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "metrics/metrics.hpp"
#include "test_images.hpp"

namespace lodopt::metrics {
namespace {

using testing::addNoise;
using testing::generateNoise;
using testing::generateScene;
using testing::TestImage;

// The definition evaluated directly per window: 2-D Gaussian weights, float64 sums.
std::vector<double> directSsimMap(const TestImage& x, const TestImage& y, int window, double sigma,
                                  const double weights[3], int& mapWidth, int& mapHeight) {
    auto gray = [&](const TestImage& image, int px, int py) {
        const std::uint8_t* p = image.at(px, py);
        return image.channels == 1 ? double(p[0]) : weights[0] * p[0] + weights[1] * p[1] + weights[2] * p[2];
    };
    const int r = window / 2;
    std::vector<double> w(static_cast<std::size_t>(window));
    double sum = 0;
    for (int k = 0; k < window; ++k) sum += w[std::size_t(k)] = std::exp(-0.5 * (k - r) * (k - r) / (sigma * sigma));
    for (double& v : w) v /= sum;
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    mapWidth = x.width - window + 1;
    mapHeight = x.height - window + 1;
    std::vector<double> map;
    for (int my = 0; my < mapHeight; ++my) {
        for (int mx = 0; mx < mapWidth; ++mx) {
            double ux = 0, uy = 0, xx = 0, yy = 0, xy = 0;
            for (int j = 0; j < window; ++j) {
                for (int i = 0; i < window; ++i) {
                    const double wij = w[std::size_t(i)] * w[std::size_t(j)];
                    const double a = gray(x, mx + i, my + j), b = gray(y, mx + i, my + j);
                    ux += wij * a;
                    uy += wij * b;
                    xx += wij * a * a;
                    yy += wij * b * b;
                    xy += wij * a * b;
                }
            }
            const double vx = xx - ux * ux, vy = yy - uy * uy, cxy = xy - ux * uy;
            map.push_back((2 * ux * uy + c1) * (2 * cxy + c2) / ((ux * ux + uy * uy + c1) * (vx + vy + c2)));
        }
    }
    return map;
}

TEST(Ssim, MapMatchesTheDefinitionEvaluatedDirectly) {
    const double paper[3] = {0.30, 0.59, 0.11};
    const double bt709[3] = {0.2126, 0.7152, 0.0722};
    const struct {
        int width, height, channels, window;
        double sigma;
        GrayWeights gray;
        const double* weights;
    } cases[] = {{40, 31, 3, 11, 1.5, GrayWeights::Paper, paper},
                 {300, 20, 4, 11, 1.5, GrayWeights::Bt709, bt709},  // two column blocks
                 {23, 80, 1, 11, 1.5, GrayWeights::Paper, paper},   // two row blocks
                 {30, 25, 3, 7, 1.0, GrayWeights::Paper, paper}};   // the generic window path
    for (const auto& c : cases) {
        const TestImage x = generateNoise(c.width, c.height, c.channels, 11);
        const TestImage y = generateScene(c.width, c.height, c.channels, 12, 1);
        MetricParameters p;
        p.ssimWindow = c.window;
        p.ssimSigma = c.sigma;
        p.grayWeights = c.gray;
        int mapWidth = 0, mapHeight = 0;
        const std::vector<double> expected = directSsimMap(x, y, c.window, c.sigma, c.weights, mapWidth, mapHeight);
        const SsimMapSize size = ssimMapSize(c.width, c.height, p);
        ASSERT_EQ(size.width, mapWidth);
        ASSERT_EQ(size.height, mapHeight);
        std::vector<double> map(expected.size() + 7 * std::size_t(mapHeight));
        ssimMap(x.view(), y.view(), p, map.data(), std::size_t(mapWidth + 7));  // a padded stride
        for (int my = 0; my < mapHeight; ++my) {
            for (int mx = 0; mx < mapWidth; ++mx) {
                ASSERT_NEAR(map[std::size_t(my) * (mapWidth + 7) + mx], expected[std::size_t(my) * mapWidth + mx],
                            1e-12)
                    << c.width << "x" << c.height << " at " << mx << "," << my;
            }
        }
    }
}

TEST(Ssim, IdenticalImagesGiveExactlyOne) {
    const TestImage images[] = {generateScene(64, 48, 3, 1, 0), generateNoise(37, 29, 4, 2),
                                generateNoise(20, 20, 1, 3),   TestImage(16, 16, 3, 0),
                                TestImage(16, 16, 3, 255),     TestImage(5, 9, 3, 77),
                                TestImage(1, 1, 1, 200)};
    for (GrayWeights gray : {GrayWeights::Paper, GrayWeights::Bt601, GrayWeights::Bt709}) {
        MetricParameters p;
        p.grayWeights = gray;
        for (const TestImage& image : images) {
            EXPECT_EQ(ssim(image.view(), image.view(), p), 1.0);
            // A copy at another address, with another row stride.
            TestImage padded(image.width + 3, image.height, image.channels);
            for (int y = 0; y < image.height; ++y) {
                std::copy_n(image.at(0, y), std::size_t(image.width) * image.channels, padded.at(0, y));
            }
            ImageView view = image.view();
            view.pixels = padded.pixels.data();
            view.rowStride = std::size_t(padded.width) * padded.channels;
            EXPECT_EQ(ssim(view, image.view(), p), 1.0);
        }
    }
}

TEST(Ssim, IsSymmetric) {
    const TestImage a = generateScene(70, 50, 3, 1, 0);
    const TestImage b = generateScene(70, 50, 3, 2, 3);
    const TestImage c = generateNoise(70, 50, 3, 4);
    EXPECT_NEAR(ssim(a.view(), b.view(), {}), ssim(b.view(), a.view(), {}), 1e-14);
    EXPECT_NEAR(ssim(a.view(), c.view(), {}), ssim(c.view(), a.view(), {}), 1e-14);
    EXPECT_LT(ssim(a.view(), b.view(), {}), 1.0);
}

TEST(Ssim, DropsMonotonicallyWithNoise) {
    const TestImage clean = generateScene(96, 80, 3, 1, 0);
    double previous = ssim(clean.view(), clean.view(), {});
    for (int amplitude : {1, 2, 4, 8, 16, 32, 64, 128}) {
        std::mt19937 rng(99);  // the same pattern each time, scaled up
        const TestImage noisy = addNoise(clean, amplitude, rng);
        const double value = ssim(noisy.view(), clean.view(), {});
        EXPECT_LT(value, previous) << "amplitude " << amplitude;
        previous = value;
    }
    EXPECT_LT(previous, 0.3);
}

TEST(Ssim, ConstantImagesReduceToTheLuminanceTerm) {
    // Zero variance: the contrast-structure factor is C2 / C2 = 1.
    const double c1 = (0.01 * 255) * (0.01 * 255);
    for (auto [a, b] : {std::pair{0, 255}, std::pair{100, 200}, std::pair{0, 1}, std::pair{254, 255}}) {
        const TestImage x(13, 12, 1, std::uint8_t(a)), y(13, 12, 1, std::uint8_t(b));
        const double expected = (2.0 * a * b + c1) / (double(a) * a + double(b) * b + c1);
        // 1e-12: E[x^2] - mean^2 of a constant cancels to a few ulps of 255^2, not to 0.
        EXPECT_NEAR(ssim(x.view(), y.view(), {}), expected, 1e-12) << a << " vs " << b;
    }
}

TEST(Ssim, SmallImagesShrinkTheWindow) {
    MetricParameters p;
    EXPECT_EQ(ssimMapSize(512, 512, p).width, 502);
    EXPECT_EQ(ssimMapSize(11, 11, p).window, 11);
    EXPECT_EQ(ssimMapSize(10, 40, p).window, 9);
    EXPECT_EQ(ssimMapSize(10, 40, p).width, 2);
    EXPECT_EQ(ssimMapSize(10, 40, p).height, 32);
    EXPECT_EQ(ssimMapSize(1, 1, p).window, 1);
    EXPECT_EQ(ssimMapSize(2, 7, p).window, 1);
    // A shrunk window is the same as asking for that window.
    const TestImage a = generateNoise(8, 30, 3, 1), b = generateNoise(8, 30, 3, 2);
    MetricParameters seven;
    seven.ssimWindow = 7;
    EXPECT_EQ(ssim(a.view(), b.view(), p), ssim(a.view(), b.view(), seven));
    // 1x1: a 1x1 window, only the luminance term remains.
    const TestImage x(1, 1, 1, 100), y(1, 1, 1, 200);
    const double c1 = (0.01 * 255) * (0.01 * 255);
    // (within 2^-41: windows are pooled in fixed point, docs/metrics.md)
    EXPECT_NEAR(ssim(x.view(), y.view(), p), (2.0 * 100 * 200 + c1) / (100.0 * 100 + 200.0 * 200 + c1), 0x1p-41);
}

TEST(Ssim, PoolMeanIsTheMean) {
    std::vector<double> map(130 * 7);
    double sum = 0;
    for (std::size_t i = 0; i < map.size(); ++i) sum += map[i] = std::sin(double(i));
    // Fixed point: each value rounded to a multiple of 2^-40, so the mean within 2^-41.
    EXPECT_NEAR(poolMean(map.data(), 130, 7, 130), sum / double(map.size()), 0x1p-41);
    std::fill(map.begin(), map.end(), 0.25);
    EXPECT_EQ(poolMean(map.data(), 130, 7, 130), 0.25);
    EXPECT_EQ(poolMean(map.data(), 13, 7, 130), 0.25);  // stride wider than the map
}

TEST(Ssim, OppositeImagesGiveNegativeSsim) {
    // Extreme contrast: a checkerboard against its inverse is anti-correlated everywhere.
    TestImage a(32, 32, 1), b(32, 32, 1);
    for (int y = 0; y < 32; ++y) {
        for (int x = 0; x < 32; ++x) {
            a.at(x, y)[0] = ((x + y) % 2) ? 255 : 0;
            b.at(x, y)[0] = ((x + y) % 2) ? 0 : 255;
        }
    }
    const double value = ssim(a.view(), b.view(), {});
    EXPECT_LT(value, -0.9);
    EXPECT_GE(value, -1.0);
}

}  // namespace
}  // namespace lodopt::metrics
