#include "procedural_textures.hpp"

#include <algorithm>
#include <cmath>

#include "procedural.hpp"

namespace lodopt::scenes::procedural {

namespace {

float fract(float x) {
    return x - std::floor(x);
}

// 1 inside [lo, hi], 0 outside, with a soft edge of `soft` on each side.
float band(float x, float lo, float hi, float soft) {
    return std::clamp(std::min(x - lo, hi - x) / soft + 0.5f, 0.0f, 1.0f);
}

}  // namespace

Texture makeBarkTexture(std::string name, int width, int height, glm::vec3 color, int style, std::uint32_t seed) {
    return makeTexture(std::move(name), width, height, [=](float u, float v) {
        if (style == 2) {
            // Birch: white with short dark horizontal dashes.
            float n = fractalNoise(u * 4.0f, v * 4.0f, 4, 4, 3, seed);
            float dash = valueNoise(u * 6.0f, v * 24.0f, 6, 24, seed + 7u);
            glm::vec3 c = color * (0.92f + 0.12f * n);
            return dash > 0.78f ? glm::vec3(0.15f, 0.13f, 0.12f) : c;
        }
        // Oak furrows run along the branch (stretched in v); pine plates are blockier.
        int px = style == 0 ? 8 : 6, py = style == 0 ? 2 : 4;
        float n = fractalNoise(u * float(px), v * float(py), px, py, 3, seed);
        float furrow = style == 0 ? std::pow(std::abs(2.0f * n - 1.0f), 0.6f) : std::floor(n * 4.0f) / 4.0f;
        float fine = valueNoise(u * 32.0f, v * 32.0f, 32, 32, seed + 3u);
        return color * (0.55f + 0.6f * furrow + 0.15f * fine);
    });
}

Texture makeLeafTexture(std::string name, int size, glm::vec3 color, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float offset = std::abs(u - 0.5f);
        float midrib = band(offset, -1.0f, 0.03f, 0.02f);
        // Veins leave the midrib at 45 degrees towards the tip.
        float vein = band(std::abs(fract((v - offset) * 5.0f) - 0.5f), -1.0f, 0.06f, 0.04f) * (offset > 0.04f);
        float n = fractalNoise(u * 4.0f, v * 4.0f, 4, 4, 2, seed);
        glm::vec3 c = color * (0.85f + 0.3f * n + 0.15f * v);
        c = glm::mix(c, color * 1.35f, 0.6f * std::max(midrib, 0.5f * vein));
        return c;
    });
}

Texture makeFoliageTexture(std::string name, int size, glm::vec3 color, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float clumps = fractalNoise(u * 4.0f, v * 4.0f, 4, 4, 3, seed);
        return color * (0.6f + 0.8f * clumps);
    });
}

Texture makeGrassTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float patches = fractalNoise(u * 4.0f, v * 4.0f, 4, 4, 3, seed);
        float blades = valueNoise(u * 48.0f, v * 48.0f, 48, 48, seed + 11u);
        glm::vec3 green(0.30f, 0.46f, 0.18f), dry(0.46f, 0.44f, 0.26f);
        glm::vec3 c = glm::mix(green, dry, std::clamp((patches - 0.55f) * 3.0f, 0.0f, 1.0f));
        return c * (0.8f + 0.35f * blades);
    });
}

namespace {

// Window pane: glass with a sky reflection gradient and a light frame.
glm::vec3 glass(float u, float v, std::uint32_t seed) {
    float reflection = 0.5f + 0.5f * valueNoise(u * 2.0f, v * 2.0f, 2, 2, seed);
    glm::vec3 dark(0.16f, 0.20f, 0.26f), sky(0.42f, 0.52f, 0.62f);
    return glm::mix(dark, sky, 0.55f * reflection * (0.4f + 0.6f * v));
}

}  // namespace

Texture makePlasterAndWindowTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, 2 * size, [=](float u, float v) {
        if (v < 0.5f) {
            // Plaster: noise that tiles along u; the v range is stretched over each piece.
            float n = fractalNoise(u * 8.0f, v * 16.0f, 8, 8, 3, seed);
            return glm::vec3(0.80f + 0.15f * n);
        }
        // One window bay: piers at both sides, a frame, a transom and a mullion.
        v = 2.0f * (v - 0.5f);
        const glm::vec3 pier(0.86f), frame(0.93f);
        if (u < 0.12f || u > 0.88f) return pier * (0.92f + 0.08f * valueNoise(u * 8, v * 8, 8, 8, seed));
        if (u < 0.16f || u > 0.84f || v < 0.06f || v > 0.94f) return frame;
        if (std::abs(v - 0.72f) < 0.025f || std::abs(u - 0.5f) < 0.015f) return frame;
        return glass(u, v, seed + 5u);
    });
}

Texture makeFacadeTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float n = fractalNoise(u * 4.0f, v * 4.0f, 4, 4, 2, seed);
        glm::vec3 wall(0.80f + 0.12f * n);
        // The window takes the middle of the bay, above a sill band.
        if (u > 0.14f && u < 0.86f && v > 0.3f && v < 0.92f) {
            if (u < 0.18f || u > 0.82f || v < 0.34f || v > 0.88f) return glm::vec3(0.93f);
            return glass((u - 0.18f) / 0.64f, (v - 0.34f) / 0.54f, seed + 5u);
        }
        if (v > 0.26f && v < 0.3f) return glm::vec3(0.7f);  // sill shadow
        return wall;
    });
}

Texture makeGravelTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float n = fractalNoise(u * 16.0f, v * 16.0f, 16, 16, 2, seed);
        return glm::vec3(0.50f, 0.49f, 0.47f) * (0.75f + 0.45f * n);
    });
}

Texture makeRoofTileTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        // Four courses, tiles offset by half a tile on alternate courses.
        float course = v * 4.0f;
        float row = std::floor(course);
        float along = fract(u * 8.0f + 0.5f * std::fmod(row, 2.0f));
        float shade = 0.7f + 0.3f * fract(course);  // each course darker at its upper edge
        float gap = along < 0.06f ? 0.75f : 1.0f;
        float n = valueNoise(u * 8.0f, row, 8, 4, seed);
        return glm::vec3(0.62f, 0.27f, 0.18f) * shade * gap * (0.85f + 0.3f * n);
    });
}

Texture makeAsphaltTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float n = fractalNoise(u * 16.0f, v * 16.0f, 16, 16, 3, seed);
        return glm::vec3(0.26f, 0.26f, 0.28f) * (0.85f + 0.3f * n);
    });
}

Texture makePavingTexture(std::string name, int size, std::uint32_t seed) {
    return makeTexture(std::move(name), size, size, [=](float u, float v) {
        float joint = (fract(u * 4.0f) < 0.05f || fract(v * 4.0f) < 0.05f) ? 0.8f : 1.0f;
        float n = valueNoise(u * 16.0f, v * 16.0f, 16, 16, seed);
        return glm::vec3(0.66f, 0.64f, 0.60f) * joint * (0.9f + 0.15f * n);
    });
}

}  // namespace lodopt::scenes::procedural
