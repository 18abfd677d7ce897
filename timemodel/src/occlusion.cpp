#include "occlusion.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace lodopt::timemodel::detail {

namespace {

struct Grid {
    int width = 0;
    int height = 0;
    std::vector<float> depth;  // window z in [-1, 1] (NDC), +inf = empty
};

struct ScreenVertex {
    double x, y, z;  // grid pixels, NDC depth
};

// The columns [first, last] of row y whose centres can lie in the triangle: the x-extent of the
// part of the triangle within one cell of the row's sample line, widened by a cell. Points the
// exact test below accepts lie within far less than a cell of the triangle, so the cells left
// out are ones it rejects: a conservative span, the same counts (DepthPass.SpansCountWhatTheBoxCounts).
bool rowSpan(const ScreenVertex* v, double py, int& first, int& last) {
    const double low = py - 1.0, high = py + 1.0;
    double xMin = std::numeric_limits<double>::infinity(), xMax = -xMin;
    for (int k = 0; k < 3; ++k) {
        const ScreenVertex& p = v[k];
        const ScreenVertex& q = v[(k + 1) % 3];
        if (p.y >= low && p.y <= high) {
            xMin = std::min(xMin, p.x);
            xMax = std::max(xMax, p.x);
        }
        for (double line : {low, high}) {
            if ((p.y - line) * (q.y - line) <= 0.0 && p.y != q.y) {
                const double x = p.x + (line - p.y) * (q.x - p.x) / (q.y - p.y);
                xMin = std::min(xMin, x);
                xMax = std::max(xMax, x);
            }
        }
    }
    if (!(xMin <= xMax)) return false;  // the band misses the triangle (or NaN)
    first = int(std::floor(xMin - 0.5)) - 1;
    last = int(std::ceil(xMax - 0.5)) + 1;
    return true;
}

// Rasterizes one screen-space triangle with pixel-centre sampling and a LESS depth test;
// counts the covered and the passing cells. `everyCell` tests the whole bounding box (the
// reference the spans are checked against).
void rasterize(const ScreenVertex& a, const ScreenVertex& b, const ScreenVertex& c, Grid& grid, std::uint64_t& covered,
               std::uint64_t& passed, bool everyCell) {
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0.0 || !std::isfinite(area)) return;
    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(grid.width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(grid.height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
    const ScreenVertex corners[3] = {a, b, c};
    for (int y = y0; y <= y1; ++y) {
        // Samples a hair off the cell centre, so that the shared edge of two triangles (a
        // quad's diagonal) does not cover a centre twice and count as a failed depth test.
        const double py = y + 0.5 + 2.3e-4;
        int first = x0, last = x1;
        if (!everyCell) {
            if (!rowSpan(corners, py, first, last)) continue;
            first = std::max(first, x0);
            last = std::min(last, x1);
        }
        for (int x = first; x <= last; ++x) {
            const double px = x + 0.5 + 1.1e-4;
            const double w0 = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
            const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
            const double w2 = 1.0 - w0 - w1;
            if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
            const float z = float(w0 * a.z + w1 * b.z + w2 * c.z);
            if (z < -1.0f || z > 1.0f) continue;
            ++covered;
            float& stored = grid.depth[std::size_t(y) * grid.width + x];
            if (z < stored) {
                stored = z;
                ++passed;
            }
        }
    }
}

}  // namespace

std::vector<double> depthPassShares(const scenes::Scene& scene, const glm::mat4& viewProjection, float aspect,
                                    int resolution, bool everyCell) {
    Grid grid;
    grid.width = aspect >= 1.0f ? resolution : std::max(1, int(std::lround(resolution * aspect)));
    grid.height = aspect >= 1.0f ? std::max(1, int(std::lround(resolution / aspect))) : resolution;
    grid.depth.assign(std::size_t(grid.width) * grid.height, std::numeric_limits<float>::infinity());
    std::vector<double> shares(scene.objects.size(), 1.0);
    std::vector<glm::vec4> clip;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const scenes::Object& object = scene.objects[o];
        if (object.levels.empty()) continue;
        const glm::mat4 mvp = viewProjection * object.transform;
        std::uint64_t covered = 0, passed = 0;
        for (const scenes::Mesh& mesh : object.levels[0].meshes) {
            clip.resize(mesh.positions.size());
            for (std::size_t v = 0; v < mesh.positions.size(); ++v) clip[v] = mvp * glm::vec4(mesh.positions[v], 1.0f);
            for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
                const glm::vec4 in[3] = {clip[mesh.indices[i]], clip[mesh.indices[i + 1]], clip[mesh.indices[i + 2]]};
                // Near-plane clip (Sutherland–Hodgman), then a fan.
                glm::vec4 polygon[4];
                int count = 0;
                for (int k = 0; k < 3; ++k) {
                    const glm::vec4& p = in[k];
                    const glm::vec4& q = in[(k + 1) % 3];
                    const float dp = p.z + p.w, dq = q.z + q.w;
                    if (dp >= 0.0f) polygon[count++] = p;
                    if ((dp >= 0.0f) != (dq >= 0.0f)) polygon[count++] = p + (q - p) * (dp / (dp - dq));
                }
                if (count < 3) continue;
                ScreenVertex screen[4];
                for (int k = 0; k < count; ++k) {
                    const double w = std::max(double(polygon[k].w), 1e-9);
                    screen[k] = {(polygon[k].x / w * 0.5 + 0.5) * grid.width,
                                 (polygon[k].y / w * 0.5 + 0.5) * grid.height, polygon[k].z / w};
                }
                for (int k = 1; k + 1 < count; ++k)
                    rasterize(screen[0], screen[k], screen[k + 1], grid, covered, passed, everyCell);
            }
        }
        if (covered > 0) shares[o] = double(passed) / double(covered);
    }
    return shares;
}

}  // namespace lodopt::timemodel::detail
