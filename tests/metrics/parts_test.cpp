// IncrementalEvaluator with parts (PartCache): owned windows come from the cache, yet after
// any sequence of part moves the result equals a from-scratch evaluate() of the image to the
// bit, map included; bad partitions and moves are MetricErrors.
#include <gtest/gtest.h>

#include <random>

#include "metrics/incremental_evaluator.hpp"
#include "metrics/metrics.hpp"
#include "test_images.hpp"

namespace lodopt::metrics {
namespace {

using testing::hash32;
using testing::TestImage;

// A synthetic layered image: part k covers an ellipse that depends on its state (coarser
// states are smaller, as coarser levels of an object cover a little less), textured by (k,
// state); where parts overlap the lower index wins (the renderer's tie rule). Everything else is
// a constant textured background.
struct PartScene {
    int width, height, channels;
    struct Ellipse {
        int cx, cy, rx, ry;
    };
    std::vector<Ellipse> parts;
    int states = 4;

    bool covers(int k, int state, int x, int y) const {
        const Ellipse& e = parts[std::size_t(k)];
        const double rx = e.rx * (1.0 - 0.12 * state), ry = e.ry * (1.0 - 0.12 * state);
        const double dx = (x - e.cx) / rx, dy = (y - e.cy) / ry;
        return dx * dx + dy * dy <= 1.0;
    }
    TestImage render(const std::vector<int>& state) const {
        TestImage image(width, height, channels);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                int owner = -1;
                for (int k = 0; k < int(parts.size()) && owner < 0; ++k) {
                    if (covers(k, state[std::size_t(k)], x, y)) owner = k;
                }
                for (int c = 0; c < channels; ++c) {
                    const std::uint32_t h =
                        owner < 0 ? hash32(x / 3, y / 3, c, 99)
                                  : hash32(x, y, c, std::uint32_t(100 + owner * 16 + state[std::size_t(owner)]));
                    image.at(x, y)[c] = std::uint8_t(owner < 0 ? 120 + h % 40 : (h % 256));
                }
            }
        }
        return image;
    }
    // Which part each pixel depends on: every state of each part counts.
    std::vector<std::int32_t> pixelParts() const {
        std::vector<std::int32_t> owners(std::size_t(width) * height, kConstantPixel);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                std::int32_t& owner = owners[std::size_t(y) * width + x];
                for (int k = 0; k < int(parts.size()); ++k) {
                    bool any = false;
                    for (int s = 0; s < states && !any; ++s) any = covers(k, s, x, y);
                    if (!any) continue;
                    owner = owner == kConstantPixel ? k : kSharedPixel;
                }
            }
        }
        return owners;
    }
    // A rectangle holding every pixel part k covers in any state.
    UpdateRect bounds(int k) const {
        const Ellipse& e = parts[std::size_t(k)];
        return {e.cx - e.rx - 1, e.cy - e.ry - 1, e.cx + e.rx + 2, e.cy + e.ry + 2};
    }
};

PartScene makeScene(int width, int height, int channels) {
    // Two lone parts, two overlapping ones, one touching the image border.
    return {width,
            height,
            channels,
            {{width / 5, height / 4, width / 8, height / 6},
             {width / 2, height / 2, width / 6, height / 5},
             {width / 2 + width / 8, height / 2 + height / 8, width / 7, height / 6},
             {width - width / 10, height - height / 8, width / 6, height / 5},
             {width / 5, height - height / 4, width / 10, height / 10}}};
}

void expectSameBits(const MetricResult& a, const MetricResult& b) {
    EXPECT_EQ(a.ssim, b.ssim);
    EXPECT_EQ(a.boundaryEntropy.candidate, b.boundaryEntropy.candidate);
    EXPECT_EQ(a.informationEntropy.candidate, b.informationEntropy.candidate);
    EXPECT_EQ(a.truePositives, b.truePositives);
    EXPECT_EQ(a.falsePositives, b.falsePositives);
    EXPECT_EQ(a.fitness, b.fitness);
}

struct Case {
    const char* name;
    int width, height, channels;
    MetricParameters parameters;
};

std::vector<Case> cases() {
    MetricParameters paper;
    paper.boundaryEntropyMode = EntropyMode::Paper;
    paper.informationEntropyMode = EntropyMode::Paper;
    MetricParameters other;
    other.grayWeights = GrayWeights::Bt709;
    other.ssimWindow = 7;
    other.ssimSigma = 1.1;
    other.boundaryHistogramBins = 1000;
    MetricParameters ssimOnly;
    ssimOnly.boundaryEntropyWeight = 0;
    ssimOnly.informationEntropyWeight = 0;
    ssimOnly.computePrecisionRecall = false;
    MetricParameters entropiesOnly;
    entropiesOnly.ssimWeight = 0;
    return {{"default rgba", 160, 120, 4, {}},   {"tall gray", 70, 150, 1, {}},
            {"paper modes", 120, 90, 3, paper},  {"bt709 window 7 1000 bins", 130, 100, 4, other},
            {"ssim only", 150, 80, 3, ssimOnly}, {"entropies only", 100, 100, 3, entropiesOnly}};
}

TEST(PartCache, RandomMovesGiveTheSameBitsAsFromScratch) {
    for (const Case& c : cases()) {
        SCOPED_TRACE(c.name);
        const PartScene scene = makeScene(c.width, c.height, c.channels);
        const int partCount = int(scene.parts.size());
        std::vector<int> state(std::size_t(partCount), 0);
        const TestImage reference = scene.render(state);
        const std::vector<int> counts(std::size_t(partCount), scene.states);
        auto cache = makePartCache(c.width, c.height, c.parameters, scene.pixelParts(), counts);
        IncrementalEvaluator evaluator(reference.view(), c.parameters);
        evaluator.setParts(cache, reference.view(), state);
        ASSERT_TRUE(evaluator.hasParts());
        expectSameBits(evaluator.result(), evaluate(reference.view(), reference.view(), c.parameters));
        std::mt19937 rng(5);
        for (int step = 0; step < 30; ++step) {
            std::vector<PartMove> moves;
            std::vector<UpdateRect> rects;
            const int changes = 1 + int(rng() % 3);
            for (int m = 0; m < changes; ++m) {
                const int k = int(rng() % std::uint32_t(partCount));
                state[std::size_t(k)] = int(rng() % std::uint32_t(scene.states));
                moves.push_back({k, state[std::size_t(k)]});
                rects.push_back(scene.bounds(k));
            }
            const TestImage image = scene.render(state);
            evaluator.update(image.view(), rects, moves);
            SCOPED_TRACE(step);
            expectSameBits(evaluator.result(), evaluate(image.view(), reference.view(), c.parameters));
            if (c.parameters.ssimWeight > 0 && step % 10 == 9) {
                const SsimMapSize size = evaluator.ssimMapSize();
                std::vector<double> map(std::size_t(size.width) * size.height);
                ssimMap(image.view(), reference.view(), c.parameters, map.data(), std::size_t(size.width));
                for (std::size_t i = 0; i < map.size(); ++i) ASSERT_EQ(evaluator.ssimMap()[i], map[i]) << i;
            }
        }
        const PartCacheStats stats = partCacheStats(*cache);
        EXPECT_EQ(stats.parts, partCount);
        EXPECT_EQ(stats.entries, std::uint64_t(partCount * scene.states));
        EXPECT_GT(stats.filledEntries, std::uint64_t(partCount));
        if (c.parameters.ssimWeight > 0) {
            EXPECT_GT(stats.ownedSsimWindows, 0u);
            EXPECT_GT(stats.liveSsimWindows, 0u);  // parts 1 and 2 overlap
        }
    }
}

TEST(PartCache, TwoEvaluatorsShareOneCache) {
    const PartScene scene = makeScene(140, 110, 3);
    const std::vector<int> counts(scene.parts.size(), scene.states);
    std::vector<int> state(scene.parts.size(), 0);
    const TestImage reference = scene.render(state);
    auto cache = makePartCache(140, 110, {}, scene.pixelParts(), counts);
    IncrementalEvaluator first(reference.view(), {}), second(reference.view(), {});
    first.setParts(cache, reference.view(), state);
    second.setParts(cache, reference.view(), state);
    // The first fills part 3's state 2; the second then only copies it.
    state[3] = 2;
    const TestImage image = scene.render(state);
    const std::vector<UpdateRect> rects = {scene.bounds(3)};
    const std::vector<PartMove> moves = {{3, 2}};
    first.update(image.view(), rects, moves);
    const std::uint64_t filled = partCacheStats(*cache).filledEntries;
    second.update(image.view(), rects, moves);
    EXPECT_EQ(partCacheStats(*cache).filledEntries, filled);
    expectSameBits(first.result(), second.result());
    expectSameBits(second.result(), evaluate(image.view(), reference.view(), {}));
}

TEST(PartCache, APartListedTwiceEndsInItsLastState) {
    // Moves 3 -> 2 -> 1 from state 1 leave part 3 where it was: nothing changes and state 2's
    // entry is not filled from an image that does not show it.
    const PartScene scene = makeScene(120, 100, 3);
    const std::vector<int> counts(scene.parts.size(), scene.states);
    std::vector<int> state(scene.parts.size(), 1);
    const TestImage image = scene.render(state);
    const TestImage reference = scene.render(std::vector<int>(scene.parts.size(), 0));
    auto cache = makePartCache(120, 100, {}, scene.pixelParts(), counts);
    IncrementalEvaluator evaluator(reference.view(), {});
    evaluator.setParts(cache, image.view(), state);
    const MetricResult before = evaluator.result();
    const std::uint64_t filled = partCacheStats(*cache).filledEntries;
    evaluator.update(image.view(), {}, std::vector<PartMove>{{3, 2}, {3, 1}});
    expectSameBits(evaluator.result(), before);
    EXPECT_EQ(partCacheStats(*cache).filledEntries, filled);
    // And 3 -> 0 -> 2 ends in 2, the state the image shows.
    state[3] = 2;
    const TestImage moved = scene.render(state);
    const std::vector<UpdateRect> rects = {scene.bounds(3)};
    evaluator.update(moved.view(), rects, std::vector<PartMove>{{3, 0}, {3, 2}});
    expectSameBits(evaluator.result(), evaluate(moved.view(), reference.view(), {}));
    EXPECT_EQ(partCacheStats(*cache).filledEntries, filled + 1);
}

TEST(PartCache, BadPartitionsAndMovesAreErrors) {
    const std::vector<std::int32_t> parts(20 * 10, kConstantPixel);
    const std::vector<int> counts = {2, 3};
    EXPECT_THROW(makePartCache(20, 11, {}, parts, counts), MetricError);  // size
    std::vector<std::int32_t> badPart = parts;
    badPart[5] = 2;  // only parts 0 and 1 exist
    EXPECT_THROW(makePartCache(20, 10, {}, badPart, counts), MetricError);
    EXPECT_THROW(makePartCache(20, 10, {}, parts, std::vector<int>{2, 0}), MetricError);  // no states

    const TestImage image(20, 10, 3, 100);
    IncrementalEvaluator evaluator(image.view(), {});
    const std::vector<PartMove> move = {{0, 1}};
    EXPECT_THROW(evaluator.update(image.view(), {}, move), MetricError);  // no parts yet
    auto cache = makePartCache(20, 10, {}, parts, counts);
    EXPECT_THROW(evaluator.setParts(cache, image.view(), std::vector<int>{0}), MetricError);     // one state short
    EXPECT_THROW(evaluator.setParts(cache, image.view(), std::vector<int>{0, 3}), MetricError);  // out of range
    MetricParameters other;
    other.ssimWindow = 7;
    IncrementalEvaluator mismatched(image.view(), other);
    EXPECT_THROW(mismatched.setParts(cache, image.view(), std::vector<int>{0, 0}), MetricError);
    evaluator.setParts(cache, image.view(), std::vector<int>{0, 0});
    EXPECT_THROW(evaluator.update(image.view(), {}, std::vector<PartMove>{{1, 3}}), MetricError);
    EXPECT_THROW(evaluator.update(image.view(), {}, std::vector<PartMove>{{2, 0}}), MetricError);
    // setCandidate drops the parts.
    evaluator.setCandidate(image.view());
    EXPECT_FALSE(evaluator.hasParts());
}

}  // namespace
}  // namespace lodopt::metrics
