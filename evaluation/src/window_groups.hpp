// Window groups: the fast path's default scoring (docs/optimizer.md "Window groups").
//
// Each metric window (an SSIM window, a pixel's Sobel neighbourhood, a pixel of the gray
// histogram) reads a few pixels, and each pixel's color depends only on the levels of the
// searched objects whose option layers can show there (cover it, and are not always behind
// another object: visibility.hpp; every other object is fixed). So a window's
// value is a function of the levels of one set of objects: the union over its pixels. Windows
// with the same set form a group; a group's score (metrics::WindowSetScore: its SSIM windows'
// fixed-point sum and its histogram counts) is a function of those objects' levels alone,
// and the image's metrics are the sum of every group's score (metrics::RegionScorer).
//
// A candidate is then scored by re-scoring only the groups of the objects whose level changed,
// each looked up by its objects' levels in a cache shared by all evaluation states and
// threads; a miss composites just the pixels that group reads, scores it and keeps the score.
// Repeated sub-combinations (a swarm revisits them constantly) cost a hash lookup and a
// histogram update; kept scores are packed into an arena and looked up in flat tables. The result is bit-identical to a from-scratch evaluation: every score
// comes from the same per-window kernels and all sums are integers.
#pragma once

#include <atomic>
#include <cstdint>
#include <cstddef>
#include <memory>
#include <mutex>
#include <new>
#include <span>
#include <vector>

#include "evaluation/evaluation.hpp"
#include "metrics/region_scorer.hpp"
#include "visibility.hpp"

namespace lodopt::evaluation::detail {

// A kept score packed in one block: the SSIM sum, then the gray and Sobel (bin, count) pairs.
struct PackedScore {
    metrics::SsimFixedSum ssim = 0;
    std::uint32_t grayCount = 0, sobelCount = 0;

    std::span<const metrics::BinCount> gray() const { return {bins(), grayCount}; }
    std::span<const metrics::BinCount> sobel() const { return {bins() + grayCount, sobelCount}; }
    // Bytes a packed copy of `score` takes (a multiple of alignof(PackedScore)).
    static std::size_t bytesFor(const metrics::WindowSetScore& score);
    // Packs `score` into `where`: bytesFor(score) bytes aligned for PackedScore.
    static const PackedScore* pack(const metrics::WindowSetScore& score, void* where);

private:
    const metrics::BinCount* bins() const {
        return std::launder(reinterpret_cast<const metrics::BinCount*>(this + 1));
    }
};

// Memory the kept scores are packed into. It only grows (until the evaluator goes), so a kept
// score's address stays valid and a lookup hands out a plain pointer: no allocation per score,
// no reference count to touch on a cold cache line.
class ScoreArena {
public:
    // `bytes` aligned for PackedScore; thread-safe.
    void* allocate(std::size_t bytes);

private:
    static constexpr std::size_t kChunkBytes = std::size_t(1) << 20;
    std::mutex mMutex;
    std::vector<std::unique_ptr<std::max_align_t[]>> mChunks;
    std::size_t mUsed = 0, mCapacity = 0;  // in the last chunk
};

struct WindowGroup {
    std::vector<int> variables;        // sorted optimizer variables whose levels it depends on
    std::vector<int> shifts;           // bit offset of each variable's option in the key
    bool cacheable = true;             // the key fits in 64 bits
    metrics::WindowSet windows;        // its SSIM windows, gray pixels and Sobel pixels
    renderer::PixelRect inputs;        // every pixel its windows read
    std::uint64_t ssimWindows = 0, pixels = 0;

    std::uint64_t key(const optimizer::Combination& combination) const {
        std::uint64_t key = 0;
        for (std::size_t i = 0; i < variables.size(); ++i) {
            key |= std::uint64_t(combination[std::size_t(variables[i])]) << shifts[i];
        }
        return key;
    }

    // Kept scores by key: open addressing with linear probing, at most half full; a slot
    // without a score is free. Guarded by `mutex`.
    struct Slot {
        std::uint64_t key = 0;
        const PackedScore* score = nullptr;
    };
    std::mutex mutex;
    std::vector<Slot> slots;
    std::size_t filled = 0;
    // The slot holding `key`, or the free slot where it would go (slots must not be empty).
    Slot& slotFor(std::uint64_t key);
};

class WindowGroups {
public:
    // Analyses the view: which searched objects each window of `scorer`'s metrics depends on
    // (those that can show at its pixels, by `visibility`). Scores are kept while their memory
    // stays under `byteBudget`.
    WindowGroups(const ViewSetup& setup, const VisibilityBounds& visibility, const metrics::RegionScorer& scorer,
                 std::size_t byteBudget);

    std::size_t size() const { return mGroups.size(); }
    WindowGroup& group(std::size_t g) { return *mGroups[g]; }
    const WindowGroup& group(std::size_t g) const { return *mGroups[g]; }
    // The groups that depend on variable v.
    const std::vector<std::uint32_t>& groupsOf(std::size_t v) const { return mGroupsOf[v]; }

    // The kept score of group g for `key`, or null.
    const PackedScore* find(std::size_t g, std::uint64_t key);
    // Keeps a packed copy of `score` for `key` when the group is cacheable and the budget
    // allows, and returns the score kept for the key (equal to `score`: another thread may have
    // kept one first); null when none is kept.
    const PackedScore* keep(std::size_t g, std::uint64_t key, const metrics::WindowSetScore& score);

    GroupCacheStats stats() const;

private:
    std::vector<std::unique_ptr<WindowGroup>> mGroups;
    std::vector<std::vector<std::uint32_t>> mGroupsOf;
    ScoreArena mArena;
    std::size_t mByteBudget = 0;
    std::atomic<std::uint64_t> mBytes{0}, mEntries{0}, mHits{0}, mMisses{0};
};

// One evaluation state of the grouped fast path: the current combination, the score each group
// has in it and their totals. Pixels are composited only when a group must be scored, and only
// over tiles that group reads.
class GroupState {
public:
    GroupState(const ViewSetup& setup, const metrics::RegionScorer& scorer, WindowGroups& groups);

    const optimizer::Combination& current() const { return mCurrent; }
    void moveTo(const optimizer::Combination& combination);
    metrics::MetricResult result() const { return mScorer.result(mTotals); }
    // The composite of the current combination, whole.
    const renderer::Frame& image();

private:
    // Composites (and loads into the scorer's gray) every tile of `rect` not yet composited for
    // the current combination.
    void composite(const renderer::PixelRect& rect);
    // Re-scores `groups` for the current combination: kept scores, else computed together.
    void rescore(std::span<const std::size_t> groups);
    // Makes `score` group g's applied score (the totals follow).
    void apply(std::size_t g, const PackedScore* score);
    // The same for a score the cache did not keep: packed into the state's own copy for g.
    void applyUnkept(std::size_t g, const metrics::WindowSetScore& score);

    const ViewSetup& mSetup;
    const metrics::RegionScorer& mScorer;
    WindowGroups& mGroups;
    optimizer::Combination mCurrent;
    std::vector<const renderer::Layer*> mLayers;  // per scene object, the current layer
    renderer::Frame mFrame;
    metrics::RegionScorer::WorkPtr mWork;
    std::vector<const PackedScore*> mApplied;                  // per group
    std::vector<std::vector<std::max_align_t>> mUnkept;        // per group, its unkept score
    metrics::WindowTotals mTotals;
    std::uint64_t mEpoch = 1;                  // bumped per move
    std::vector<std::uint64_t> mTileEpoch;     // per tile, the epoch it was composited in
    std::vector<std::uint64_t> mGroupEpoch;    // per group, the epoch it was last re-scored in
    std::vector<std::size_t> mAffected;
    struct Miss {
        std::size_t group;
        std::uint64_t key;
    };
    std::vector<Miss> mMisses;
    std::vector<const metrics::WindowSet*> mMissSets;
    std::vector<metrics::WindowSetScore> mMissScores;  // scratch, reused
    std::vector<metrics::WindowSetScore*> mMissOuts;
    int mTilesX = 0, mTilesY = 0;
};

}  // namespace lodopt::evaluation::detail
