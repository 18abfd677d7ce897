// Stand-ins and interpenetrating occluders for SceneIndex (stand_ins.hpp).
#include "stand_ins.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "scenes/lod_generation.hpp"

namespace lodopt::scheduler::detail {

namespace {

// `mesh` with `indices` (into its vertices) and only the vertices they use: the tables
// transform every vertex.
scenes::Mesh compactMesh(const scenes::Mesh& mesh, std::vector<std::uint32_t> indices) {
    std::vector<std::uint32_t> remap(mesh.positions.size(), UINT32_MAX);
    scenes::Mesh compact;
    compact.material = mesh.material;
    compact.flatNormals = mesh.flatNormals;
    for (std::uint32_t& index : indices) {
        if (remap[index] == UINT32_MAX) {
            remap[index] = std::uint32_t(compact.positions.size());
            compact.positions.push_back(mesh.positions[index]);
            if (index < mesh.normals.size()) compact.normals.push_back(mesh.normals[index]);
            if (index < mesh.uvs.size()) compact.uvs.push_back(mesh.uvs[index]);
            if (index < mesh.uvs1.size()) compact.uvs1.push_back(mesh.uvs1[index]);
            if (index < mesh.tangents.size()) compact.tangents.push_back(mesh.tangents[index]);
            if (index < mesh.colors.size()) compact.colors.push_back(mesh.colors[index]);
        }
        index = remap[index];
    }
    compact.indices = std::move(indices);
    return compact;
}

std::size_t triangleCount(const scenes::Level& level) {
    std::size_t total = 0;
    for (const scenes::Mesh& mesh : level.meshes) total += mesh.indices.size() / 3;
    return total;
}

// Object-space area of the triangle whose indices start at `first`.
double triangleArea(const scenes::Mesh& mesh, std::size_t first) {
    const glm::vec3 a = mesh.positions[mesh.indices[first]], b = mesh.positions[mesh.indices[first + 1]],
                    c = mesh.positions[mesh.indices[first + 2]];
    return 0.5 * double(glm::length(glm::cross(b - a, c - a)));
}

double surfaceArea(const scenes::Level& level) {
    double area = 0.0;
    for (const scenes::Mesh& mesh : level.meshes) {
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) area += triangleArea(mesh, i);
    }
    return area;
}

// `level` cut to its kProxyTriangles largest triangles (by area; ties by order), its meshes
// compacted to the vertices those use.
scenes::Level largestTriangles(const scenes::Level& level) {
    struct Triangle {
        double area;
        std::size_t mesh, first;
    };
    std::vector<Triangle> triangles;
    for (std::size_t m = 0; m < level.meshes.size(); ++m) {
        const scenes::Mesh& mesh = level.meshes[m];
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) triangles.push_back({triangleArea(mesh, i), m, i});
    }
    const std::size_t kept = std::min(triangles.size(), kProxyTriangles);
    std::stable_sort(triangles.begin(), triangles.end(),
                     [](const Triangle& x, const Triangle& y) { return x.area > y.area; });
    std::vector<std::vector<std::size_t>> firsts(level.meshes.size());
    for (std::size_t t = 0; t < kept; ++t) firsts[triangles[t].mesh].push_back(triangles[t].first);
    scenes::Level result = level;
    for (std::size_t m = 0; m < level.meshes.size(); ++m) {
        std::sort(firsts[m].begin(), firsts[m].end());
        std::vector<std::uint32_t> indices;
        for (std::size_t first : firsts[m])
            indices.insert(indices.end(), level.meshes[m].indices.begin() + std::ptrdiff_t(first),
                           level.meshes[m].indices.begin() + std::ptrdiff_t(first + 3));
        result.meshes[m] = compactMesh(level.meshes[m], std::move(indices));
    }
    return result;
}

// True when `other` reaches into `box` beyond `margin` from its faces along every axis: a flat
// sea through the middle of a hull does, a building standing on a flat ground does not.
bool reachesInto(const scenes::Bounds& other, const scenes::Bounds& box, float margin) {
    for (int axis = 0; axis < 3; ++axis) {
        const float low = std::max(other.min[axis], box.min[axis]), high = std::min(other.max[axis], box.max[axis]);
        if (low > high || high <= box.min[axis] + margin || low >= box.max[axis] - margin) return false;
    }
    return true;
}

}  // namespace

scenes::Object proxyOf(const scenes::Object& object) {
    scenes::Object proxy = object;
    for (scenes::Level& level : proxy.levels) {
        const std::size_t total = triangleCount(level);
        const std::size_t stride = std::max<std::size_t>(1, (total + kProxyTriangles - 1) / kProxyTriangles);
        std::size_t triangle = 0;
        for (scenes::Mesh& mesh : level.meshes) {
            std::vector<std::uint32_t> kept;
            for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3, ++triangle) {
                if (triangle % stride != 0) continue;
                kept.insert(kept.end(), mesh.indices.begin() + std::ptrdiff_t(i),
                            mesh.indices.begin() + std::ptrdiff_t(i + 3));
            }
            mesh = compactMesh(mesh, std::move(kept));
        }
    }
    return proxy;
}

scenes::Object surfaceProxyOf(const scenes::Object& object) {
    scenes::Object proxy = object;
    for (scenes::Level& level : proxy.levels) {
        const std::size_t total = triangleCount(level);
        if (total <= kProxyTriangles) continue;
        const float ratio = float(kProxyTriangles) / float(total);
        scenes::Level simplified = level;
        for (scenes::Mesh& mesh : simplified.meshes) {
            scenes::Mesh out;
            scenes::simplifyMesh(mesh, ratio, out);
            mesh = std::move(out);
        }
        const double area = surfaceArea(level);
        const double kept = surfaceArea(simplified);
        level = area > 0.0 && std::abs(kept / area - 1.0) <= 0.1 ? std::move(simplified) : largestTriangles(level);
    }
    return proxy;
}

std::vector<int> interpenetratingOccluders(const std::vector<scenes::Bounds>& worldBoxes, int object) {
    std::vector<int> occluders;
    const scenes::Bounds& box = worldBoxes[std::size_t(object)];
    if (box.empty()) return occluders;
    const float margin = 0.01f * glm::length(box.max - box.min);
    for (int p = 0; p < object; ++p) {
        const scenes::Bounds& other = worldBoxes[std::size_t(p)];
        if (!other.empty() && reachesInto(other, box, margin)) occluders.push_back(p);
    }
    return occluders;
}

scenes::Object cutToBox(const scenes::Object& occluder, const scenes::Bounds& box) {
    scenes::Object cut;
    cut.name = occluder.name;
    cut.transform = occluder.transform;
    cut.levels.push_back(occluder.levels.front());
    for (scenes::Mesh& mesh : cut.levels.front().meshes) {
        std::vector<glm::vec3> world(mesh.positions.size());
        for (std::size_t v = 0; v < world.size(); ++v)
            world[v] = glm::vec3(occluder.transform * glm::vec4(mesh.positions[v], 1.0f));
        std::vector<std::uint32_t> indices;
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const glm::vec3 a = world[mesh.indices[i]], b = world[mesh.indices[i + 1]], c = world[mesh.indices[i + 2]];
            const glm::vec3 low = glm::min(a, glm::min(b, c)), high = glm::max(a, glm::max(b, c));
            if (glm::all(glm::lessThanEqual(low, box.max)) && glm::all(glm::greaterThanEqual(high, box.min)))
                indices.insert(indices.end(), mesh.indices.begin() + std::ptrdiff_t(i),
                               mesh.indices.begin() + std::ptrdiff_t(i + 3));
        }
        mesh = compactMesh(mesh, std::move(indices));
    }
    return cut;
}

}  // namespace lodopt::scheduler::detail
