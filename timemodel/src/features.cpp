// Frame features (DONG15 eq. 5; CITY17 after Wimmer & Wonka 2003): per-level sums, the
// projected bounding-box area that CITY17 uses for "#pixels", and the per-view table.
#include "timemodel/features.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>

#include "occlusion.hpp"

namespace lodopt::timemodel {

const char* featureName(Feature feature) {
    switch (feature) {
        case Feature::kVertices:
            return "vertices";
        case Feature::kTriangles:
            return "triangles";
        case Feature::kTextureBytes:
            return "texture_bytes";
        case Feature::kDrawCalls:
            return "draw_calls";
        case Feature::kPixels:
            return "pixels";
        case Feature::kDrawnObjects:
            return "drawn_objects";
        case Feature::kMatrices:
            return "matrices";
        case Feature::kBoundingBoxes:
            return "bounding_boxes";
        case Feature::kVisibleTriangles:
            return "visible_triangles";
        case Feature::kRasterPixels:
            return "raster_pixels";
        case Feature::kEdgePixels:
            return "edge_pixels";
        case Feature::kShadedPixels:
            return "shaded_pixels";
        case Feature::kTexturedPixels:
            return "textured_pixels";
        case Feature::kShadedEdgePixels:
            return "shaded_edge_pixels";
        case Feature::kPartialBlocks:
            return "partial_blocks";
        case Feature::kShadedPartialBlocks:
            return "shaded_partial_blocks";
    }
    return "unknown";
}

const std::array<Feature, kFeatureCount>& allFeatures() {
    static const std::array<Feature, kFeatureCount> features = {
        Feature::kVertices,         Feature::kTriangles,        Feature::kTextureBytes,  Feature::kDrawCalls,
        Feature::kPixels,           Feature::kDrawnObjects,     Feature::kMatrices,      Feature::kBoundingBoxes,
        Feature::kVisibleTriangles, Feature::kRasterPixels,     Feature::kEdgePixels,    Feature::kShadedPixels,
        Feature::kTexturedPixels,   Feature::kShadedEdgePixels, Feature::kPartialBlocks, Feature::kShadedPartialBlocks};
    return features;
}

FrameFeatures& FrameFeatures::operator+=(const FrameFeatures& other) {
    for (std::size_t i = 0; i < kFeatureCount; ++i) values[i] += other.values[i];
    return *this;
}

FrameFeatures& FrameFeatures::operator-=(const FrameFeatures& other) {
    for (std::size_t i = 0; i < kFeatureCount; ++i) values[i] -= other.values[i];
    return *this;
}

FrameFeatures operator+(FrameFeatures a, const FrameFeatures& b) {
    return a += b;
}
FrameFeatures operator-(FrameFeatures a, const FrameFeatures& b) {
    return a -= b;
}

namespace {

// Signed distances to the near (z >= -w) and far (z <= w) planes in clip space.
float nearDistance(const glm::vec4& p) {
    return p.z + p.w;
}
float farDistance(const glm::vec4& p) {
    return p.w - p.z;
}

// Clips segment [a, b] to one plane given by `distance` (inside >= 0); false when nothing is left.
template <typename Distance>
bool clipSegment(glm::vec4& a, glm::vec4& b, Distance distance) {
    const float da = distance(a), db = distance(b);
    if (da < 0.0f && db < 0.0f) return false;
    if (da < 0.0f)
        a = a + (b - a) * (da / (da - db));
    else if (db < 0.0f)
        b = b + (a - b) * (db / (db - da));
    return true;
}

}  // namespace

ProjectedOutline projectedOutline(const scenes::Bounds& box, const glm::mat4& modelViewProjection) {
    ProjectedOutline outline;
    if (box.empty()) return outline;
    glm::vec4 corners[8];
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                          (corner & 4) ? box.max.z : box.min.z);
        corners[corner] = modelViewProjection * glm::vec4(p, 1.0f);
    }
    float minX = 1e30f, minY = 1e30f, maxX = -1e30f, maxY = -1e30f;
    bool any = false;
    auto add = [&](const glm::vec4& point) {
        if (point.w <= 0.0f) return;  // only possible for a degenerate projection
        const float x = point.x / point.w, y = point.y / point.w;
        minX = std::min(minX, x);
        maxX = std::max(maxX, x);
        minY = std::min(minY, y);
        maxY = std::max(maxY, y);
        any = true;
    };
    // The clipped box's vertices are its corners inside both planes plus the edges' crossings
    // of them, so clipping the 12 edges and projecting their ends gives its exact outline.
    // Most boxes lie between the planes: then no edge is clipped and the outline is the
    // corners' (the same values, a third of the divisions).
    bool inside = true;
    for (const glm::vec4& corner : corners)
        inside = inside && nearDistance(corner) >= 0.0f && farDistance(corner) >= 0.0f;
    for (int a = 0; a < 8 && inside; ++a) add(corners[a]);
    for (int a = 0; a < 8 && !inside; ++a) {
        for (int axis = 1; axis < 8; axis <<= 1) {
            if (a & axis) continue;
            glm::vec4 p = corners[a], q = corners[a | axis];
            if (!clipSegment(p, q, nearDistance) || !clipSegment(p, q, farDistance)) continue;
            add(p);
            add(q);
        }
    }
    if (any) outline = {minX, minY, maxX, maxY, false};
    return outline;
}

double projectedPixels(const scenes::Bounds& objectBounds, const glm::mat4& modelViewProjection, int width,
                       int height) {
    return viewportPixels(projectedOutline(objectBounds, modelViewProjection), width, height);
}

double viewportPixels(const ProjectedOutline& outline, int width, int height) {
    assert(width > 0 && height > 0);
    if (outline.empty) return 0.0;
    const float minX = std::max(outline.minX, -1.0f), minY = std::max(outline.minY, -1.0f);
    const float maxX = std::min(outline.maxX, 1.0f), maxY = std::min(outline.maxY, 1.0f);
    if (maxX <= minX || maxY <= minY) return 0.0;
    return double(maxX - minX) * 0.5 * width * double(maxY - minY) * 0.5 * height;
}

namespace {

bool textured(const std::vector<scenes::Material>& materials, int material) {
    return material >= 0 && std::size_t(material) < materials.size() && materials[material].baseColorTexture.present();
}

// The work a FeatureTable may skip, from the features it needs.
struct FeatureWork {
    bool partialBlocks = true;  // the 4x4 block walk per triangle
    bool depthPass = true;      // the software depth pass: the shaded features' shares
};

FeatureWork workFor(const FeatureSet& needed) {
    FeatureWork work;
    work.partialBlocks = contains(needed, Feature::kPartialBlocks) || contains(needed, Feature::kShadedPartialBlocks);
    work.depthPass = std::any_of(kDepthTestedFeatures.begin(), kDepthTestedFeatures.end(),
                                 [&](Feature feature) { return contains(needed, feature); });
    return work;
}

// `depthPassShare` is the object's share of fragments passing the depth test (0 when the depth
// pass was skipped: the shaded features are then 0).
FrameFeatures levelContribution(const scenes::Level& level, const std::vector<scenes::Material>& materials,
                                const glm::mat4& modelViewProjection, int width, int height, double depthPassShare,
                                bool countPartialBlocks = true) {
    const scenes::LevelStats& stats = level.stats;
    FrameFeatures f;
    f[Feature::kVertices] = double(stats.vertices);
    f[Feature::kTriangles] = double(stats.triangles);
    f[Feature::kTextureBytes] = double(stats.textureBytes);
    f[Feature::kDrawCalls] = double(stats.drawCalls);
    f[Feature::kPixels] = projectedPixels(stats.bounds, modelViewProjection, width, height);
    f[Feature::kDrawnObjects] = 1.0;
    f[Feature::kMatrices] = 1.0;
    // One running sum over the meshes (the same bits as rasterFeatures of the level); the
    // textured meshes' share is what their turns added.
    RasterFeatures raster;
    double texturedRaster = 0.0;
    for (const scenes::Mesh& mesh : level.meshes) {
        const double before = raster.rasterPixels;
        addRasterFeatures(mesh, modelViewProjection, width, height, raster, countPartialBlocks);
        if (textured(materials, mesh.material)) texturedRaster += raster.rasterPixels - before;
    }
    f[Feature::kVisibleTriangles] = raster.visibleTriangles;
    f[Feature::kRasterPixels] = raster.rasterPixels;
    f[Feature::kEdgePixels] = raster.edgePixels;
    f[Feature::kShadedPixels] = raster.rasterPixels * depthPassShare;
    f[Feature::kTexturedPixels] = texturedRaster * depthPassShare;
    f[Feature::kShadedEdgePixels] = raster.edgePixels * depthPassShare;
    f[Feature::kPartialBlocks] = raster.partialBlocks;
    f[Feature::kShadedPartialBlocks] = raster.partialBlocks * depthPassShare;
    return f;
}

glm::mat4 viewProjectionMatrix(const scenes::Camera& camera, int width, int height) {
    return scenes::projectionMatrix(camera, float(width) / float(height)) * scenes::viewMatrix(camera);
}

}  // namespace

std::vector<double> depthTestedShares(const scenes::Scene& scene, const scenes::Camera& camera, int width, int height,
                                      int depthPassCells) {
    assert(width > 0 && height > 0 && depthPassCells > 0);
    return detail::depthPassShares(scene, viewProjectionMatrix(camera, width, height), float(width) / float(height),
                                   depthPassCells);
}

FeatureTable::FeatureTable(const scenes::Scene& scene, const scenes::Camera& camera, int width, int height,
                           int depthPassCells, const FeatureSet& needed) {
    assert(width > 0 && height > 0 && depthPassCells > 0);
    const glm::mat4 viewProjection = viewProjectionMatrix(camera, width, height);
    mFirstLevel.reserve(scene.objects.size() + 1);
    const FeatureWork work = workFor(needed);
    const std::vector<double> shares =
        work.depthPass ? detail::depthPassShares(scene, viewProjection, float(width) / float(height), depthPassCells)
                       : std::vector<double>(scene.objects.size(), 0.0);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const scenes::Object& object = scene.objects[o];
        mFirstLevel.push_back(static_cast<int>(mContributions.size()));
        const glm::mat4 modelViewProjection = viewProjection * object.transform;
        for (const scenes::Level& level : object.levels) {
            mContributions.push_back(levelContribution(level, scene.materials, modelViewProjection, width, height,
                                                       shares[o], work.partialBlocks));
        }
    }
    mFirstLevel.push_back(static_cast<int>(mContributions.size()));  // end sentinel
    mFrameConstant[Feature::kBoundingBoxes] = double(scene.objects.size());
}

int FeatureTable::levelCount(int object) const {
    assert(object >= 0 && object < objectCount());
    return mFirstLevel[object + 1] - mFirstLevel[object];
}

const FrameFeatures& FeatureTable::contribution(int object, int level) const {
    assert(object >= 0 && object < objectCount());
    if (level == scenes::kNotDrawn) return mZero;
    assert(level >= 0 && level < levelCount(object));
    return mContributions[mFirstLevel[object] + level];
}

void FeatureTable::features(const scenes::Combination& combination, FrameFeatures& out) const {
    assert(static_cast<int>(combination.size()) == objectCount());
    out = mFrameConstant;
    for (int object = 0; object < objectCount(); ++object) {
        const int level = combination[object];
        if (level != scenes::kNotDrawn) out += contribution(object, level);
    }
}

FrameFeatures FeatureTable::features(const scenes::Combination& combination) const {
    FrameFeatures out;
    features(combination, out);
    return out;
}

FrameFeatures FeatureTable::delta(int object, int oldLevel, int newLevel) const {
    return contribution(object, newLevel) - contribution(object, oldLevel);
}

FrameFeatures computeFrameFeatures(const scenes::Scene& scene, const scenes::Combination& combination,
                                   const scenes::Camera& camera, int width, int height) {
    assert(combination.size() == scene.objects.size());
    assert(width > 0 && height > 0);
    const glm::mat4 viewProjection = viewProjectionMatrix(camera, width, height);
    FrameFeatures out;
    out[Feature::kBoundingBoxes] = double(scene.objects.size());
    const std::vector<double> shares =
        detail::depthPassShares(scene, viewProjection, float(width) / float(height), FeatureTable::kDepthPassCells);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        const int level = combination[o];
        if (level == scenes::kNotDrawn) continue;
        const scenes::Object& object = scene.objects[o];
        out += levelContribution(object.levels[level], scene.materials, viewProjection * object.transform, width,
                                 height, shares[o]);
    }
    return out;
}

}  // namespace lodopt::timemodel
