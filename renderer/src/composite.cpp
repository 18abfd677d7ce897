// Rebuilding a frame from per-object layers by nearest depth.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/renderer.hpp"

namespace lodopt::renderer {

void clearColorBytes(glm::vec4 clearColor, std::uint8_t out[4]) {
    for (int c = 0; c < 4; ++c) {
        out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(clearColor[c], 0.0f, 1.0f) * 255.0f));
    }
}

namespace {

void clearRect(PixelRect rect, glm::vec4 clearColor, Frame& out) {
    std::uint8_t clear[4];
    clearColorBytes(clearColor, clear);
    for (int y = rect.y0; y < rect.y1; ++y) {
        std::uint8_t* color = &out.rgba[(std::size_t(y) * out.width + rect.x0) * 4];
        float* depth = &out.depth[std::size_t(y) * out.width + rect.x0];
        for (int x = rect.x0; x < rect.x1; ++x, color += 4, ++depth) {
            std::copy(clear, clear + 4, color);
            *depth = 1.0f;
        }
    }
}

// Layers in object order with a strict depth test: on equal depth the lower object index
// stays, exactly as GL_LESS keeps the first-drawn object in a full render.
void applyLayer(const Layer& layer, PixelRect rect, Frame& out) {
    const int x0 = std::max(rect.x0, layer.rect.x0), x1 = std::min(rect.x1, layer.rect.x1);
    const int y0 = std::max(rect.y0, layer.rect.y0), y1 = std::min(rect.y1, layer.rect.y1);
    if (x0 >= x1 || y0 >= y1) return;
    const int layerWidth = layer.rect.width();
    const int count = x1 - x0;
    for (int y = y0; y < y1; ++y) {
        const std::size_t l = std::size_t(y - layer.rect.y0) * layerWidth + (x0 - layer.rect.x0);
        const std::size_t f = std::size_t(y) * out.width + x0;
        const float* layerDepth = &layer.depth[l];
        float* frameDepth = &out.depth[f];
        // Whole RGBA8 pixels as 32-bit words: a select per pixel that the compiler vectorizes.
        std::uint32_t layerColor[512];
        std::uint32_t frameColor[512];
        for (int start = 0; start < count; start += 512) {
            const int n = std::min(512, count - start);
            std::memcpy(layerColor, &layer.rgba[(l + start) * 4], std::size_t(n) * 4);
            std::memcpy(frameColor, &out.rgba[(f + start) * 4], std::size_t(n) * 4);
            for (int x = 0; x < n; ++x) {
                const bool nearer = layerDepth[start + x] < frameDepth[start + x];
                frameDepth[start + x] = nearer ? layerDepth[start + x] : frameDepth[start + x];
                frameColor[x] = nearer ? layerColor[x] : frameColor[x];
            }
            std::memcpy(&out.rgba[(f + start) * 4], frameColor, std::size_t(n) * 4);
        }
    }
}

}  // namespace

void composite(const std::vector<const Layer*>& layers, int width, int height, glm::vec4 clearColor, Frame& out) {
    out.width = width;
    out.height = height;
    out.rgba.resize(std::size_t(width) * height * 4);
    out.depth.resize(std::size_t(width) * height);
    compositeRect(layers, PixelRect{0, 0, width, height}, clearColor, out);
}

void compositeRect(const std::vector<const Layer*>& layers, PixelRect rect, glm::vec4 clearColor, Frame& out) {
    rect.x0 = std::max(rect.x0, 0);
    rect.y0 = std::max(rect.y0, 0);
    rect.x1 = std::min(rect.x1, out.width);
    rect.y1 = std::min(rect.y1, out.height);
    if (rect.empty()) return;
    clearRect(rect, clearColor, out);
    for (const Layer* layer : layers) {
        if (layer && !layer->rect.empty()) applyLayer(*layer, rect, out);
    }
}

}  // namespace lodopt::renderer
