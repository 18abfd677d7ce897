// LOD chains with meshoptimizer 0.18 (Kapoulkine, meshoptimizer: quadric-error edge collapse
// after Garland & Heckbert 1997, "Surface simplification using quadric error metrics";
// meshopt_simplifySloppy is vertex clustering). Each level is simplified from level 0, so
// its error is measured against level 0 directly.
#include "scenes/lod_generation.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include <meshoptimizer.h>

namespace lodopt::scenes {

namespace {

// Vertex layout for welding: exact duplicates (same position, normal and uv) become one
// vertex, so that triangle soups have connectivity for the simplifier.
// Every attribute of a vertex: duplicates are welded only when all of them agree.
struct WeldVertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec2 uv1;
    glm::vec4 tangent;
    glm::vec4 color;
};

// Largest extent of the meshes' bounding box (what meshopt_simplifyScale measures, so that
// its relative errors times this are object-space distances).
float extentOf(const Mesh* meshes, std::size_t count) {
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (std::size_t m = 0; m < count; ++m) {
        for (const glm::vec3& p : meshes[m].positions) {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
    }
    if (high.x < low.x) return 0.0f;
    const glm::vec3 size = high - low;
    return std::max(size.x, std::max(size.y, size.z));
}

}  // namespace

float simplifyMesh(const Mesh& source, float ratio, Mesh& out) {
    assert(ratio > 0.0f && ratio <= 1.0f);
    assert(source.normals.size() == source.positions.size());
    assert(source.uvs.empty() || source.uvs.size() == source.positions.size());
    assert(source.uvs1.empty() || source.uvs1.size() == source.positions.size());
    assert(source.tangents.empty() || source.tangents.size() == source.positions.size());
    assert(source.colors.empty() || source.colors.size() == source.positions.size());
    out = Mesh();
    out.material = source.material;
    out.flatNormals = source.flatNormals;
    const std::size_t triangles = source.indices.size() / 3;
    if (ratio >= 1.0f || triangles == 0) {
        out = source;
        return 0.0f;
    }
    const std::size_t targetIndices = static_cast<std::size_t>(std::lround(double(triangles) * ratio)) * 3;
    if (targetIndices == 0) return 1.0f;  // nothing left: the whole extent is lost

    // Weld exact duplicates.
    const std::size_t vertexCount = source.positions.size();
    std::vector<WeldVertex> vertices(vertexCount);
    for (std::size_t v = 0; v < vertexCount; ++v) {
        vertices[v] = {source.positions[v],
                       source.normals[v],
                       source.uvs.empty() ? glm::vec2(0.0f) : source.uvs[v],
                       source.uvs1.empty() ? glm::vec2(0.0f) : source.uvs1[v],
                       source.tangents.empty() ? glm::vec4(0.0f) : source.tangents[v],
                       source.colors.empty() ? glm::vec4(0.0f) : source.colors[v]};
    }
    std::vector<unsigned int> remap(vertexCount);
    const std::size_t welded = meshopt_generateVertexRemap(remap.data(), source.indices.data(), source.indices.size(),
                                                           vertices.data(), vertexCount, sizeof(WeldVertex));
    std::vector<WeldVertex> unique(welded);
    meshopt_remapVertexBuffer(unique.data(), vertices.data(), vertexCount, sizeof(WeldVertex), remap.data());
    std::vector<unsigned int> indices(source.indices.size());
    meshopt_remapIndexBuffer(indices.data(), source.indices.data(), source.indices.size(), remap.data());

    const float* positions = &unique[0].position.x;
    std::vector<unsigned int> simplified(indices.size());
    float error = 0.0f;
    // The ratio is the contract, so the error bound is left open (1 = the whole extent).
    // Locked borders keep open edges (and the seams between an object's meshes) in place;
    // when that stalls above twice the target, borders are released, then clustering is
    // the last resort.
    std::size_t count = meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions, welded,
                                         sizeof(WeldVertex), targetIndices, 1.0f, meshopt_SimplifyLockBorder, &error);
    if (count > 2 * targetIndices) {
        count = meshopt_simplify(simplified.data(), indices.data(), indices.size(), positions, welded, sizeof(WeldVertex),
                                 targetIndices, 1.0f, 0, &error);
    }
    if (count > 2 * targetIndices) {
        count = meshopt_simplifySloppy(simplified.data(), indices.data(), indices.size(), positions, welded,
                                       sizeof(WeldVertex), targetIndices, 1.0f, &error);
    }
    simplified.resize(count);
    if (count == 0) return std::max(error, 1.0f);

    // Keep only the vertices the simplified triangles use.
    std::vector<unsigned int> fetch(welded);
    const std::size_t used = meshopt_optimizeVertexFetchRemap(fetch.data(), simplified.data(), count, welded);
    std::vector<WeldVertex> kept(used);
    meshopt_remapVertexBuffer(kept.data(), unique.data(), welded, sizeof(WeldVertex), fetch.data());
    meshopt_remapIndexBuffer(simplified.data(), simplified.data(), count, fetch.data());
    out.positions.resize(used);
    out.normals.resize(used);
    if (!source.uvs.empty()) out.uvs.resize(used);
    if (!source.uvs1.empty()) out.uvs1.resize(used);
    if (!source.tangents.empty()) out.tangents.resize(used);
    if (!source.colors.empty()) out.colors.resize(used);
    for (std::size_t v = 0; v < used; ++v) {
        out.positions[v] = kept[v].position;
        out.normals[v] = kept[v].normal;
        if (!source.uvs.empty()) out.uvs[v] = kept[v].uv;
        if (!source.uvs1.empty()) out.uvs1[v] = kept[v].uv1;
        if (!source.tangents.empty()) out.tangents[v] = kept[v].tangent;
        if (!source.colors.empty()) out.colors[v] = kept[v].color;
    }
    out.indices.assign(simplified.begin(), simplified.end());
    return error;
}

void generateLodChain(Object& object, const std::vector<float>& ratios) {
    assert(!object.levels.empty());
    assert(!ratios.empty() && ratios.front() == 1.0f);
    for (std::size_t k = 1; k < ratios.size(); ++k) assert(ratios[k] > 0.0f && ratios[k] <= ratios[k - 1]);

    Level base = std::move(object.levels[0]);
    object.levels.clear();
    object.levels.reserve(ratios.size());  // `finest` below must stay valid
    base.simplificationError = 0.0f;
    const float objectExtent = extentOf(base.meshes.data(), base.meshes.size());
    std::uint64_t previousTriangles = 0;
    for (const Mesh& mesh : base.meshes) previousTriangles += mesh.indices.size() / 3;
    object.levels.push_back(std::move(base));
    const Level& finest = object.levels[0];

    for (std::size_t k = 1; k < ratios.size(); ++k) {
        Level level;
        float worst = 0.0f;  // absolute error, object-space units
        std::uint64_t triangles = 0;
        for (const Mesh& mesh : finest.meshes) {
            Mesh simplified;
            const float relative = simplifyMesh(mesh, ratios[k], simplified);
            worst = std::max(worst, relative * extentOf(&mesh, 1));
            triangles += simplified.indices.size() / 3;
            if (!simplified.indices.empty()) level.meshes.push_back(std::move(simplified));
        }
        // A level must earn its place: at least 10% fewer triangles than the one before.
        if (triangles == 0 || double(triangles) > 0.9 * double(previousTriangles)) continue;
        level.simplificationError = objectExtent > 0.0f ? worst / objectExtent : 0.0f;
        previousTriangles = triangles;
        object.levels.push_back(std::move(level));
    }
}

}  // namespace lodopt::scenes
