// Rebuilding a frame from per-object layers by nearest depth, optionally reporting what changed.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "renderer/renderer.hpp"

namespace lodopt::renderer {

void clearColorBytes(glm::vec4 clearColor, std::uint8_t out[4]) {
    for (int c = 0; c < 4; ++c) {
        out[c] = static_cast<std::uint8_t>(std::lround(std::clamp(clearColor[c], 0.0f, 1.0f) * 255.0f));
    }
}

namespace {

PixelRect clippedToFrame(PixelRect rect, const Frame& out) {
    return {std::max(rect.x0, 0), std::max(rect.y0, 0), std::min(rect.x1, out.width), std::min(rect.y1, out.height)};
}

// The clear color as one RGBA8 word.
std::uint32_t clearWord(glm::vec4 clearColor) {
    std::uint8_t bytes[4];
    clearColorBytes(clearColor, bytes);
    std::uint32_t word;
    std::memcpy(&word, bytes, 4);
    return word;
}

// Pixels per row chunk: scratch rows live on the stack.
constexpr int kChunk = 512;

// The layers that reach `rect` into `reaching`, still in object order (the order the depth
// test needs), and those of them that blend into `blended`, in the full render's back-to-front
// order.
void layersReaching(const std::vector<const Layer*>& layers, PixelRect rect, std::vector<const Layer*>& reaching,
                    std::vector<const Layer*>& blended) {
    reaching.clear();
    blended.clear();
    for (const Layer* layer : layers) {
        if (!layer || layer->rect.empty()) continue;
        const PixelRect& r = layer->rect;
        if (r.x0 < rect.x1 && rect.x0 < r.x1 && r.y0 < rect.y1 && rect.y0 < r.y1) {
            reaching.push_back(layer);
            if (layer->blends()) blended.push_back(layer);
        }
    }
    std::sort(blended.begin(), blended.end(), [](const Layer* a, const Layer* b) {
        return a->blendDistance != b->blendDistance ? a->blendDistance > b->blendDistance : a->object < b->object;
    });
}

// x * y / 255 rounded to nearest, for x, y in 0..255: the blend unit's normalized product
// (llvmpipe's "geometric series plus rounding", exact for 16-bit products), so that one
// blended fragment composited here gives the byte the full render's blending gives.
inline std::uint32_t mulUnorm8(std::uint32_t x, std::uint32_t y) {
    const std::uint32_t t = x * y;
    return (t + (t >> 8) + 0x80) >> 8;
}

// The columns [a, b) of `layer` on row y (frame coordinates), clipped to its covered span.
bool layerColumns(const Layer& layer, int y, int x0, int n, int& a, int& b) {
    const PixelRect& r = layer.rect;
    if (y < r.y0 || y >= r.y1) return false;
    a = std::max(x0, r.x0);
    b = std::min(x0 + n, r.x1);
    if (!layer.rowSpans.empty()) {
        // Uncovered pixels (depth 1) never win the depth test: only the covered span.
        const RowSpan& span = layer.rowSpans[std::size_t(y - r.y0)];
        a = std::max(a, span.x0);
        b = std::min(b, span.x1);
    }
    return a < b;
}

// Composites row y, columns [x0, x0 + n) with n <= kChunk, into `color` and `depth`: the clear
// color at depth 1, then the layers' opaque surfaces in object order with a strict depth test,
// so that on equal depth the lower object index stays, exactly as GL_LESS keeps the first-drawn
// object in a full render; then the blended layers, back to front, where their nearest fragment
// is strictly in front of that: color = blended + color x (1 - coverage), per channel, as
// glBlendFuncSeparate(SRC_ALPHA, ONE_MINUS_SRC_ALPHA, ONE, ONE_MINUS_SRC_ALPHA) adds with
// saturation. Every composite goes through here, so all give the same values.
void compositeRowChunk(const std::vector<const Layer*>& layers, const std::vector<const Layer*>& blended, int y,
                       int x0, int n, std::uint32_t clear, std::uint32_t* color, float* depth) {
    std::fill_n(color, n, clear);
    std::fill_n(depth, n, 1.0f);
    for (const Layer* layer : layers) {
        int a = 0, b = 0;
        if (!layerColumns(*layer, y, x0, n, a, b)) continue;
        const PixelRect& r = layer->rect;
        const std::size_t l = std::size_t(y - r.y0) * r.width() + (a - r.x0);
        // A mask instead of a branch, and __restrict (the layer and the scratch row never
        // alias): both are needed for GCC to vectorize the select.
        const float* __restrict layerDepth = &layer->occluderDepth()[l];
        const std::uint8_t* __restrict layerColor = &layer->rgba[l * 4];
        float* __restrict rowDepth = depth + (a - x0);
        std::uint32_t* __restrict rowColor = color + (a - x0);
        for (int i = 0; i < b - a; ++i) {
            const float near = layerDepth[i], far = rowDepth[i];
            const std::uint32_t nearer = 0u - std::uint32_t(near < far);
            std::uint32_t source;
            std::memcpy(&source, layerColor + std::size_t(i) * 4, 4);
            rowDepth[i] = near < far ? near : far;
            rowColor[i] = (source & nearer) | (rowColor[i] & ~nearer);
        }
    }
    for (const Layer* layer : blended) {
        int a = 0, b = 0;
        if (!layerColumns(*layer, y, x0, n, a, b)) continue;
        const PixelRect& r = layer->rect;
        const std::size_t l = std::size_t(y - r.y0) * r.width() + (a - r.x0);
        // Where the layer has blended fragments its nearest fragment is a blended one, so
        // `depth` is that fragment's depth there.
        const float* nearest = &layer->depth[l];
        const float* farthest = &layer->blendFarthest[l];
        const std::uint8_t* over = &layer->blendRgba[l * 4];
        for (int i = 0; i < b - a; ++i) {
            const float behind = depth[a - x0 + i];
            if (!(nearest[i] < behind)) continue;
            std::uint8_t* target = reinterpret_cast<std::uint8_t*>(color + (a - x0 + i));
            if (farthest[i] == nearest[i]) {
                // One fragment (in front): the pre-blended color and coverage, as exact.
                const std::uint8_t* source = over + std::size_t(i) * 4;
                const std::uint32_t coverage = source[3];
                if (coverage == 0) continue;
                for (int c = 0; c < 4; ++c) {
                    target[c] = std::uint8_t(std::min<std::uint32_t>(255, source[c] + mulUnorm8(target[c], 255 - coverage)));
                }
                continue;
            }
            // Several fragments: those in front of the opaque composite, one by one in draw order,
            // as the blend unit takes them (pre-blended, they would round differently; and an
            // opaque surface of another object may pass between them).
            const std::uint32_t pixel = std::uint32_t(l + i);
            const auto found = std::lower_bound(layer->stackPixels.begin(), layer->stackPixels.end(), pixel);
            if (found == layer->stackPixels.end() || *found != pixel) continue;
            const std::size_t stack = std::size_t(found - layer->stackPixels.begin());
            for (std::uint32_t f = layer->stackStarts[stack]; f < layer->stackStarts[stack + 1]; ++f) {
                const Layer::BlendFragment& fragment = layer->stackFragments[f];
                if (!(fragment.depth < behind)) continue;
                const std::uint32_t alpha = fragment.rgba[3];
                for (int c = 0; c < 3; ++c) {
                    target[c] = std::uint8_t(std::min<std::uint32_t>(
                        255, mulUnorm8(fragment.rgba[c], alpha) + mulUnorm8(target[c], 255 - alpha)));
                }
                target[3] = std::uint8_t(std::min<std::uint32_t>(255, alpha + mulUnorm8(target[3], 255 - alpha)));
            }
        }
    }
}

// Sets bit `row` of columns[i] for each of the n pixels whose color changed from `before` to
// `now`; true when any did. memcmp first: most rows of a recomposited region are unchanged.
bool markChangedColumns(const std::uint32_t* now, const std::uint8_t* before, int n, int row,
                        std::uint32_t* columns) {
    if (std::memcmp(now, before, std::size_t(n) * 4) == 0) return false;
    for (int i = 0; i < n; ++i) {
        std::uint32_t old;
        std::memcpy(&old, before + std::size_t(i) * 4, 4);
        columns[i] |= std::uint32_t(now[i] != old) << row;
    }
    return true;
}

// Appends the tight rectangle of each run of marked columns in [x0, x1) of the band starting
// at row `bandTop`, runs less than `splitGap` unmarked columns apart joined, and clears the marks.
void appendColumnRuns(std::uint32_t* columns, int x0, int x1, int bandTop, int splitGap,
                      std::vector<PixelRect>& changed) {
    for (int x = x0; x < x1;) {
        if (!columns[x]) {
            ++x;
            continue;
        }
        const int start = x;
        int end = x;  // one past the last marked column of the run
        std::uint32_t rows = 0;
        for (int gap = 0; x < x1 && gap < splitGap; ++x) {
            gap = columns[x] ? 0 : gap + 1;
            if (columns[x]) end = x + 1;
            rows |= columns[x];
            columns[x] = 0;
        }
        changed.push_back({start, bandTop + std::countr_zero(rows), end, bandTop + 32 - std::countl_zero(rows)});
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
    rect = clippedToFrame(rect, out);
    if (rect.empty()) return;
    std::vector<const Layer*> reaching, blended;
    layersReaching(layers, rect, reaching, blended);
    const std::uint32_t clear = clearWord(clearColor);
    std::uint32_t color[kChunk];
    float depth[kChunk];
    for (int y = rect.y0; y < rect.y1; ++y) {
        for (int x = rect.x0; x < rect.x1; x += kChunk) {
            const int n = std::min(kChunk, rect.x1 - x);
            compositeRowChunk(reaching, blended, y, x, n, clear, color, depth);
            const std::size_t at = std::size_t(y) * out.width + x;
            std::memcpy(&out.rgba[at * 4], color, std::size_t(n) * 4);
            std::memcpy(&out.depth[at], depth, std::size_t(n) * sizeof(float));
        }
    }
}

std::vector<RowSpan> coveredRowSpans(const Layer& layer) {
    const PixelRect& r = layer.rect;
    std::vector<RowSpan> spans(std::size_t(r.height()));
    for (int y = 0; y < r.height(); ++y) {
        const float* depth = &layer.depth[std::size_t(y) * r.width()];
        int first = 0, last = r.width();
        while (first < last && !(depth[first] < 1.0f)) ++first;
        while (last > first && !(depth[last - 1] < 1.0f)) --last;
        if (first < last) spans[std::size_t(y)] = {r.x0 + first, r.x0 + last};
    }
    return spans;
}

void compositeSpansChanges(const std::vector<const Layer*>& layers, int top, std::span<const RowSpan> spans,
                           glm::vec4 clearColor, ChangeGrid grid, Frame& out, std::vector<PixelRect>& changed) {
    CompositeScratch scratch;
    compositeSpansChanges(layers, top, spans, clearColor, grid, out, changed, scratch);
}

void compositeSpansChanges(const std::vector<const Layer*>& layers, int top, std::span<const RowSpan> spans,
                           glm::vec4 clearColor, ChangeGrid grid, Frame& out, std::vector<PixelRect>& changed,
                           CompositeScratch& scratch) {
    const int rowBegin = std::max(top, 0);
    const int rowEnd = std::min(top + int(spans.size()), out.height);
    if (rowBegin >= rowEnd) return;
    const int bandRows = std::clamp(grid.bandRows, 1, 32), splitGap = std::max(grid.splitGap, 1);
    PixelRect hull{out.width, rowBegin, 0, rowEnd};
    for (int y = rowBegin; y < rowEnd; ++y) {
        const RowSpan& span = spans[std::size_t(y - top)];
        if (!span.empty()) hull = {std::min(hull.x0, span.x0), rowBegin, std::max(hull.x1, span.x1), rowEnd};
    }
    hull = clippedToFrame(hull, out);
    if (hull.empty()) return;
    layersReaching(layers, hull, scratch.reaching, scratch.blended);
    const std::vector<const Layer*>& reaching = scratch.reaching;
    const std::vector<const Layer*>& blended = scratch.blended;
    const std::uint32_t clear = clearWord(clearColor);
    std::uint32_t color[kChunk];
    float depth[kChunk];
    // appendColumnRuns clears every mark it reads, so the buffer is all zero between calls.
    std::vector<std::uint32_t>& columns = scratch.columns;
    if (columns.size() != std::size_t(out.width)) columns.assign(std::size_t(out.width), 0);
    // Bands counted from `top`, so that the caller's band grid does not depend on clipping.
    for (int bandTop = top + (rowBegin - top) / bandRows * bandRows; bandTop < rowEnd; bandTop += bandRows) {
        const int bandBottom = std::min(rowEnd, bandTop + bandRows);
        int changedX0 = out.width, changedX1 = 0;  // columns the band's changes span
        for (int y = std::max(bandTop, rowBegin); y < bandBottom; ++y) {
            const RowSpan& span = spans[std::size_t(y - top)];
            const int x0 = std::max(span.x0, 0), x1 = std::min(span.x1, out.width);
            for (int x = x0; x < x1; x += kChunk) {
                const int n = std::min(kChunk, x1 - x);
                compositeRowChunk(reaching, blended, y, x, n, clear, color, depth);
                const std::size_t at = std::size_t(y) * out.width + x;
                std::uint8_t* frameColor = &out.rgba[at * 4];
                if (markChangedColumns(color, frameColor, n, y - bandTop, &columns[std::size_t(x)])) {
                    changedX0 = std::min(changedX0, x);
                    changedX1 = std::max(changedX1, x + n);
                }
                std::memcpy(frameColor, color, std::size_t(n) * 4);
                std::memcpy(&out.depth[at], depth, std::size_t(n) * sizeof(float));
            }
        }
        appendColumnRuns(columns.data(), changedX0, changedX1, bandTop, splitGap, changed);
    }
}

void compositeRectChanges(const std::vector<const Layer*>& layers, PixelRect rect, glm::vec4 clearColor, ChangeGrid grid,
                          Frame& out, std::vector<PixelRect>& changed) {
    if (rect.empty()) return;
    const std::vector<RowSpan> spans(std::size_t(rect.height()), RowSpan{rect.x0, rect.x1});
    compositeSpansChanges(layers, rect.y0, spans, clearColor, grid, out, changed);
}

}  // namespace lodopt::renderer
