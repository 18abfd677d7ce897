// Quadtree of tiles after CITY17 §3 (see scheduler/tiles.hpp).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "scheduler/tiles.hpp"

namespace lodopt::scheduler {

Quadtree::Quadtree(const std::vector<ObjectShape>& shapes, const QuadtreeParameters& parameters) {
    if (parameters.leafCapacity < 1) {
        throw std::invalid_argument("quadtree: leafCapacity = " + std::to_string(parameters.leafCapacity) +
                                    ", must be >= 1");
    }
    if (parameters.maxDepth < 0 || parameters.maxDepth > 30) {
        throw std::invalid_argument("quadtree: maxDepth = " + std::to_string(parameters.maxDepth) +
                                    ", must be in [0, 30]");
    }
    std::vector<int> objects;
    glm::vec2 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (int o = 0; o < int(shapes.size()); ++o) {
        if (shapes[o].radius <= 0.0f) continue;
        objects.push_back(o);
        const glm::vec2 p(shapes[o].center.x, shapes[o].center.z);
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    if (objects.empty()) {
        low = high = glm::vec2(0.0f);
    }
    // A square root tile, so that tiles stay square at every depth.
    const glm::vec2 center = 0.5f * (low + high);
    const float half = 0.5f * std::max(high.x - low.x, high.y - low.y) * 1.0001f + 1e-3f;
    mTiles.reserve(2 * objects.size() / std::size_t(parameters.leafCapacity) + 8);
    mObjects.reserve(objects.size());
    build(objects, shapes, center - half, center + half, 0, parameters);
}

int Quadtree::build(std::vector<int>& objects, const std::vector<ObjectShape>& shapes, glm::vec2 low, glm::vec2 high,
                    int depth, const QuadtreeParameters& parameters) {
    Tile tile;
    tile.depth = depth;
    tile.low = glm::vec3(std::numeric_limits<float>::max());
    tile.high = glm::vec3(-std::numeric_limits<float>::max());
    for (int o : objects) {
        tile.low = glm::min(tile.low, shapes[o].center - glm::vec3(shapes[o].radius));
        tile.high = glm::max(tile.high, shapes[o].center + glm::vec3(shapes[o].radius));
    }
    if (objects.empty()) tile.low = tile.high = glm::vec3(0.0f);
    const int index = int(mTiles.size());
    if (int(objects.size()) <= parameters.leafCapacity || depth >= parameters.maxDepth) {
        tile.firstObject = int(mObjects.size());
        tile.objectCount = int(objects.size());
        mObjects.insert(mObjects.end(), objects.begin(), objects.end());
        ++mLeaves;
        mTiles.push_back(tile);
        return index;
    }
    tile.leaf = false;
    mTiles.push_back(tile);
    const glm::vec2 mid = 0.5f * (low + high);
    std::vector<int> quadrants[4];
    for (int o : objects) {
        const int q = (shapes[o].center.x >= mid.x ? 1 : 0) + (shapes[o].center.z >= mid.y ? 2 : 0);
        quadrants[q].push_back(o);
    }
    for (int q = 0; q < 4; ++q) {
        if (quadrants[q].empty()) continue;
        const glm::vec2 childLow(q & 1 ? mid.x : low.x, q & 2 ? mid.y : low.y);
        const glm::vec2 childHigh(q & 1 ? high.x : mid.x, q & 2 ? high.y : mid.y);
        const int child = build(quadrants[q], shapes, childLow, childHigh, depth + 1, parameters);
        mTiles[index].children[q] = child;  // by index: build() may have reallocated mTiles
    }
    return index;
}

void Quadtree::visibleLeaves(const Frustum& frustum, glm::vec3 eye, std::vector<int>& out,
                             std::vector<double>& distanceScratch) const {
    out.clear();
    if (mTiles.empty()) return;
    mStack.clear();
    mStack.push_back(0);
    while (!mStack.empty()) {
        const int index = mStack.back();
        mStack.pop_back();
        const Tile& tile = mTiles[index];
        if (tile.leaf && tile.objectCount == 0) continue;
        if (!frustum.intersectsBox(tile.low, tile.high)) continue;
        if (tile.leaf) {
            out.push_back(index);
        } else {
            for (int q = 3; q >= 0; --q) {
                if (tile.children[q] >= 0) mStack.push_back(tile.children[q]);
            }
        }
    }
    distanceScratch.resize(mTiles.size());
    for (int index : out) {
        const Tile& tile = mTiles[index];
        const glm::vec3 nearest = glm::clamp(eye, tile.low, tile.high);
        distanceScratch[index] = double(glm::length(nearest - eye));
    }
    std::sort(out.begin(), out.end(), [&](int a, int b) {
        return distanceScratch[a] != distanceScratch[b] ? distanceScratch[a] < distanceScratch[b] : a < b;
    });
}

}  // namespace lodopt::scheduler
