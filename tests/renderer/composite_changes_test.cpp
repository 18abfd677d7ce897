// compositeSpansChanges / compositeRectChanges: the frame equals a fresh composite, and the
// reported rectangles cover every pixel whose color changed (checked against a brute-force
// diff), stay inside the recomposited region and are tight per band and cluster. Synthetic layers (no GL):
// few depth values, so equal-depth ties between objects are frequent.
#include <gtest/gtest.h>

#include <random>

#include "renderer/renderer.hpp"

using namespace lodopt;

namespace {

constexpr int kWidth = 97, kHeight = 83;  // odd sizes: bands and chunks do not divide evenly
const glm::vec4 kClear{158.0f / 255.0f, 194.0f / 255.0f, 230.0f / 255.0f, 1.0f};

// A layer of `object` with a random rectangle partly outside the frame clipped to it, random
// covered pixels (about 70 %), depths from four values and colors from four values.
renderer::Layer randomLayer(int object, std::mt19937& random) {
    renderer::Layer layer;
    layer.object = object;
    const int x0 = int(random() % kWidth), y0 = int(random() % kHeight);
    layer.rect = {x0, y0, std::min(kWidth, x0 + 1 + int(random() % 60)), std::min(kHeight, y0 + 1 + int(random() % 60))};
    const std::size_t pixels = std::size_t(layer.rect.width()) * layer.rect.height();
    const float depths[] = {0.25f, 0.5f, 0.75f, 0.9f};
    const std::uint8_t colors[4][4] = {{10, 20, 30, 255}, {200, 40, 40, 255}, {40, 200, 40, 255}, {200, 40, 41, 255}};
    for (std::size_t i = 0; i < pixels; ++i) {
        const bool covered = random() % 10 < 7;
        layer.depth.push_back(covered ? depths[random() % 4] : 1.0f);
        const std::uint8_t* color = colors[random() % 4];
        layer.rgba.insert(layer.rgba.end(), color, color + 4);
        layer.coveredPixels += covered;
    }
    return layer;
}

bool samePixel(const renderer::Frame& a, const renderer::Frame& b, int x, int y) {
    const std::size_t at = (std::size_t(y) * kWidth + x) * 4;
    return std::equal(&a.rgba[at], &a.rgba[at] + 4, &b.rgba[at]);
}

bool inside(const renderer::PixelRect& r, int x, int y) { return x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1; }

// Every pixel that differs between `before` and `after` lies in some rectangle of `changed`;
// every rectangle lies in one band of `region`, its four edges each touch a changed pixel
// (tight), and rectangles of one band are at least grid.splitGap columns apart.
void expectChangesCovered(const renderer::Frame& before, const renderer::Frame& after,
                          const std::vector<renderer::PixelRect>& changed, const renderer::PixelRect& region,
                          renderer::ChangeGrid grid) {
    const int bandRows = grid.bandRows;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            if (samePixel(before, after, x, y)) continue;
            bool covered = false;
            for (const renderer::PixelRect& rect : changed) covered = covered || inside(rect, x, y);
            ASSERT_TRUE(covered) << "changed pixel (" << x << ", " << y << ") not reported";
        }
    }
    for (const renderer::PixelRect& rect : changed) {
        ASSERT_FALSE(rect.empty());
        EXPECT_GE(rect.x0, region.x0);
        EXPECT_LE(rect.x1, region.x1);
        EXPECT_GE(rect.y0, region.y0);
        EXPECT_LE(rect.y1, region.y1);
        EXPECT_EQ((rect.y0 - region.y0) / bandRows, (rect.y1 - 1 - region.y0) / bandRows) << "spans two bands";
        bool left = false, right = false, top = false, bottom = false;
        for (int y = rect.y0; y < rect.y1; ++y) {
            left = left || !samePixel(before, after, rect.x0, y);
            right = right || !samePixel(before, after, rect.x1 - 1, y);
        }
        for (int x = rect.x0; x < rect.x1; ++x) {
            top = top || !samePixel(before, after, x, rect.y0);
            bottom = bottom || !samePixel(before, after, x, rect.y1 - 1);
        }
        EXPECT_TRUE(left && right && top && bottom) << "rectangle not tight";
    }
    for (std::size_t i = 1; i < changed.size(); ++i) {
        const renderer::PixelRect &a = changed[i - 1], &b = changed[i];
        if ((a.y0 - region.y0) / bandRows != (b.y0 - region.y0) / bandRows) continue;
        EXPECT_GE(b.x0 - a.x1, grid.splitGap) << "clusters of one band closer than the split gap";
    }
}

renderer::ChangeGrid randomGrid(std::mt19937& random) {
    return {1 + int(random() % 12), 1 + int(random() % 20)};
}

renderer::PixelRect unite(const renderer::PixelRect& a, const renderer::PixelRect& b) {
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

}  // namespace

TEST(CompositeChanges, CoveredRowSpansMatchTheLayersDepth) {
    std::mt19937 random(3);
    for (int trial = 0; trial < 50; ++trial) {
        const renderer::Layer layer = randomLayer(0, random);
        const std::vector<renderer::RowSpan> spans = renderer::coveredRowSpans(layer);
        ASSERT_EQ(spans.size(), std::size_t(layer.rect.height()));
        for (int y = 0; y < layer.rect.height(); ++y) {
            int first = -1, last = -1;
            for (int x = 0; x < layer.rect.width(); ++x) {
                if (layer.depth[std::size_t(y) * layer.rect.width() + x] >= 1.0f) continue;
                if (first < 0) first = x;
                last = x;
            }
            if (first < 0) {
                EXPECT_TRUE(spans[y].empty());
            } else {
                EXPECT_EQ(spans[y].x0, layer.rect.x0 + first);
                EXPECT_EQ(spans[y].x1, layer.rect.x0 + last + 1);
            }
        }
    }
}

TEST(CompositeChanges, RectangleVariantReportsEveryChangedPixel) {
    std::mt19937 random(7);
    const int objects = 6;
    std::vector<renderer::Layer> pool;  // two candidate layers per object
    for (int o = 0; o < objects; ++o) {
        pool.push_back(randomLayer(o, random));
        pool.push_back(randomLayer(o, random));
    }
    std::vector<const renderer::Layer*> layers;
    for (int o = 0; o < objects; ++o) layers.push_back(&pool[std::size_t(2 * o)]);
    renderer::Frame frame;
    renderer::composite(layers, kWidth, kHeight, kClear, frame);
    int reported = 0, unchanged = 0;
    for (int step = 0; step < 300; ++step) {
        const renderer::ChangeGrid grid = randomGrid(random);
        const int object = int(random() % objects);
        const renderer::Layer* next = &pool[std::size_t(2 * object) + random() % 2];  // often the same layer
        const renderer::PixelRect region = unite(layers[object]->rect, next->rect);
        layers[object] = next;
        const renderer::Frame before = frame;
        std::vector<renderer::PixelRect> changed;
        renderer::compositeRectChanges(layers, region, kClear, grid, frame, changed);
        renderer::Frame fresh;
        renderer::composite(layers, kWidth, kHeight, kClear, fresh);
        ASSERT_EQ(frame.rgba, fresh.rgba) << "step " << step;
        ASSERT_EQ(frame.depth, fresh.depth) << "step " << step;
        expectChangesCovered(before, frame, changed, region, grid);
        if (before.rgba == frame.rgba) {
            EXPECT_TRUE(changed.empty()) << "nothing changed, yet rectangles were reported";
            ++unchanged;
        }
        reported += !changed.empty();
    }
    // Both outcomes occurred, so both branches above were exercised.
    EXPECT_GT(reported, 50);
    EXPECT_GT(unchanged, 10);
}

TEST(CompositeChanges, SpanVariantOverTheChangedLayersCoverageReportsEveryChangedPixel) {
    std::mt19937 random(11);
    const int objects = 8;
    std::vector<renderer::Layer> pool;  // three candidate layers per object
    for (int o = 0; o < objects; ++o) {
        for (int k = 0; k < 3; ++k) pool.push_back(randomLayer(o, random));
    }
    std::vector<const renderer::Layer*> layers;
    for (int o = 0; o < objects; ++o) layers.push_back(&pool[std::size_t(3 * o)]);
    renderer::Frame frame;
    renderer::composite(layers, kWidth, kHeight, kClear, frame);
    for (int step = 0; step < 300; ++step) {
        const renderer::ChangeGrid grid = randomGrid(random);
        // Rows of the whole frame; a changed layer's covered columns, old and new, per row:
        // what the fast evaluator passes.
        std::vector<renderer::RowSpan> rows(kHeight);
        auto widen = [&](const renderer::Layer& layer) {
            const std::vector<renderer::RowSpan> spans = renderer::coveredRowSpans(layer);
            for (std::size_t i = 0; i < spans.size(); ++i) {
                if (spans[i].empty()) continue;
                renderer::RowSpan& row = rows[std::size_t(layer.rect.y0) + i];
                row = row.empty() ? spans[i] : renderer::RowSpan{std::min(row.x0, spans[i].x0), std::max(row.x1, spans[i].x1)};
            }
        };
        const int changes = 1 + int(random() % 3);
        for (int c = 0; c < changes; ++c) {
            const int object = int(random() % objects);
            widen(*layers[object]);
            layers[object] = &pool[std::size_t(3 * object) + random() % 3];
            widen(*layers[object]);
        }
        const renderer::Frame before = frame;
        std::vector<renderer::PixelRect> changed;
        renderer::compositeSpansChanges(layers, 0, rows, kClear, grid, frame, changed);
        renderer::Frame fresh;
        renderer::composite(layers, kWidth, kHeight, kClear, fresh);
        ASSERT_EQ(frame.rgba, fresh.rgba) << "step " << step;
        ASSERT_EQ(frame.depth, fresh.depth) << "step " << step;  // outside the spans nothing could change
        expectChangesCovered(before, frame, changed, renderer::PixelRect{0, 0, kWidth, kHeight}, grid);
    }
}
