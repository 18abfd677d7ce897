// Deterministic test images for the metrics tests.
//
// generateScene / generateNoise mirror scripts/metrics_reference.py exactly (integer
// arithmetic only), so values pinned from that script apply to these images.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "metrics/metrics.hpp"

namespace lodopt::metrics::testing {

struct TestImage {
    int width = 0, height = 0, channels = 0;
    std::vector<std::uint8_t> pixels;

    TestImage() = default;
    TestImage(int w, int h, int c, std::uint8_t fill = 0)
        : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, fill) {}
    std::uint8_t* at(int x, int y) { return pixels.data() + (std::size_t(y) * width + x) * channels; }
    const std::uint8_t* at(int x, int y) const { return pixels.data() + (std::size_t(y) * width + x) * channels; }
    ImageView view() const { return makeImageView(pixels.data(), width, height, channels); }
};

inline std::uint32_t hash32(std::uint32_t x, std::uint32_t y, std::uint32_t c, std::uint32_t seed) {
    std::uint32_t h = x * 374761393u + y * 668265263u + c * 2246822519u + seed * 3266489917u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return h ^ (h >> 16);
}

constexpr std::uint8_t kBackground[4] = {158, 194, 230, 255};

// Sky background, a shaded box (moved right by `shift`) and a disk, light noise on both.
inline TestImage generateScene(int width, int height, int channels, std::uint32_t seed, int shift) {
    TestImage image(width, height, channels);
    const int cx = (13 * width) / 20, cy = (9 * height) / 20;
    const int radius = std::min(width, height) / 5 - (shift ? 1 : 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            int color[4] = {kBackground[0], kBackground[1], kBackground[2], kBackground[3]};
            bool covered = false;
            if (width / 5 + shift <= x && x < width / 2 + shift && height / 4 <= y && y < (3 * height) / 4) {
                color[0] = (40 + 3 * x) % 200;
                color[1] = (90 + 2 * y) % 150;
                color[2] = 60;
                covered = true;
            }
            if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius) {
                color[0] = 230 - 2 * (x - cx + radius);
                color[1] = 120 + (y - cy);
                color[2] = 30 + x % 17;
                covered = true;
            }
            if (covered) {
                for (int c = 0; c < 3; ++c) {
                    color[c] = std::clamp(color[c] + int(hash32(x, y, c, seed) % 7) - 3, 0, 255);
                }
            }
            std::uint8_t* p = image.at(x, y);
            if (channels == 1) {
                p[0] = std::uint8_t((30 * color[0] + 59 * color[1] + 11 * color[2] + 50) / 100);
            } else {
                for (int c = 0; c < channels; ++c) p[c] = std::uint8_t(color[c]);
            }
        }
    }
    return image;
}

inline TestImage generateNoise(int width, int height, int channels, std::uint32_t seed) {
    TestImage image(width, height, channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < channels; ++c) image.at(x, y)[c] = std::uint8_t(hash32(x, y, c, seed) & 255);
        }
    }
    return image;
}

// Adds uniform noise in [-amplitude, amplitude] to every channel (clamped), from `rng`.
inline TestImage addNoise(const TestImage& image, int amplitude, std::mt19937& rng) {
    TestImage out = image;
    std::uniform_int_distribution<int> noise(-amplitude, amplitude);
    for (auto& v : out.pixels) v = std::uint8_t(std::clamp(int(v) + noise(rng), 0, 255));
    return out;
}

// Fills [x0, x1) x [y0, y1) with random bytes from `rng` (the shape of an object that changed).
inline void scribble(TestImage& image, int x0, int y0, int x1, int y1, std::mt19937& rng) {
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<int> mode(0, 2);
    const int kind = mode(rng);
    const int flat = byte(rng);
    for (int y = y0; y < y1; ++y) {
        for (int x = x0; x < x1; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                // Random noise, a flat color, or the background: all three happen in renders.
                image.at(x, y)[c] = kind == 0 ? std::uint8_t(byte(rng)) : kind == 1 ? std::uint8_t(flat) : kBackground[c];
            }
        }
    }
}

}  // namespace lodopt::metrics::testing
