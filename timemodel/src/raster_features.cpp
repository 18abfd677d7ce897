// Raster features of a level's geometry for one viewpoint: what llvmpipe actually works on.
// llvmpipe clips and bins every triangle that is not trivially outside the frustum, rasterizes
// its area (partial 4x4 blocks along its edges cost extra) and, with early depth testing,
// shades only the fragments that pass. See features.hpp for the measurements behind them.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "timemodel/features.hpp"

namespace lodopt::timemodel {

namespace {

// Outcode bits: outside the plane x < -w, x > w, y < -w, y > w, z < -w (near), z > w (far).
std::uint8_t outcode(const glm::vec4& p) {
    std::uint8_t code = 0;
    if (p.x < -p.w) code |= 1;
    if (p.x > p.w) code |= 2;
    if (p.y < -p.w) code |= 4;
    if (p.y > p.w) code |= 8;
    if (p.z < -p.w) code |= 16;
    if (p.z > p.w) code |= 32;
    return code;
}

// Clips polygon `in` (n points) to the half plane `sign * coordinate(p) <= limit`.
int clipAxis(const glm::dvec2* in, int n, int axis, double sign, double limit, glm::dvec2* out) {
    int count = 0;
    for (int i = 0; i < n; ++i) {
        const glm::dvec2& p = in[i];
        const glm::dvec2& q = in[(i + 1) % n];
        const double dp = limit - sign * p[axis], dq = limit - sign * q[axis];
        if (dp >= 0.0) out[count++] = p;
        if ((dp >= 0.0) != (dq >= 0.0)) out[count++] = p + (q - p) * (dp / (dp - dq));
    }
    return count;
}

// llvmpipe's raster block, in pixels.
constexpr double kBlock = 4.0;
// Clipping leaves a border edge a rounding error off the border's line (x = 1e-15 for 0), which
// would cost a whole row or column of blocks: within this many blocks of a block line, snap to it.
constexpr double kSnap = 1e-7;

// A polygon edge that is not horizontal, for x at a given y without a division.
struct SlopedEdge {
    double low, high;  // its y range
    double xAtLow, slope;
};

// The x-extent [low, high] of a convex polygon on the line y = `y`, from its sloped edges (a
// horizontal edge's ends are ends of sloped ones); empty (low > high) when the line misses it.
// A line within kSnap blocks of an edge's end counts as through it.
void extentAt(const SlopedEdge* edges, int count, double y, double& low, double& high) {
    constexpr double tolerance = kSnap * kBlock;
    low = std::numeric_limits<double>::infinity();
    high = -low;
    for (int i = 0; i < count; ++i) {
        const SlopedEdge& e = edges[i];
        if (y < e.low - tolerance || y > e.high + tolerance) continue;
        const double x = e.xAtLow + std::clamp(y - e.low, 0.0, e.high - e.low) * e.slope;
        low = std::min(low, x);
        high = std::max(high, x);
    }
}

// The 4x4 blocks that convex polygon `v` (n <= 8 points, pixel coordinates inside a `width` x
// `height` viewport) covers only partly: per block row, the blocks its band of the polygon
// reaches minus those whose four corners lie inside it (a convex polygon then holds the block).
// llvmpipe evaluates the coverage mask per pixel only in such blocks; two long edges of a
// sliver share their blocks, which summing edge lengths would count twice.
double partialBlocks(const glm::dvec2* v, int n, double width, double height) {
    SlopedEdge edges[8];
    int count = 0;
    double yMin = v[0].y, yMax = v[0].y;
    for (int i = 0; i < n; ++i) {
        const glm::dvec2& p = v[i];
        const glm::dvec2& q = v[(i + 1) % n];
        yMin = std::min(yMin, p.y);
        yMax = std::max(yMax, p.y);
        if (p.y == q.y) continue;
        const glm::dvec2& bottom = p.y < q.y ? p : q;
        const glm::dvec2& top = p.y < q.y ? q : p;
        edges[count++] = {bottom.y, top.y, bottom.x, (top.x - bottom.x) / (top.y - bottom.y)};
    }
    const int lastRow = int(std::ceil(height / kBlock)) - 1, lastColumn = int(std::ceil(width / kBlock)) - 1;
    const int firstRow = std::clamp(int(std::floor(yMin / kBlock + kSnap)), 0, lastRow);
    const int endRow = std::clamp(int(std::ceil(yMax / kBlock - kSnap)) - 1, firstRow, lastRow);
    double partial = 0.0;
    double lowBelow, highBelow, lowAbove, highAbove;
    extentAt(edges, count, firstRow * kBlock, lowBelow, highBelow);
    for (int row = firstRow; row <= endRow; ++row, lowBelow = lowAbove, highBelow = highAbove) {
        const double bottom = row * kBlock, top = bottom + kBlock;
        extentAt(edges, count, top, lowAbove, highAbove);
        double low = std::min(lowBelow, lowAbove), high = std::max(highBelow, highAbove);
        for (int i = 0; i < n; ++i) {
            if (v[i].y >= bottom && v[i].y <= top) {
                low = std::min(low, v[i].x);
                high = std::max(high, v[i].x);
            }
        }
        if (!(low <= high)) continue;
        const int first = std::clamp(int(std::floor(low / kBlock + kSnap)), 0, lastColumn);
        const int last = std::clamp(int(std::ceil(high / kBlock - kSnap)) - 1, first, lastColumn);
        double full = 0.0;
        if (lowBelow <= highBelow && lowAbove <= highAbove) {
            const double inLow = std::max(lowBelow, lowAbove), inHigh = std::min(highBelow, highAbove);
            full = std::max(0.0, std::floor(inHigh / kBlock + kSnap) - std::ceil(inLow / kBlock - kSnap));
        }
        partial += double(last - first + 1) - full;
    }
    return partial;
}

// Screen area in pixels of triangle (a, b, c) in clip space, clipped to the near plane and the
// viewport; adds the length of its clipped edges that are not on the viewport border to `edges`
// and its partly covered 4x4 blocks to `*blocks` (not counted when null).
double triangleRasterPixels(const glm::vec4& a, const glm::vec4& b, const glm::vec4& c, double halfWidth,
                            double halfHeight, double& edges, double* blocks) {
    glm::vec4 polygon[4];
    int count = 0;
    const glm::vec4 in[3] = {a, b, c};
    for (int i = 0; i < 3; ++i) {  // Sutherland–Hodgman against z >= -w
        const glm::vec4& p = in[i];
        const glm::vec4& q = in[(i + 1) % 3];
        const float dp = p.z + p.w, dq = q.z + q.w;
        if (dp >= 0.0f) polygon[count++] = p;
        if ((dp >= 0.0f) != (dq >= 0.0f)) polygon[count++] = p + (q - p) * (dp / (dp - dq));
    }
    if (count < 3) return 0.0;
    // Each clip adds at most one point: 4 after the near plane, 8 after the viewport.
    glm::dvec2 screen[8], other[8];
    for (int i = 0; i < count; ++i) {
        const double w = std::max(double(polygon[i].w), 1e-12);
        screen[i] = {double(polygon[i].x) / w * halfWidth, double(polygon[i].y) / w * halfHeight};
    }
    count = clipAxis(screen, count, 0, 1.0, halfWidth, other);
    count = clipAxis(other, count, 0, -1.0, halfWidth, screen);
    count = clipAxis(screen, count, 1, 1.0, halfHeight, other);
    count = clipAxis(other, count, 1, -1.0, halfHeight, screen);
    if (count < 3) return 0.0;
    double twiceArea = 0.0;
    auto onBorder = [&](const glm::dvec2& p, const glm::dvec2& q) {
        const double ex = 1e-9 * halfWidth, ey = 1e-9 * halfHeight;
        return (std::abs(std::abs(p.x) - halfWidth) < ex && std::abs(q.x - p.x) < ex) ||
               (std::abs(std::abs(p.y) - halfHeight) < ey && std::abs(q.y - p.y) < ey);
    };
    for (int i = 0; i < count; ++i) {
        const glm::dvec2& p = screen[i];
        const glm::dvec2& q = screen[(i + 1) % count];
        twiceArea += p.x * q.y - q.x * p.y;
        if (!onBorder(p, q)) edges += glm::length(q - p);
    }
    if (twiceArea == 0.0 || !std::isfinite(twiceArea)) return 0.0;
    for (int i = 0; i < count; ++i) screen[i] += glm::dvec2(halfWidth, halfHeight);  // pixels from the corner
    if (blocks) *blocks += partialBlocks(screen, count, 2.0 * halfWidth, 2.0 * halfHeight);
    return 0.5 * std::abs(twiceArea);
}

}  // namespace

void addRasterFeatures(const scenes::Mesh& mesh, const glm::mat4& modelViewProjection, int width, int height,
                       RasterFeatures& sum, bool countPartialBlocks) {
    assert(width > 0 && height > 0);
    thread_local std::vector<glm::vec4> clip;
    thread_local std::vector<std::uint8_t> codes;
    clip.resize(mesh.positions.size());
    codes.resize(mesh.positions.size());
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        clip[v] = modelViewProjection * glm::vec4(mesh.positions[v], 1.0f);
        codes[v] = outcode(clip[v]);
    }
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const std::uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
        if (codes[a] & codes[b] & codes[c]) continue;  // trivially outside one plane
        sum.visibleTriangles += 1.0;
        sum.rasterPixels += triangleRasterPixels(clip[a], clip[b], clip[c], 0.5 * width, 0.5 * height, sum.edgePixels,
                                                 countPartialBlocks ? &sum.partialBlocks : nullptr);
    }
}

RasterFeatures rasterFeatures(const std::vector<scenes::Mesh>& meshes, const glm::mat4& modelViewProjection, int width,
                              int height) {
    RasterFeatures result;
    for (const scenes::Mesh& mesh : meshes) addRasterFeatures(mesh, modelViewProjection, width, height, result);
    return result;
}

}  // namespace lodopt::timemodel
