// Quadtree of tiles for large scenes (CITY17, "A virtual globe-based time-critical adaptive
// visualization method for 3D city models", Int. J. Digital Earth 2017, §3; method.md §6).
//
// Objects are binned by the ground-plane (x, z) position of their bounding-sphere centre; a
// tile splits into four while it holds more than `leafCapacity` objects and is shallower than
// `maxDepth`. Every tile keeps the world box around all its objects' spheres, so a frame culls
// whole tiles against the frustum before it looks at a single object, and walks the visible
// leaves nearest first (the order of CITY17's Algorithm 1).
#pragma once

#include <array>
#include <glm/glm.hpp>
#include <vector>

#include "scheduler/importance.hpp"
#include "scheduler/scene_index.hpp"

namespace lodopt::scheduler {

struct QuadtreeParameters {
    int leafCapacity = 16;  // >= 1 objects per leaf before it splits
    int maxDepth = 10;      // >= 0 levels below the root
};

class Quadtree {
public:
    struct Tile {
        glm::vec3 low{0.0f}, high{0.0f};              // world box around the objects' spheres
        std::array<int, 4> children{-1, -1, -1, -1};  // tile indices, -1 for an empty quadrant
        bool leaf = true;
        int firstObject = 0;  // leaf: range in objects()
        int objectCount = 0;
        int depth = 0;
    };

    // `shapes` one per object (objects with radius 0 are left out). Throws
    // std::invalid_argument for bad parameters.
    Quadtree(const std::vector<ObjectShape>& shapes, const QuadtreeParameters& parameters = {});

    const std::vector<Tile>& tiles() const { return mTiles; }
    // Object indices, grouped by leaf.
    const std::vector<int>& objects() const { return mObjects; }
    int leafCount() const { return mLeaves; }

    // Leaves intersecting `frustum`, nearest first by the distance from `eye` to the leaf's box
    // (ties by tile index), into `out` (cleared; no allocation once it has grown).
    void visibleLeaves(const Frustum& frustum, glm::vec3 eye, std::vector<int>& out,
                       std::vector<double>& distanceScratch) const;

private:
    int build(std::vector<int>& objects, const std::vector<ObjectShape>& shapes, glm::vec2 low, glm::vec2 high,
              int depth, const QuadtreeParameters& parameters);

    std::vector<Tile> mTiles;
    std::vector<int> mObjects;
    int mLeaves = 0;
    mutable std::vector<int> mStack;
};

}  // namespace lodopt::scheduler
