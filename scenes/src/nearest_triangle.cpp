// The nearest triangle of a set (nearest_triangle.hpp): Ericson's closest point, a binned-SAH
// BVH. Compiled with -ffp-contract=off (scenes/CMakeLists.txt), as geometric_error.cpp.
#include "nearest_triangle.hpp"

#include <algorithm>
#include <cmath>

namespace lodopt::scenes::detail {

namespace {

constexpr std::uint32_t kLeafTriangles = 4;

// Squared distance from `p` to segment ab (a point when a == b).
double segmentDistanceSquared(const Point& p, const Point& a, const Point& b) {
    const Point ab = b - a;
    const double length2 = glm::dot(ab, ab);
    double t = length2 > 0.0 ? glm::dot(p - a, ab) / length2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    const Point d = p - (a + t * ab);
    return glm::dot(d, d);
}

}  // namespace

// Ericson §5.1.5, ClosestPtPointTriangle: the Voronoi regions of the vertices, then of the
// edges, then the face. In the face region the distance is taken to the plane (dot with the
// normal) rather than to the reconstructed point, which keeps it exact to rounding for points
// on the triangle.
double triangleDistanceSquared(const Point& p, const Triangle& triangle) {
    const Point& a = triangle.a;
    const Point& b = triangle.b;
    const Point& c = triangle.c;
    if (triangle.degenerate) {
        return std::min(segmentDistanceSquared(p, a, b),
                        std::min(segmentDistanceSquared(p, b, c), segmentDistanceSquared(p, c, a)));
    }
    const Point ab = b - a;
    const Point ac = c - a;
    const Point ap = p - a;
    const double d1 = glm::dot(ab, ap);
    const double d2 = glm::dot(ac, ap);
    if (d1 <= 0.0 && d2 <= 0.0) return glm::dot(ap, ap);
    const Point bp = p - b;
    const double d3 = glm::dot(ab, bp);
    const double d4 = glm::dot(ac, bp);
    if (d3 >= 0.0 && d4 <= d3) return glm::dot(bp, bp);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
        const Point d = ap - (d1 / (d1 - d3)) * ab;
        return glm::dot(d, d);
    }
    const Point cp = p - c;
    const double d5 = glm::dot(ab, cp);
    const double d6 = glm::dot(ac, cp);
    if (d6 >= 0.0 && d5 <= d6) return glm::dot(cp, cp);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
        const Point d = ap - (d2 / (d2 - d6)) * ac;
        return glm::dot(d, d);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        const Point d = bp - w * (c - b);
        return glm::dot(d, d);
    }
    const Point normal = glm::cross(ab, ac);
    const double height = glm::dot(ap, normal);
    return height * height / glm::dot(normal, normal);
}

// Splits nodes until kLeafTriangles or fewer (equal centroids are split all the same, so a leaf
// never holds more). The tree's shape (which std::partition's and std::nth_element's
// implementations decide) does not change a result: the nearest distance is a minimum over all
// triangles, each measured alike. Reorders the triangles; returns the old index of each.
std::vector<std::uint32_t> buildBvh(TriangleSet& surface) {
    std::vector<Triangle>& triangles = surface.triangles;
    std::vector<Point> centroids(triangles.size());
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        centroids[t] = (triangles[t].a + triangles[t].b + triangles[t].c) / 3.0;
    }
    std::vector<std::uint32_t> order(triangles.size());
    for (std::size_t t = 0; t < order.size(); ++t) order[t] = static_cast<std::uint32_t>(t);

    surface.nodes.clear();
    surface.nodes.reserve(2 * triangles.size() / kLeafTriangles + 1);
    struct Pending {
        std::uint32_t node, first, count;
    };
    std::vector<Pending> stack;
    surface.nodes.emplace_back();
    stack.push_back({0, 0, static_cast<std::uint32_t>(triangles.size())});
    while (!stack.empty()) {
        const Pending pending = stack.back();
        stack.pop_back();
        Box box, centroidBox;
        for (std::uint32_t i = pending.first; i < pending.first + pending.count; ++i) {
            const Triangle& triangle = triangles[order[i]];
            box.add(triangle.a);
            box.add(triangle.b);
            box.add(triangle.c);
            centroidBox.add(centroids[order[i]]);
        }
        surface.nodes[pending.node].box = box;
        const Point extent = centroidBox.max - centroidBox.min;
        if (pending.count <= kLeafTriangles) {
            surface.nodes[pending.node].first = pending.first;
            surface.nodes[pending.node].count = pending.count;
            continue;
        }
        // Binned surface area heuristic (Wald 2007): the split that minimises area x triangles
        // over both halves, so that overlapping geometry (leaf cards) shares few boxes; a
        // median split when all centroids fall in one bin.
        constexpr int kBins = 12;
        int bestAxis = -1;
        int bestBin = 0;
        double bestCost = std::numeric_limits<double>::max();
        const auto halfArea = [](const Box& b) {
            const Point d = b.max - b.min;
            return d.x * d.y + d.y * d.z + d.z * d.x;
        };
        const auto binOf = [&](std::uint32_t t, int axis) {
            const double scale = kBins / extent[axis];
            return std::min(kBins - 1, int((centroids[t][axis] - centroidBox.min[axis]) * scale));
        };
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.0)) continue;
            Box bins[kBins];
            std::uint32_t counts[kBins] = {};
            for (std::uint32_t i = pending.first; i < pending.first + pending.count; ++i) {
                const int bin = binOf(order[i], axis);
                const Triangle& triangle = triangles[order[i]];
                bins[bin].add(triangle.a);
                bins[bin].add(triangle.b);
                bins[bin].add(triangle.c);
                ++counts[bin];
            }
            double rightCost[kBins] = {};
            Box right;
            std::uint32_t rightCount = 0;
            for (int bin = kBins - 1; bin > 0; --bin) {
                right.add(bins[bin]);
                rightCount += counts[bin];
                rightCost[bin] = rightCount > 0 ? halfArea(right) * rightCount : 0.0;
            }
            Box left;
            std::uint32_t leftCount = 0;
            for (int bin = 0; bin + 1 < kBins; ++bin) {
                left.add(bins[bin]);
                leftCount += counts[bin];
                if (leftCount == 0 || leftCount == pending.count) continue;
                const double cost = halfArea(left) * leftCount + rightCost[bin + 1];
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = bin;
                }
            }
        }
        std::uint32_t half = 0;
        const auto begin = order.begin() + pending.first;
        const auto end = begin + pending.count;
        if (bestAxis >= 0) {
            half = static_cast<std::uint32_t>(
                std::partition(begin, end, [&](std::uint32_t t) { return binOf(t, bestAxis) <= bestBin; }) - begin);
        } else {
            const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
            half = pending.count / 2;
            std::nth_element(begin, begin + half, end,
                             [&](std::uint32_t l, std::uint32_t r) { return centroids[l][axis] < centroids[r][axis]; });
        }
        const auto left = static_cast<std::uint32_t>(surface.nodes.size());
        const std::uint32_t right = left + 1;
        surface.nodes.emplace_back();
        surface.nodes.emplace_back();
        surface.nodes[pending.node].first = left;
        surface.nodes[pending.node].count = 0;
        stack.push_back({right, pending.first + half, pending.count - half});
        stack.push_back({left, pending.first, half});
    }
    std::vector<Triangle> sorted(triangles.size());
    for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = triangles[order[i]];
    triangles = std::move(sorted);
    return order;
}

// Squared distance from `p` to the nearest triangle of `surface` (which has triangles).
// `hint` is a triangle to start the bound from (the previous sample's nearest, since
// consecutive samples lie close together); it becomes this sample's nearest.
double nearestDistanceSquared(const TriangleSet& surface, const Point& p, std::uint32_t& hint,
                              std::vector<std::uint32_t>& stack) {
    double best = triangleDistanceSquared(p, surface.triangles[hint]);
    stack.clear();
    stack.push_back(0);
    while (!stack.empty()) {
        const BvhNode& node = surface.nodes[stack.back()];
        stack.pop_back();
        if (node.count > 0) {
            for (std::uint32_t t = node.first; t < node.first + node.count; ++t) {
                const double d = triangleDistanceSquared(p, surface.triangles[t]);
                if (d < best) {
                    best = d;
                    hint = t;
                }
            }
            continue;
        }
        const std::uint32_t children[2] = {node.first, node.first + 1};
        const double near0 = surface.nodes[children[0]].box.distanceSquared(p);
        const double near1 = surface.nodes[children[1]].box.distanceSquared(p);
        // Nearer child on top of the stack, so that it tightens `best` before the other is tested.
        const bool firstNearer = near0 <= near1;
        const double nearD = firstNearer ? near0 : near1;
        const double farD = firstNearer ? near1 : near0;
        if (farD < best) stack.push_back(children[firstNearer ? 1 : 0]);
        if (nearD < best) stack.push_back(children[firstNearer ? 0 : 1]);
    }
    return best;
}

}  // namespace lodopt::scenes::detail
