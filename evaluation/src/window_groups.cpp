// Window groups: the analysis (which objects each window depends on) and the grouped state.
#include "window_groups.hpp"

#include <algorithm>
#include <bit>
#include <map>
#include <memory>
#include <unordered_map>

namespace lodopt::evaluation::detail {

namespace {

// Sets of variables, interned: id 0 is the empty set. Unions are memoised, because
// neighbouring pixels and windows mostly share their set.
class SetTable {
public:
    SetTable() { intern({}); }

    int unite(int a, int b) {
        if (a == b || b == 0) return a;
        if (a == 0) return b;
        if (a > b) std::swap(a, b);
        const std::uint64_t memoKey = (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
        const auto found = mUnions.find(memoKey);
        if (found != mUnions.end()) return found->second;
        std::vector<int> merged;
        std::set_union(mSets[std::size_t(a)].begin(), mSets[std::size_t(a)].end(), mSets[std::size_t(b)].begin(),
                       mSets[std::size_t(b)].end(), std::back_inserter(merged));
        const int id = intern(std::move(merged));
        mUnions.emplace(memoKey, id);
        return id;
    }
    int single(int variable) { return intern({variable}); }
    const std::vector<int>& set(int id) const { return mSets[std::size_t(id)]; }

private:
    int intern(std::vector<int> set) {
        const auto [at, added] = mIds.emplace(set, int(mSets.size()));
        if (added) mSets.push_back(std::move(set));
        return at->second;
    }
    std::vector<std::vector<int>> mSets;
    std::map<std::vector<int>, int> mIds;
    std::unordered_map<std::uint64_t, int> mUnions;
};

// Per position of a `window` x `window` box in a width x height grid of set ids, the union of
// the box: (width - window + 1) x (height - window + 1) ids, rows packed.
std::vector<int> boxUnions(const std::vector<int>& sets, int width, int height, int window, SetTable& table) {
    const int outWidth = width - window + 1, outHeight = height - window + 1;
    if (outWidth <= 0 || outHeight <= 0) return {};
    std::vector<int> rows(std::size_t(outWidth) * height), out(std::size_t(outWidth) * outHeight);
    for (int y = 0; y < height; ++y) {
        const int* in = sets.data() + std::size_t(y) * width;
        for (int x = 0; x < outWidth; ++x) {
            int acc = in[x];
            for (int k = 1; k < window; ++k) acc = table.unite(acc, in[x + k]);
            rows[std::size_t(y) * outWidth + x] = acc;
        }
    }
    for (int y = 0; y < outHeight; ++y) {
        for (int x = 0; x < outWidth; ++x) {
            int acc = rows[std::size_t(y) * outWidth + x];
            for (int k = 1; k < window; ++k) acc = table.unite(acc, rows[std::size_t(y + k) * outWidth + x]);
            out[std::size_t(y) * outWidth + x] = acc;
        }
    }
    return out;
}

renderer::PixelRect unite(const renderer::PixelRect& a, const renderer::PixelRect& b) {
    if (a.empty()) return b;
    return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

metrics::ImageView viewOf(const renderer::Frame& frame) {
    return metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4);
}

// Tiles of the lazy composite: small enough that a thin group composites little, large
// enough that compositing calls stay few.
constexpr int kTile = 32;

}  // namespace

WindowGroups::WindowGroups(const ViewSetup& setup, const VisibilityBounds& visibility,
                           const metrics::RegionScorer& scorer, std::size_t byteBudget)
    : mByteBudget(byteBudget) {
    const int width = setup.width(), height = setup.height();
    const std::vector<int>& objects = setup.variableObjects();
    const std::vector<int> counts = setup.levelCounts();
    SetTable table;
    // Per pixel, the variables whose option layers can show there (VisibilityBounds).
    std::vector<int> pixelSets(std::size_t(width) * height, 0);
    for (std::size_t v = 0; v < objects.size(); ++v) {
        const int single = table.single(int(v));
        for (int level : setup.objects()[objects[v]].optionLevels) {
            const renderer::Layer& layer = setup.layer(objects[v], level);
            const renderer::PixelRect& r = layer.rect;
            for (int y = std::max(r.y0, 0); y < std::min(r.y1, height); ++y) {
                const float* depth = layer.depth.data() + std::size_t(y - r.y0) * r.width();
                int* row = pixelSets.data() + std::size_t(y) * width;
                for (int x = std::max(r.x0, 0); x < std::min(r.x1, width); ++x) {
                    if (visibility.canShow(std::size_t(y) * width + x, objects[v], depth[x - r.x0])) {
                        row[x] = table.unite(row[x], single);
                    }
                }
            }
        }
    }
    std::vector<int> groupOfSet;  // set id -> group index, -1 while none
    auto groupFor = [&](int set) -> WindowGroup& {
        if (std::size_t(set) >= groupOfSet.size()) groupOfSet.resize(std::size_t(set) + 1, -1);
        if (groupOfSet[std::size_t(set)] < 0) {
            groupOfSet[std::size_t(set)] = int(mGroups.size());
            auto group = std::make_unique<WindowGroup>();
            group->variables = table.set(set);
            int shift = 0;
            for (int v : group->variables) {
                group->shifts.push_back(shift);
                shift += counts[std::size_t(v)] > 1 ? std::bit_width(unsigned(counts[std::size_t(v)] - 1)) : 0;
            }
            group->cacheable = shift <= 64;
            mGroups.push_back(std::move(group));
        }
        return *mGroups[std::size_t(groupOfSet[std::size_t(set)])];
    };
    // Runs of equal set ids on each row of `sets` (a grid of `gridWidth` columns) go to their
    // groups; `add` records one run (grid coordinates).
    auto collect = [&](const std::vector<int>& sets, int gridWidth, auto add) {
        if (gridWidth <= 0) return;
        const int gridHeight = int(sets.size() / std::size_t(gridWidth));
        for (int y = 0; y < gridHeight; ++y) {
            const int* row = sets.data() + std::size_t(y) * gridWidth;
            for (int x0 = 0; x0 < gridWidth;) {
                int x1 = x0 + 1;
                while (x1 < gridWidth && row[x1] == row[x0]) ++x1;
                add(groupFor(row[x0]), y, x0, x1);
                x0 = x1;
            }
        }
    };
    const metrics::SsimMapSize map = scorer.ssimMapSize();
    if (map.width > 0) {
        const int window = map.window;
        collect(boxUnions(pixelSets, width, height, window, table), map.width,
                [&](WindowGroup& group, int y, int x0, int x1) {
                    group.windows.ssim.push_back({y, x0, x1});
                    group.ssimWindows += std::uint64_t(x1 - x0);
                    group.inputs = unite(group.inputs, {x0, y, x1 + window - 1, y + window});
                });
    }
    if (scorer.sobelBins() > 0 && width >= 3 && height >= 3) {
        // Interior pixel (x, y) reads (x - 1 .. x + 1, y - 1 .. y + 1): grid cell (x - 1, y - 1).
        collect(boxUnions(pixelSets, width, height, 3, table), width - 2,
                [&](WindowGroup& group, int y, int x0, int x1) {
                    group.windows.sobel.push_back({y + 1, x0 + 1, x1 + 1});
                    group.inputs = unite(group.inputs, {x0, y, x1 + 2, y + 3});
                });
    }
    if (scorer.grayBins() > 0) {
        collect(pixelSets, width, [&](WindowGroup& group, int y, int x0, int x1) {
            group.windows.gray.push_back({y, x0, x1});
            group.pixels += std::uint64_t(x1 - x0);
            group.inputs = unite(group.inputs, {x0, y, x1, y + 1});
        });
    }
    mGroupsOf.resize(objects.size());
    for (std::size_t g = 0; g < mGroups.size(); ++g) {
        for (int v : mGroups[g]->variables) mGroupsOf[std::size_t(v)].push_back(std::uint32_t(g));
    }
}

std::size_t PackedScore::bytesFor(const metrics::WindowSetScore& score) {
    const std::size_t bytes = sizeof(PackedScore) + (score.gray.size() + score.sobel.size()) * sizeof(metrics::BinCount);
    return (bytes + alignof(PackedScore) - 1) / alignof(PackedScore) * alignof(PackedScore);
}

const PackedScore* PackedScore::pack(const metrics::WindowSetScore& score, void* where) {
    auto* packed = new (where) PackedScore;
    packed->ssim = score.ssim;
    packed->grayCount = std::uint32_t(score.gray.size());
    packed->sobelCount = std::uint32_t(score.sobel.size());
    auto* bins = reinterpret_cast<metrics::BinCount*>(packed + 1);
    std::uninitialized_copy(score.gray.begin(), score.gray.end(), bins);
    std::uninitialized_copy(score.sobel.begin(), score.sobel.end(), bins + score.gray.size());
    return packed;
}

void* ScoreArena::allocate(std::size_t bytes) {
    constexpr std::size_t unit = sizeof(std::max_align_t);
    static_assert(alignof(std::max_align_t) >= alignof(PackedScore));
    const std::size_t units = (bytes + unit - 1) / unit;
    std::lock_guard lock(mMutex);
    if (mChunks.empty() || mUsed + units > mCapacity) {
        mCapacity = std::max(kChunkBytes / unit, units);
        mChunks.push_back(std::make_unique_for_overwrite<std::max_align_t[]>(mCapacity));
        mUsed = 0;
    }
    void* at = mChunks.back().get() + mUsed;
    mUsed += units;
    return at;
}

WindowGroup::Slot& WindowGroup::slotFor(std::uint64_t key) {
    const std::size_t mask = slots.size() - 1;
    std::uint64_t hash = key * 0x9E3779B97F4A7C15ull;
    for (std::size_t i = std::size_t(hash ^ (hash >> 29)) & mask;; i = (i + 1) & mask) {
        if (!slots[i].score || slots[i].key == key) return slots[i];
    }
}

const PackedScore* WindowGroups::find(std::size_t g, std::uint64_t key) {
    WindowGroup& group = *mGroups[g];
    if (group.cacheable) {
        std::lock_guard lock(group.mutex);
        if (!group.slots.empty()) {
            if (const PackedScore* score = group.slotFor(key).score) {
                mHits.fetch_add(1, std::memory_order_relaxed);
                return score;
            }
        }
    }
    mMisses.fetch_add(1, std::memory_order_relaxed);
    return nullptr;
}

const PackedScore* WindowGroups::keep(std::size_t g, std::uint64_t key, const metrics::WindowSetScore& score) {
    WindowGroup& group = *mGroups[g];
    if (!group.cacheable) return nullptr;
    const std::size_t packedBytes = PackedScore::bytesFor(score);
    std::lock_guard lock(group.mutex);
    if (!group.slots.empty()) {
        if (const PackedScore* kept = group.slotFor(key).score) return kept;
    }
    // The memory counted: the packed score, and the table's growth when it would pass half full.
    const bool grow = 2 * (group.filled + 1) > group.slots.size();
    const std::size_t slotCount = grow ? std::max<std::size_t>(8, 2 * group.slots.size()) : group.slots.size();
    const std::uint64_t bytes = packedBytes + (slotCount - group.slots.size()) * sizeof(WindowGroup::Slot);
    if (mBytes.load(std::memory_order_relaxed) + bytes > mByteBudget) return nullptr;
    if (grow) {
        std::vector<WindowGroup::Slot> old(slotCount);
        old.swap(group.slots);
        for (const WindowGroup::Slot& slot : old) {
            if (slot.score) group.slotFor(slot.key) = slot;
        }
    }
    WindowGroup::Slot& slot = group.slotFor(key);
    slot.key = key;
    slot.score = PackedScore::pack(score, mArena.allocate(packedBytes));
    ++group.filled;
    mBytes.fetch_add(bytes, std::memory_order_relaxed);
    mEntries.fetch_add(1, std::memory_order_relaxed);
    return slot.score;
}

GroupCacheStats WindowGroups::stats() const {
    GroupCacheStats stats;
    stats.groups = int(mGroups.size());
    for (const auto& group : mGroups) {
        stats.ssimWindows += group->ssimWindows;
        if (group->variables.size() >= 2) stats.multiObjectSsimWindows += group->ssimWindows;
        stats.largestGroup = std::max(stats.largestGroup, int(group->variables.size()));
        stats.uncacheableGroups += group->cacheable ? 0 : 1;
    }
    stats.entries = mEntries.load();
    stats.bytes = mBytes.load();
    stats.hits = mHits.load();
    stats.misses = mMisses.load();
    return stats;
}

GroupState::GroupState(const ViewSetup& setup, const metrics::RegionScorer& scorer, WindowGroups& groups)
    : mSetup(setup), mScorer(scorer), mGroups(groups), mWork(scorer.makeWork()), mTotals(scorer.emptyTotals()) {
    mCurrent.assign(setup.variableObjects().size(), 0);
    const scenes::Combination levels = setup.toScene(mCurrent);
    for (std::size_t o = 0; o < levels.size(); ++o) mLayers.push_back(&setup.layer(int(o), levels[o]));
    mFrame.width = setup.width();
    mFrame.height = setup.height();
    mFrame.rgba.assign(std::size_t(mFrame.width) * mFrame.height * 4, 0);
    mFrame.depth.assign(std::size_t(mFrame.width) * mFrame.height, 1.0f);
    mTilesX = (mFrame.width + kTile - 1) / kTile;
    mTilesY = (mFrame.height + kTile - 1) / kTile;
    mTileEpoch.assign(std::size_t(mTilesX) * mTilesY, 0);
    mGroupEpoch.assign(groups.size(), 0);
    mApplied.resize(groups.size());
    mUnkept.resize(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g) mAffected.push_back(g);
    rescore(mAffected);
}

void GroupState::composite(const renderer::PixelRect& rect) {
    const int tx0 = std::max(rect.x0, 0) / kTile, tx1 = (std::min(rect.x1, mFrame.width) + kTile - 1) / kTile;
    const int ty0 = std::max(rect.y0, 0) / kTile, ty1 = (std::min(rect.y1, mFrame.height) + kTile - 1) / kTile;
    for (int ty = ty0; ty < ty1; ++ty) {
        // Stale tiles of a row in runs: one compositing call per run.
        for (int tx = tx0; tx < tx1;) {
            if (mTileEpoch[std::size_t(ty) * mTilesX + tx] == mEpoch) {
                ++tx;
                continue;
            }
            int end = tx;
            while (end < tx1 && mTileEpoch[std::size_t(ty) * mTilesX + end] != mEpoch) {
                mTileEpoch[std::size_t(ty) * mTilesX + end] = mEpoch;
                ++end;
            }
            const renderer::PixelRect tiles{tx * kTile, ty * kTile, std::min(end * kTile, mFrame.width),
                                            std::min((ty + 1) * kTile, mFrame.height)};
            renderer::compositeRect(mLayers, tiles, mSetup.clearColor(), mFrame);
            mScorer.loadPixels(*mWork, viewOf(mFrame), tiles.x0, tiles.y0, tiles.x1, tiles.y1);
            tx = end;
        }
    }
}

void GroupState::apply(std::size_t g, const PackedScore* score) {
    if (const PackedScore* old = mApplied[g]) mTotals.add(old->ssim, old->gray(), old->sobel(), -1);
    mTotals.add(score->ssim, score->gray(), score->sobel(), 1);
    mApplied[g] = score;
}

void GroupState::applyUnkept(std::size_t g, const metrics::WindowSetScore& score) {
    // The old score may live in the buffer the new one goes to: take it off first.
    if (const PackedScore* old = mApplied[g]) mTotals.add(old->ssim, old->gray(), old->sobel(), -1);
    mApplied[g] = nullptr;
    std::vector<std::max_align_t>& buffer = mUnkept[g];
    const std::size_t units = (PackedScore::bytesFor(score) + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t);
    if (buffer.size() < units) buffer.resize(units);
    apply(g, PackedScore::pack(score, buffer.data()));
}

void GroupState::rescore(std::span<const std::size_t> groups) {
    // Kept scores first; the rest are composited and scored together, so that windows of
    // groups that interleave are computed once (RegionScorer::scoreMany).
    mMisses.clear();
    for (std::size_t g : groups) {
        const std::uint64_t key = mGroups.group(g).key(mCurrent);
        if (const PackedScore* score = mGroups.find(g, key)) {
            apply(g, score);
        } else {
            mMisses.push_back({g, key});
        }
    }
    if (mMisses.empty()) return;
    mMissSets.clear();
    mMissOuts.clear();
    if (mMissScores.size() < mMisses.size()) mMissScores.resize(mMisses.size());
    for (std::size_t i = 0; i < mMisses.size(); ++i) {
        const WindowGroup& group = mGroups.group(mMisses[i].group);
        composite(group.inputs);
        mMissSets.push_back(&group.windows);
        mMissOuts.push_back(&mMissScores[i]);
    }
    mScorer.scoreMany(*mWork, mMissSets, mMissOuts);
    for (std::size_t i = 0; i < mMisses.size(); ++i) {
        const std::size_t g = mMisses[i].group;
        if (const PackedScore* kept = mGroups.keep(g, mMisses[i].key, mMissScores[i])) {
            apply(g, kept);
        } else {
            applyUnkept(g, mMissScores[i]);
        }
    }
}

void GroupState::moveTo(const optimizer::Combination& combination) {
    ++mEpoch;
    mAffected.clear();
    const std::vector<int>& objects = mSetup.variableObjects();
    for (std::size_t v = 0; v < combination.size(); ++v) {
        if (combination[v] == mCurrent[v]) continue;
        const int object = objects[v];
        mLayers[std::size_t(object)] = &mSetup.layer(object, mSetup.objects()[object].optionLevels[combination[v]]);
        mCurrent[v] = combination[v];
        for (std::uint32_t g : mGroups.groupsOf(v)) {
            if (mGroupEpoch[g] == mEpoch) continue;
            mGroupEpoch[g] = mEpoch;
            mAffected.push_back(g);
        }
    }
    rescore(mAffected);
}

const renderer::Frame& GroupState::image() {
    composite({0, 0, mFrame.width, mFrame.height});
    return mFrame;
}

}  // namespace lodopt::evaluation::detail
