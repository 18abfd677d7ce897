// Two-sided surface deviation after Metro (Cignoni, Rocchini, Scopigno 1998, "Metro: measuring
// error on simplified surfaces"): sample each surface, measure every sample to the nearest point
// of the other (nearest_triangle.hpp). This file: the samples, the one-sided measurements with
// their peak search, and the scene-wide computation (objects grouped by geometry, in parallel).
// Everything is computed in double from the float positions, one sample after the other in a
// fixed order, so a result never depends on the thread that computed it; the file is compiled
// with -ffp-contract=off (scenes/CMakeLists.txt), so no platform fuses a multiply-add.
#include "scenes/geometric_error.hpp"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>
#include <unordered_set>

#include "nearest_triangle.hpp"

namespace lodopt::scenes {

namespace {

using detail::Box;
using detail::Point;
using detail::Triangle;

// A point a + u (b - a) + v (c - a) of triangle `triangle` (u, v >= 0, u + v <= 1).
struct AreaSample {
    Point position;
    std::uint32_t triangle = 0;
    double u = 0.0, v = 0.0;
};

// One side of the measurement: its triangles (transformed) in a BVH, its samples.
struct Surface : detail::TriangleSet {
    std::vector<double> triangleAreas;
    std::vector<AreaSample> areaSamples;
    std::vector<Point> vertexSamples;
    double area = 0.0;
    Box bounds;  // of the vertices its triangles use
    bool hasTriangles() const { return !triangles.empty(); }
};

// Radical inverse in base 2 of `i` (van der Corput), in [0, 1), exact in double.
double vanDerCorput(std::uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    return double(i) * 0x1p-32;
}

Point transformPoint(const glm::dmat4& transform, const glm::vec3& p) {
    return Point(transform * glm::dvec4(glm::dvec3(p), 1.0));
}

// A position's bits, to find exact duplicates.
struct PositionBits {
    std::uint32_t x, y, z;
    bool operator==(const PositionBits&) const = default;
};
struct PositionBitsHash {
    std::size_t operator()(const PositionBits& p) const {
        std::uint64_t h = (std::uint64_t(p.x) * 0x9e3779b97f4a7c15ull) ^ (std::uint64_t(p.y) * 0xc2b2ae3d27d4eb4full);
        h ^= std::uint64_t(p.z) * 0x165667b19e3779f9ull;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};
PositionBits positionBits(const glm::vec3& p) {
    PositionBits bits;
    std::memcpy(&bits.x, &p.x, 4);
    std::memcpy(&bits.y, &p.y, 4);
    std::memcpy(&bits.z, &p.z, 4);
    return bits;
}

std::size_t triangleCount(const std::vector<Mesh>& meshes) {
    std::size_t count = 0;
    for (const Mesh& mesh : meshes) count += mesh.indices.size() / 3;
    return count;
}

// Metro's default sample count, samplesPerTriangle per triangle of the finer surface, within
// the bounds: the density follows the detail there is to miss.
std::uint32_t sampleCount(std::size_t trianglesA, std::size_t trianglesB, const GeometricErrorParameters& parameters) {
    const double wanted = double(parameters.samplesPerTriangle) * double(std::max(trianglesA, trianglesB));
    return static_cast<std::uint32_t>(
        std::clamp(wanted, double(parameters.minSamplesPerSide), double(parameters.maxSamplesPerSide)));
}

void assertValid(const GeometricErrorParameters& parameters) {
    assert(parameters.samplesPerTriangle >= 0);
    assert(parameters.minSamplesPerSide >= 1);
    assert(parameters.maxSamplesPerSide >= parameters.minSamplesPerSide);
    assert(parameters.maxVertexSamples >= 0);
    assert(parameters.threads >= 0);
    (void)parameters;
}

// `samples` area samples (when the surface has area), at most maxVertexSamples vertices.
Surface prepareSurface(const std::vector<Mesh>& meshes, const glm::dmat4& transform, std::uint32_t samples,
                       const GeometricErrorParameters& parameters) {
    Surface surface;
    std::vector<double> areas;  // per triangle, in mesh order
    std::unordered_set<PositionBits, PositionBitsHash> seen;
    for (const Mesh& mesh : meshes) {
        assert(mesh.indices.size() % 3 == 0);
        std::vector<bool> used(mesh.positions.size(), false);
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            for (int k = 0; k < 3; ++k) assert(mesh.indices[i + k] < mesh.positions.size());
            Triangle triangle{transformPoint(transform, mesh.positions[mesh.indices[i]]),
                              transformPoint(transform, mesh.positions[mesh.indices[i + 1]]),
                              transformPoint(transform, mesh.positions[mesh.indices[i + 2]])};
            const Point ab = triangle.b - triangle.a;
            const Point ac = triangle.c - triangle.a;
            const Point normal = glm::cross(ab, ac);
            const double normal2 = glm::dot(normal, normal);
            // A normal this short against its edges (sin^2 of their angle below 1e-24) does not
            // give the face a plane: measured to as three edges, with no area.
            triangle.degenerate = !(normal2 > 1e-24 * glm::dot(ab, ab) * glm::dot(ac, ac));
            areas.push_back(triangle.degenerate ? 0.0 : 0.5 * std::sqrt(normal2));
            for (int k = 0; k < 3; ++k) used[mesh.indices[i + k]] = true;
            surface.triangles.push_back(triangle);
        }
        // Each position once (meshes split vertices along seams and flat edges), in order.
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            if (!used[v] || !seen.insert(positionBits(mesh.positions[v])).second) continue;
            surface.vertexSamples.push_back(transformPoint(transform, mesh.positions[v]));
            surface.bounds.add(surface.vertexSamples.back());
        }
    }
    if (!surface.hasTriangles()) return surface;

    // Vertices beyond the cap: an evenly strided subset, in order.
    const auto maxVertices = static_cast<std::size_t>(parameters.maxVertexSamples);
    if (surface.vertexSamples.size() > maxVertices) {
        const std::size_t count = surface.vertexSamples.size();
        for (std::size_t j = 0; j < maxVertices; ++j) {
            surface.vertexSamples[j] = surface.vertexSamples[j * count / maxVertices];
        }
        surface.vertexSamples.resize(maxVertices);
    }

    const std::vector<std::uint32_t> order = detail::buildBvh(surface);
    std::vector<std::uint32_t> position(order.size());  // mesh order → BVH order
    surface.triangleAreas.resize(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        position[order[i]] = static_cast<std::uint32_t>(i);
        surface.triangleAreas[i] = areas[order[i]];
    }

    // Systematic area sampling, in mesh order (the BVH's order may differ between standard
    // libraries): sample i sits at (i + 1/2) / N of the cumulative area, which picks its
    // triangle and, by where it falls in that triangle's share, one coordinate r1; the other,
    // r2, is the van der Corput number of i, so a triangle's samples form a stratified
    // (Hammersley-like) set. u = sqrt(r1) (1 - r2), v = sqrt(r1) r2 is uniform in area.
    for (double a : areas) surface.area += a;
    if (surface.area > 0.0) {
        const std::uint32_t count = samples;
        surface.areaSamples.reserve(count);
        std::size_t t = 0;
        double start = 0.0;  // cumulative area before triangle t
        for (std::uint32_t i = 0; i < count; ++i) {
            const double target = (double(i) + 0.5) / double(count) * surface.area;
            while (t + 1 < areas.size() && (areas[t] == 0.0 || start + areas[t] <= target)) start += areas[t++];
            const double r1 = std::clamp((target - start) / areas[t], 0.0, 1.0);
            const double r2 = vanDerCorput(i);
            AreaSample sample;
            sample.triangle = position[t];
            sample.u = std::sqrt(r1) * (1.0 - r2);
            sample.v = std::sqrt(r1) * r2;
            const Triangle& triangle = surface.triangles[sample.triangle];
            sample.position = triangle.a + sample.u * (triangle.b - triangle.a) + sample.v * (triangle.c - triangle.a);
            surface.areaSamples.push_back(sample);
        }
    }
    return surface;
}

// Peaks refined per side: the largest samples on this many different triangles.
constexpr std::size_t kPeakSeeds = 32;
constexpr int kPeakEvaluations = 96;  // per seed

// The largest distance to `to` near `seed` on its triangle, by compass search over (u, v)
// (six directions in the triangle's plane, the step halved when none gains) from the spacing
// of the samples down to 1/256 of it. Samples find where the deviation peaks; a peak narrower
// than their spacing (over a gap or a spike simplification removed) is what this finds, so the
// maximum depends little on the sample count. Every value is a true distance of a point of the
// surface, so the maximum still bounds the Hausdorff distance from below.
double refinePeak(const Surface& from, const AreaSample& seed, double seedDistance2, const Surface& to,
                  std::uint32_t& hint, std::vector<std::uint32_t>& stack) {
    const Triangle& triangle = from.triangles[seed.triangle];
    const Point ab = triangle.b - triangle.a;
    const Point ac = triangle.c - triangle.a;
    // The (u, v) triangle has area 1/2 and stands for triangleAreas[t]: a sample's share of the
    // surface, area / N, is (area / N) / (2 triangleArea) of (u, v) space.
    const double share = from.area / double(from.areaSamples.size()) / (2.0 * from.triangleAreas[seed.triangle]);
    const double initialStep = std::min(0.5, std::sqrt(share));
    static constexpr double kDirections[6][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, -1}, {-1, 1}};
    double u = seed.u, v = seed.v, best = seedDistance2;
    int evaluations = 0;
    for (double step = initialStep; step >= initialStep / 256.0 && evaluations < kPeakEvaluations;) {
        double bestU = u, bestV = v, bestHere = best;
        for (const auto& direction : kDirections) {
            const double cu = u + step * direction[0];
            const double cv = v + step * direction[1];
            if (cu < 0.0 || cv < 0.0 || cu + cv > 1.0) continue;
            ++evaluations;
            const double d = detail::nearestDistanceSquared(to, triangle.a + cu * ab + cv * ac, hint, stack);
            if (d > bestHere) {
                bestHere = d;
                bestU = cu;
                bestV = cv;
            }
        }
        if (bestHere > best) {
            best = bestHere;
            u = bestU;
            v = bestV;
        } else {
            step *= 0.5;
        }
    }
    return best;
}

struct OneSided {
    double maximum = 0.0;
    double areaSum = 0.0;  // of the area samples' distances (or the vertices' without area)
    std::size_t areaCount = 0;
};

// `from`'s samples measured to `to`, which has triangles.
OneSided measure(const Surface& from, const Surface& to) {
    OneSided result;
    std::uint32_t hint = 0;
    std::vector<std::uint32_t> stack;
    stack.reserve(64);
    std::vector<double> distances2(from.areaSamples.size());
    double maximum2 = 0.0;
    for (std::size_t i = 0; i < from.areaSamples.size(); ++i) {
        distances2[i] = detail::nearestDistanceSquared(to, from.areaSamples[i].position, hint, stack);
        maximum2 = std::max(maximum2, distances2[i]);
        result.areaSum += std::sqrt(distances2[i]);
    }
    result.areaCount = from.areaSamples.size();
    double vertexSum = 0.0;
    for (const Point& p : from.vertexSamples) {
        const double d2 = detail::nearestDistanceSquared(to, p, hint, stack);
        maximum2 = std::max(maximum2, d2);
        vertexSum += std::sqrt(d2);
    }
    if (result.areaCount == 0) {
        result.areaSum = vertexSum;
        result.areaCount = from.vertexSamples.size();
    }

    // The largest samples, ties by index, one per triangle.
    std::vector<std::uint32_t> ranked(from.areaSamples.size());
    for (std::size_t i = 0; i < ranked.size(); ++i) ranked[i] = static_cast<std::uint32_t>(i);
    std::sort(ranked.begin(), ranked.end(), [&](std::uint32_t l, std::uint32_t r) {
        return distances2[l] != distances2[r] ? distances2[l] > distances2[r] : l < r;
    });
    std::vector<std::uint32_t> seeded;
    for (std::size_t i = 0; i < ranked.size() && seeded.size() < kPeakSeeds; ++i) {
        const AreaSample& seed = from.areaSamples[ranked[i]];
        if (std::find(seeded.begin(), seeded.end(), seed.triangle) != seeded.end()) continue;
        seeded.push_back(seed.triangle);
        maximum2 = std::max(maximum2, refinePeak(from, seed, distances2[ranked[i]], to, hint, stack));
    }
    result.maximum = std::sqrt(maximum2);
    return result;
}

SurfaceDeviation deviation(const Surface& a, const Surface& b) {
    if (!a.hasTriangles() || !b.hasTriangles()) {
        // Nothing to measure to: the whole of the other surface is missing.
        const double d = std::max(a.bounds.diagonal(), b.bounds.diagonal());
        return {d, d};
    }
    const OneSided ab = measure(a, b);
    const OneSided ba = measure(b, a);
    SurfaceDeviation result;
    result.maximum = std::max(ab.maximum, ba.maximum);
    const std::size_t count = ab.areaCount + ba.areaCount;
    result.mean = count > 0 ? (ab.areaSum + ba.areaSum) / double(count) : 0.0;
    return result;
}

// Positions and indices of every mesh equal (what the deviation reads).
bool sameGeometry(const std::vector<Mesh>& a, const std::vector<Mesh>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t m = 0; m < a.size(); ++m) {
        if (a[m].positions != b[m].positions || a[m].indices != b[m].indices) return false;
    }
    return true;
}

bool sameLevelsGeometry(const Object& a, const Object& b) {
    if (a.levels.size() != b.levels.size()) return false;
    for (std::size_t k = 0; k < a.levels.size(); ++k) {
        if (!sameGeometry(a.levels[k].meshes, b.levels[k].meshes)) return false;
    }
    return true;
}

// 64-bit hash of every level's positions and indices (bytes, with their counts).
std::uint64_t geometryHash(const Object& object) {
    std::uint64_t hash = 0x9e3779b97f4a7c15ull;
    const auto mix = [&hash](std::uint64_t word) {
        hash ^= word + 0x9e3779b97f4a7c15ull + (hash << 6) + (hash >> 2);
        hash *= 0xff51afd7ed558ccdull;
        hash ^= hash >> 33;
    };
    const auto mixBytes = [&mix](const void* data, std::size_t bytes) {
        mix(bytes);
        const auto* p = static_cast<const unsigned char*>(data);
        std::size_t i = 0;
        for (; i + 8 <= bytes; i += 8) {
            std::uint64_t word;
            std::memcpy(&word, p + i, 8);
            mix(word);
        }
        std::uint64_t tail = 0;
        if (bytes > i) std::memcpy(&tail, p + i, bytes - i);  // an empty mesh's data() may be null
        mix(tail);
    };
    for (const Level& level : object.levels) {
        mix(level.meshes.size());
        for (const Mesh& mesh : level.meshes) {
            mixBytes(mesh.positions.data(), mesh.positions.size() * sizeof(glm::vec3));
            mixBytes(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
        }
    }
    return hash;
}

// The linear part of an object's transform as a uniform scale times an orthogonal matrix, when
// it is one (within float rounding): the scale, else a negative number.
double similarityScale(const glm::dmat3& linear) {
    const glm::dmat3 gram = glm::transpose(linear) * linear;
    const double scale2 = (gram[0][0] + gram[1][1] + gram[2][2]) / 3.0;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            const double expected = i == j ? scale2 : 0.0;
            if (std::abs(gram[i][j] - expected) > 1e-6 * scale2) return -1.0;
        }
    }
    return std::sqrt(scale2);
}

// Objects measured together: the same geometry under the same measuring transform.
struct Group {
    std::size_t representative = 0;  // an object index
    glm::dmat4 measuringTransform{1.0};
    std::vector<bool> levelNeeded;
    std::once_flag prepared;
    std::unique_ptr<Surface> level0;
    std::atomic<std::size_t> remaining{0};  // tasks still to read level0
};

struct Task {
    std::size_t group = 0;
    std::size_t level = 0;
    double maximum = 0.0;
};

// Runs work(i) for i in [0, count) on `threads` threads; rethrows the first exception.
template <typename Work>
void parallelFor(std::size_t count, int threads, const Work& work) {
    std::size_t workers = threads > 0 ? std::size_t(threads) : std::max(1u, std::thread::hardware_concurrency());
    workers = std::min(workers, count);
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failureMutex;
    const auto run = [&] {
        for (std::size_t i = next++; i < count; i = next++) {
            try {
                work(i);
            } catch (...) {
                std::lock_guard<std::mutex> lock(failureMutex);
                if (!failure) failure = std::current_exception();
                next = count;
            }
        }
    };
    if (workers <= 1) {
        run();
    } else {
        std::vector<std::thread> pool;
        for (std::size_t w = 0; w < workers; ++w) pool.emplace_back(run);
        for (std::thread& thread : pool) thread.join();
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace

SurfaceDeviation surfaceDeviation(const std::vector<Mesh>& a, const std::vector<Mesh>& b, const glm::mat4& transform,
                                  const GeometricErrorParameters& parameters) {
    assertValid(parameters);
    const glm::dmat4 measuring(transform);
    const std::uint32_t samples = sampleCount(triangleCount(a), triangleCount(b), parameters);
    return deviation(prepareSurface(a, measuring, samples, parameters),
                     prepareSurface(b, measuring, samples, parameters));
}

void computeGeometricErrors(Scene& scene, const GeometricErrorParameters& parameters) {
    assertValid(parameters);

    // Group the objects; objectGroup[o] and objectScale[o] say how object o reads its results.
    std::vector<std::unique_ptr<Group>> groups;
    std::unordered_multimap<std::uint64_t, std::size_t> groupsByHash;
    std::vector<std::size_t> objectGroup(scene.objects.size(), 0);
    std::vector<double> objectScale(scene.objects.size(), 1.0);
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        Object& object = scene.objects[o];
        if (!object.levels.empty() && !object.levels[0].geometricError) object.levels[0].geometricError = 0.0f;
        bool needed = false;
        for (const Level& level : object.levels) needed = needed || !level.geometricError;
        if (!needed) continue;
        // Translation never changes a distance; a similarity only scales it, so such objects
        // are measured in object space.
        const glm::dmat3 linear(glm::dmat4(object.transform));
        const double scale = similarityScale(linear);
        const glm::dmat4 measuring = scale >= 0.0 ? glm::dmat4(1.0) : glm::dmat4(linear);
        objectScale[o] = scale >= 0.0 ? scale : 1.0;
        const std::uint64_t hash = geometryHash(object);
        std::size_t found = groups.size();
        const auto [begin, end] = groupsByHash.equal_range(hash);
        for (auto it = begin; it != end && found == groups.size(); ++it) {
            const Group& group = *groups[it->second];
            if (group.measuringTransform == measuring &&
                sameLevelsGeometry(scene.objects[group.representative], object)) {
                found = it->second;
            }
        }
        if (found == groups.size()) {
            auto group = std::make_unique<Group>();
            group->representative = o;
            group->measuringTransform = measuring;
            group->levelNeeded.assign(object.levels.size(), false);
            groups.push_back(std::move(group));
            groupsByHash.emplace(hash, found);
        }
        objectGroup[o] = found;
        for (std::size_t k = 1; k < object.levels.size(); ++k) {
            if (!object.levels[k].geometricError) groups[found]->levelNeeded[k] = true;
        }
    }

    // One task per group and level, in group order, so that a group's level 0 is prepared once
    // by whichever task comes first and released by the last.
    std::vector<Task> tasks;
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const Object& object = scene.objects[groups[g]->representative];
        for (std::size_t k = 1; k < object.levels.size(); ++k) {
            if (!groups[g]->levelNeeded[k]) continue;
            if (sameGeometry(object.levels[k].meshes, object.levels[0].meshes)) continue;  // stays 0
            tasks.push_back({g, k, 0.0});
            ++groups[g]->remaining;
        }
    }
    parallelFor(tasks.size(), parameters.threads, [&](std::size_t t) {
        Task& task = tasks[t];
        Group& group = *groups[task.group];
        const Object& object = scene.objects[group.representative];
        const std::vector<Mesh>& finest = object.levels[0].meshes;
        const std::vector<Mesh>& coarse = object.levels[task.level].meshes;
        const std::size_t finestTriangles = triangleCount(finest);
        std::call_once(group.prepared, [&] {
            group.level0 = std::make_unique<Surface>(prepareSurface(
                finest, group.measuringTransform, sampleCount(finestTriangles, 0, parameters), parameters));
        });
        // Level 0 is usually the finer surface, and its samples serve every level; a level with
        // more triangles asks for more samples on both sides, and gets its own level 0.
        const std::uint32_t samples = sampleCount(finestTriangles, triangleCount(coarse), parameters);
        const Surface level = prepareSurface(coarse, group.measuringTransform, samples, parameters);
        if (group.level0->areaSamples.empty() || group.level0->areaSamples.size() == samples) {
            task.maximum = deviation(level, *group.level0).maximum;
        } else {
            task.maximum =
                deviation(level, prepareSurface(finest, group.measuringTransform, samples, parameters)).maximum;
        }
        if (--group.remaining == 0) group.level0.reset();
    });

    std::vector<std::vector<double>> groupMaximum(groups.size());
    for (std::size_t g = 0; g < groups.size(); ++g) {
        groupMaximum[g].assign(scene.objects[groups[g]->representative].levels.size(), 0.0);
    }
    for (const Task& task : tasks) groupMaximum[task.group][task.level] = task.maximum;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        Object& object = scene.objects[o];
        for (std::size_t k = 1; k < object.levels.size(); ++k) {
            if (object.levels[k].geometricError) continue;
            object.levels[k].geometricError = static_cast<float>(objectScale[o] * groupMaximum[objectGroup[o]][k]);
        }
    }
}

}  // namespace lodopt::scenes
