// RegionScorer: the scores of a partition of every window and pixel add up to evaluate()'s
// result, to the bit, whatever the partition.
#include <gtest/gtest.h>

#include <random>

#include "metrics/region_scorer.hpp"
#include "test_images.hpp"

using namespace lodopt::metrics;
namespace images = lodopt::metrics::testing;
using images::TestImage;

namespace {

MetricParameters searchLike() {
    MetricParameters p;
    p.computePrecisionRecall = false;
    return p;
}

// Every SSIM window, gray pixel and interior pixel of a width x height image, split by rows
// and columns into `pieces` x `pieces` rectangles, one set each (runs row by row).
std::vector<WindowSet> gridPartition(int width, int height, const SsimMapSize& map, int pieces) {
    std::vector<WindowSet> sets(std::size_t(pieces) * pieces);
    auto split = [&](int x, int y, int w, int h) {
        return std::size_t(std::min(y * pieces / h, pieces - 1)) * pieces + std::size_t(std::min(x * pieces / w, pieces - 1));
    };
    auto addRuns = [&](int x0, int x1, int y0, int y1, int w, int h, auto member) {
        for (int y = y0; y < y1; ++y) {
            for (int x = x0; x < x1;) {
                const std::size_t set = split(x, y, w, h);
                int end = x + 1;
                while (end < x1 && split(end, y, w, h) == set) ++end;
                (sets[set].*member).push_back({y, x, end});
                x = end;
            }
        }
    };
    addRuns(0, map.width, 0, map.height, map.width, map.height, &WindowSet::ssim);
    addRuns(0, width, 0, height, width, height, &WindowSet::gray);
    addRuns(1, width - 1, 1, height - 1, width, height, &WindowSet::sobel);
    return sets;
}

}  // namespace

TEST(RegionScorer, PartitionScoresAddUpToEvaluateToTheBit) {
    const MetricParameters p = searchLike();
    for (const auto& [width, height] : {std::pair{64, 48}, std::pair{131, 77}}) {
        const TestImage reference = images::generateNoise(width, height, 4, 1);
        TestImage candidate = images::generateNoise(width, height, 4, 2);
        // Half the candidate equals the reference: windows there are exactly 1.
        for (int y = 0; y < height / 2; ++y) {
            std::copy_n(reference.at(0, y), width * 4, candidate.at(0, y));
        }
        const MetricResult expected = evaluate(candidate.view(), reference.view(), p);
        RegionScorer scorer(reference.view(), p);
        auto work = scorer.makeWork();
        scorer.loadPixels(*work, candidate.view(), 0, 0, width, height);
        for (int pieces : {1, 3, 7}) {
            WindowTotals totals = scorer.emptyTotals();
            for (const WindowSet& set : gridPartition(width, height, scorer.ssimMapSize(), pieces)) {
                WindowSetScore score;
                scorer.score(*work, set, score);
                totals.add(score, 1);
            }
            const MetricResult got = scorer.result(totals);
            SCOPED_TRACE(std::to_string(width) + "x" + std::to_string(height) + " in " + std::to_string(pieces) + "^2 sets");
            EXPECT_EQ(got.ssim, expected.ssim);
            EXPECT_EQ(got.boundaryEntropy.candidate, expected.boundaryEntropy.candidate);
            EXPECT_EQ(got.informationEntropy.candidate, expected.informationEntropy.candidate);
            EXPECT_EQ(got.fitness, expected.fitness);
            EXPECT_LT(got.fitness, 1.0);
        }
    }
}

TEST(RegionScorer, RemovingAScoreUndoesIt) {
    const MetricParameters p = searchLike();
    const TestImage reference = images::generateNoise(40, 40, 3, 4);
    const TestImage other = images::generateNoise(40, 40, 3, 5);
    RegionScorer scorer(reference.view(), p);
    auto work = scorer.makeWork();
    const std::vector<WindowSet> sets = gridPartition(40, 40, scorer.ssimMapSize(), 2);
    // The reference's scores, then one set swapped to the other image's and back.
    scorer.loadPixels(*work, reference.view(), 0, 0, 40, 40);
    WindowTotals totals = scorer.emptyTotals();
    std::vector<WindowSetScore> scores(sets.size());
    for (std::size_t k = 0; k < sets.size(); ++k) {
        scorer.score(*work, sets[k], scores[k]);
        totals.add(scores[k], 1);
    }
    EXPECT_EQ(scorer.result(totals).fitness, 1.0);
    scorer.loadPixels(*work, other.view(), 0, 0, 40, 40);
    WindowSetScore swapped;
    scorer.score(*work, sets[1], swapped);
    totals.add(scores[1], -1);
    totals.add(swapped, 1);
    EXPECT_LT(scorer.result(totals).fitness, 1.0);
    totals.add(swapped, -1);
    totals.add(scores[1], 1);
    EXPECT_EQ(scorer.result(totals).fitness, 1.0);
}

TEST(RegionScorer, RefusesWhatIsNotAWindowSum) {
    const TestImage reference = images::generateNoise(16, 16, 4, 1);
    MetricParameters withPrecision;  // precision/recall on by default
    EXPECT_FALSE(RegionScorer::supports(withPrecision));
    EXPECT_THROW(RegionScorer(reference.view(), withPrecision), MetricError);
    MetricParameters paper = searchLike();
    paper.boundaryEntropyMode = EntropyMode::Paper;
    EXPECT_FALSE(RegionScorer::supports(paper));
    paper.boundaryEntropyWeight = 0;  // not computed: no longer matters
    EXPECT_TRUE(RegionScorer::supports(paper));
    RegionScorer scorer(reference.view(), searchLike());
    auto work = scorer.makeWork();
    const TestImage wrongSize = images::generateNoise(15, 16, 4, 1);
    EXPECT_THROW(scorer.loadPixels(*work, wrongSize.view(), 0, 0, 15, 16), MetricError);
}

// scoreMany computes the windows of several sets in shared rectangles; each set must get what
// score() gives it alone. Sets that interleave on every row (a random owner per run of 1-9
// windows), runs far from the rest on some rows (rectangles of their own, not at column 0 nor
// at a band's first row) and a set with no SSIM window.
TEST(RegionScorer, ScoringSetsTogetherGivesEachSetsOwnScore) {
    const MetricParameters p = searchLike();
    const int width = 150, height = 70;
    const TestImage reference = images::generateNoise(width, height, 4, 8);
    TestImage candidate = images::generateNoise(width, height, 4, 9);
    for (int y = 0; y < height / 3; ++y) std::copy_n(reference.at(0, y), width * 4, candidate.at(0, y));
    RegionScorer scorer(reference.view(), p);
    auto work = scorer.makeWork();
    scorer.loadPixels(*work, candidate.view(), 0, 0, width, height);
    const SsimMapSize map = scorer.ssimMapSize();
    std::mt19937 random(11);
    std::vector<WindowSet> sets(6);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < 60;) {
            const int end = std::min(60, x + 1 + int(random() % 9));
            sets[random() % 5].ssim.push_back({y, x, end});
            x = end;
        }
        // Runs far from the others (their own rectangles), on some rows only.
        if (y % 7 < 3) sets[3].ssim.push_back({y, 90, 97});
        if (y >= 20 && y < 26) sets[4].ssim.push_back({y, 120, std::min(131, map.width)});
    }
    sets[5].gray.push_back({3, 10, 40});  // histogram pixels only
    sets[5].sobel.push_back({4, 10, 40});
    sets[0].gray.push_back({5, 0, width});
    std::vector<WindowSetScore> alone(sets.size()), together(sets.size());
    for (std::size_t k = 0; k < sets.size(); ++k) scorer.score(*work, sets[k], alone[k]);
    std::vector<const WindowSet*> setPointers;
    std::vector<WindowSetScore*> outPointers;
    for (std::size_t k = 0; k < sets.size(); ++k) {
        setPointers.push_back(&sets[k]);
        together[k].ssim = 12345;  // overwritten
        outPointers.push_back(&together[k]);
    }
    scorer.scoreMany(*work, setPointers, outPointers);
    for (std::size_t k = 0; k < sets.size(); ++k) {
        SCOPED_TRACE("set " + std::to_string(k));
        EXPECT_TRUE(alone[k].ssim == together[k].ssim);
        EXPECT_EQ(alone[k].gray, together[k].gray);
        EXPECT_EQ(alone[k].sobel, together[k].sobel);
    }
    EXPECT_TRUE(alone[0].ssim != 0);
    EXPECT_TRUE(together[5].ssim == 0);
    // Two sets, one of them empty, and a single set: the same answers.
    scorer.scoreMany(*work, std::span<const WindowSet* const>(setPointers.data() + 4, 2),
                     std::span<WindowSetScore* const>(outPointers.data() + 4, 2));
    EXPECT_TRUE(together[4].ssim == alone[4].ssim);
    scorer.scoreMany(*work, std::span<const WindowSet* const>(setPointers.data(), 1),
                     std::span<WindowSetScore* const>(outPointers.data(), 1));
    EXPECT_TRUE(together[0].ssim == alone[0].ssim);
    EXPECT_THROW(scorer.scoreMany(*work, std::span<const WindowSet* const>(setPointers.data(), 2),
                                  std::span<WindowSetScore* const>(outPointers.data(), 1)),
                 MetricError);
}
