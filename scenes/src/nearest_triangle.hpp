// The nearest point of a triangle set to a point, for the geometric error
// (geometric_error.cpp): Ericson's closest point on a triangle (Real-Time Collision Detection,
// 2005, §5.1.5) and a bounding-volume hierarchy split by the binned surface area heuristic (Wald
// 2007, "On fast construction of SAH-based bounding volume hierarchies"), so that a query does not
// visit every triangle. Everything is in double; the result is a minimum over all triangles, so
// it does not depend on the tree's shape.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

namespace lodopt::scenes::detail {

using Point = glm::dvec3;

struct Box {
    Point min{std::numeric_limits<double>::max()};
    Point max{-std::numeric_limits<double>::max()};
    void add(const Point& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void add(const Box& box) {
        min = glm::min(min, box.min);
        max = glm::max(max, box.max);
    }
    bool empty() const { return max.x < min.x; }
    double diagonal() const { return empty() ? 0.0 : glm::length(max - min); }
    // Squared distance from `p` to the box (0 inside): a lower bound for every triangle in it.
    double distanceSquared(const Point& p) const {
        // Per axis the distance outside the slab, 0 inside it.
        const double dx = std::max(std::max(min.x - p.x, p.x - max.x), 0.0);
        const double dy = std::max(std::max(min.y - p.y, p.y - max.y), 0.0);
        const double dz = std::max(std::max(min.z - p.z, p.z - max.z), 0.0);
        return dx * dx + dy * dy + dz * dz;
    }
};

struct Triangle {
    Point a, b, c;
    bool degenerate = false;  // no usable normal: measured to as its three edges
};

// A node covers triangles [first, first + count) when it is a leaf (count > 0); an inner node's
// children are nodes `first` and `first + 1`.
struct BvhNode {
    Box box;
    std::uint32_t first = 0;
    std::uint32_t count = 0;
};

// Triangles in BVH order and the tree over them.
struct TriangleSet {
    std::vector<Triangle> triangles;
    std::vector<BvhNode> nodes;
};

// Squared distance from `p` to `triangle` (to its three edges when degenerate).
double triangleDistanceSquared(const Point& p, const Triangle& triangle);

// Builds set.nodes over set.triangles, reordering the triangles; returns the old index of each.
std::vector<std::uint32_t> buildBvh(TriangleSet& set);

// Squared distance from `p` to the nearest triangle of `set` (which has triangles). `hint` is a
// triangle to start the bound from (the previous query's nearest, since consecutive queries lie
// close together); it becomes this query's nearest. `stack` is scratch space.
double nearestDistanceSquared(const TriangleSet& set, const Point& p, std::uint32_t& hint,
                              std::vector<std::uint32_t>& stack);

}  // namespace lodopt::scenes::detail
