// Procedural trees and their five LODs; leaf pruning after Dong et al. 2015 (DONG15), eqs.
// (1)-(3). The algorithm and the normalisation of the importance terms are documented in
// forest_tree.hpp.
#include "forest_tree.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <numeric>

#include "scenes/mesh_builder.hpp"

namespace lodopt::scenes::forest {

using procedural::Rng;

const char* speciesName(Species species) {
    switch (species) {
        case Species::Oak:
            return "oak";
        case Species::Pine:
            return "pine";
        case Species::Birch:
            return "birch";
    }
    return "unknown";
}

glm::vec3 barkColor(Species species) {
    switch (species) {
        case Species::Oak:
            return {0.36f, 0.28f, 0.21f};
        case Species::Pine:
            return {0.45f, 0.30f, 0.22f};
        case Species::Birch:
            return {0.86f, 0.85f, 0.80f};
    }
    return glm::vec3(0.5f);
}

glm::vec3 leafColor(Species species) {
    switch (species) {
        case Species::Oak:
            return {0.30f, 0.50f, 0.16f};
        case Species::Pine:
            return {0.16f, 0.34f, 0.20f};
        case Species::Birch:
            return {0.50f, 0.66f, 0.22f};
    }
    return glm::vec3(0.3f, 0.5f, 0.2f);
}

std::vector<float> leafImportance(const std::vector<Leaf>& leaves) {
    std::vector<float> importance(leaves.size(), 0.0f);
    if (leaves.empty()) return importance;
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    float maxArea = 0.0f;
    for (const Leaf& leaf : leaves) {
        lo = glm::min(lo, leafCenter(leaf));
        hi = glm::max(hi, leafCenter(leaf));
        maxArea = std::max(maxArea, leafArea(leaf));
    }
    const glm::vec3 crownCenter = 0.5f * (lo + hi);
    float maxDistance = 0.0f;
    for (const Leaf& leaf : leaves) maxDistance = std::max(maxDistance, glm::length(leafCenter(leaf) - crownCenter));
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        const Leaf& leaf = leaves[i];
        const glm::vec3 center = leafCenter(leaf);
        float dis = maxDistance > 0.0f ? glm::length(center - crownCenter) / maxDistance : 0.0f;
        glm::vec3 radial(center.x, 0.0f, center.z);
        float radialLength = glm::length(radial);
        radial = radialLength > 1e-6f ? radial / radialLength : glm::vec3(1.0f, 0.0f, 0.0f);
        float cosine = std::abs(glm::dot(leafNormal(leaf), radial));
        float area = maxArea > 0.0f ? leafArea(leaf) / maxArea : 0.0f;
        importance[i] = kWeightDistance * dis + kWeightCosine * cosine + kWeightArea * area;  // DONG15 eq. (1)
    }
    return importance;
}

std::vector<Leaf> pruneLeaves(const std::vector<Leaf>& leaves, float lambda) {
    assert(lambda > 0.0f && lambda <= 1.0f);
    if (lambda >= 1.0f || leaves.empty()) return leaves;
    const std::vector<float> importance = leafImportance(leaves);
    std::vector<std::size_t> order(leaves.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return importance[a] > importance[b]; });
    // DONG15 eq. (2): keep the first lambda*N leaves in descending importance.
    const auto keep = std::size_t(std::ceil(double(lambda) * double(leaves.size())));
    std::vector<bool> kept(leaves.size(), false);
    for (std::size_t k = 0; k < keep; ++k) kept[order[k]] = true;
    // DONG15 eq. (3): area x 1/sqrt(lambda), i.e. both card edges x lambda^(-1/4).
    const float edgeScale = std::pow(lambda, -0.25f);
    std::vector<Leaf> result;
    result.reserve(keep);
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        if (!kept[i]) continue;
        Leaf leaf = leaves[i];
        leaf.length *= edgeScale;
        leaf.width *= edgeScale;
        result.push_back(leaf);
    }
    return result;
}

namespace {

// Shape parameters of a species (lengths in metres, angles in degrees above horizontal).
struct SpeciesShape {
    float heightMin, heightMax;
    float trunkRadiusPerHeight;
    float crownBase;  // fraction of the height where branching starts
    float trunkTop;   // fraction of the height the trunk reaches
    float crownRadiusPerHeight;
    bool conifer;                // whorled branches inside a cone instead of an ellipsoid crown
    int primaryMin, primaryMax;  // order-1 branches (conifer: whorls)
    int perWhorl;
    float elevationMin, elevationMax;
    int secondaryPerPrimary, tertiaryPerSecondary;
    int leafCount;
    float leafLength, leafWidth;
};

SpeciesShape shapeOf(Species species) {
    // Fields in declaration order: height range, trunk radius / height, crown base, trunk top,
    // crown radius / height, conifer, order-1 count range, per whorl, elevation range,
    // secondaries, tertiaries, leaf cards, leaf length and width.
    switch (species) {
        case Species::Oak:
            return {8.0f, 13.0f, 0.030f, 0.30f, 0.72f, 0.42f, false, 8, 11, 1, 15.0f, 55.0f, 3, 2, 1050, 0.92f, 0.60f};
        case Species::Pine:
            return {12.0f, 18.0f, 0.024f, 0.28f, 1.0f, 0.20f, true, 11, 14, 5, -15.0f, 12.0f, 2, 0, 850, 0.88f, 0.37f};
        case Species::Birch:
            return {10.0f, 15.0f, 0.018f, 0.38f, 0.92f, 0.19f, false, 7, 10, 1, 45.0f, 70.0f, 3, 2, 900, 0.60f, 0.40f};
    }
    return shapeOf(Species::Oak);
}

// The space branches and leaves grow in.
struct Envelope {
    bool cone = false;
    glm::vec3 center{0.0f};                              // ellipsoid centre
    glm::vec3 radii{1.0f};                               // ellipsoid radii
    float bottom = 0.0f, top = 1.0f, baseRadius = 1.0f;  // cone

    bool contains(glm::vec3 p) const {
        if (cone) {
            if (p.y < bottom - 0.5f || p.y > top) return false;
            float r = baseRadius * std::clamp((top - p.y) / (top - bottom), 0.0f, 1.0f);
            return p.x * p.x + p.z * p.z <= r * r + 0.04f;
        }
        glm::vec3 q = (p - center) / radii;
        return glm::dot(q, q) <= 1.0f;
    }
    // Distance from `p` along unit `direction` before leaving the envelope (0.1 m steps).
    float reach(glm::vec3 p, glm::vec3 direction, float limit) const {
        float t = 0.0f;
        while (t < limit && contains(p + direction * (t + 0.1f))) t += 0.1f;
        return t;
    }
};

glm::vec3 perpendicular(glm::vec3 v, Rng& rng) {
    for (int attempt = 0; attempt < 8; ++attempt) {
        glm::vec3 p = glm::cross(v, rng.unitVector());
        if (glm::length(p) > 0.1f) return glm::normalize(p);
    }
    glm::vec3 p = glm::cross(v, std::abs(v.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0));
    return glm::normalize(p);
}

// A child direction: the parent's turned by `angleDeg` towards a random perpendicular,
// nudged upwards by `lift` (branches of broadleaves reach for light).
glm::vec3 childDirection(glm::vec3 parent, float angleDeg, float lift, Rng& rng) {
    glm::vec3 side = perpendicular(parent, rng);
    float a = glm::radians(angleDeg);
    return glm::normalize(parent * std::cos(a) + side * std::sin(a) + glm::vec3(0.0f, lift, 0.0f));
}

float radiusAt(const Branch& b, float t) {
    return glm::mix(b.radiusStart, b.radiusEnd, t);
}

void addLeaves(TreeSkeleton& tree, const SpeciesShape& shape, const Envelope& envelope, Rng& rng) {
    // Leaves hang on the finer branches, in proportion to their length.
    std::vector<std::size_t> hosts;
    std::vector<float> cumulative;
    float total = 0.0f;
    for (std::size_t i = 0; i < tree.branches.size(); ++i) {
        if (tree.branches[i].order < 1) continue;
        // Broadleaf limbs (order 1) carry leaves on their outer half only: half the weight.
        float weight = (shape.conifer || tree.branches[i].order > 1) ? 1.0f : 0.5f;
        total += weight * glm::length(tree.branches[i].end - tree.branches[i].start);
        hosts.push_back(i);
        cumulative.push_back(total);
    }
    if (hosts.empty()) return;
    const glm::vec3 crownCenter =
        envelope.cone ? glm::vec3(0.0f, 0.5f * (envelope.bottom + envelope.top), 0.0f) : envelope.center;
    const int leafCount = int(float(shape.leafCount) * rng.uniform(0.85f, 1.15f));
    tree.leaves.reserve(std::size_t(leafCount));
    for (int i = 0; i < leafCount; ++i) {
        float pick = rng.uniform() * total;
        std::size_t k = std::size_t(std::lower_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin());
        const Branch& host = tree.branches[hosts[std::min(k, hosts.size() - 1)]];
        float t = (!shape.conifer && host.order == 1) ? rng.uniform(0.5f, 1.0f) : rng.uniform(0.2f, 1.0f);
        glm::vec3 along = glm::normalize(host.end - host.start);
        glm::vec3 point = glm::mix(host.start, host.end, t);
        glm::vec3 outward = point - crownCenter;
        outward = glm::length(outward) > 1e-4f ? glm::normalize(outward) : glm::vec3(0, 1, 0);
        Leaf leaf;
        // Cards cluster around their twig rather than lining it.
        leaf.base = point + rng.unitVector() * rng.uniform(0.02f, 0.3f);
        glm::vec3 axis = rng.unitVector() + along * (shape.conifer ? 1.2f : 0.6f) + outward * 0.5f;
        if (!shape.conifer) axis.y += 0.2f;
        leaf.axis = glm::length(axis) > 1e-3f ? glm::normalize(axis) : along;
        leaf.side = perpendicular(leaf.axis, rng);
        // One face per card (the renderer lights a back face with the flipped normal): turn the
        // front away from the crown centre so that the bent normals (meshLeaves) agree with it.
        if (glm::dot(leafNormal(leaf), outward) < 0.0f) leaf.side = -leaf.side;
        float size = rng.uniform(0.8f, 1.2f);
        leaf.length = shape.leafLength * size;
        leaf.width = shape.leafWidth * size * rng.uniform(0.9f, 1.1f);
        tree.leaves.push_back(leaf);
    }
}

void growBroadleaf(TreeSkeleton& tree, const SpeciesShape& shape, Rng& rng) {
    const float h = tree.height;
    const float trunkRadius = shape.trunkRadiusPerHeight * h;
    const float crownRadius = shape.crownRadiusPerHeight * h * rng.uniform(0.85f, 1.1f);
    Envelope envelope;
    envelope.center = {0.0f, 0.5f * (shape.crownBase * h + h), 0.0f};
    envelope.radii = {crownRadius, 0.5f * (h - shape.crownBase * h), crownRadius};

    // The trunk: two segments with a slight kink at the crown base.
    glm::vec3 kink(rng.uniform(-0.15f, 0.15f), shape.crownBase * h, rng.uniform(-0.15f, 0.15f));
    glm::vec3 top(rng.uniform(-0.3f, 0.3f), shape.trunkTop * h, rng.uniform(-0.3f, 0.3f));
    const float kinkRadius = trunkRadius * 0.75f;
    tree.branches.push_back({{0.0f, -0.5f, 0.0f}, kink, trunkRadius * 1.15f, kinkRadius, 0});
    tree.branches.push_back({kink, top, kinkRadius, trunkRadius * 0.3f, 0});
    const Branch upper = tree.branches.back();

    const int primaries = rng.uniformInt(shape.primaryMin, shape.primaryMax);
    const float golden = glm::radians(137.5f);
    for (int i = 0; i < primaries; ++i) {
        float t = (float(i) + rng.uniform(0.2f, 0.8f)) / float(primaries);
        glm::vec3 start = glm::mix(upper.start, upper.end, t * 0.9f);
        float azimuth = float(i) * golden + rng.uniform(-0.3f, 0.3f);
        float elevation = glm::radians(rng.uniform(shape.elevationMin, shape.elevationMax));
        glm::vec3 dir(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                      std::cos(elevation) * std::sin(azimuth));
        float length = std::max(0.8f, envelope.reach(start, dir, 2.5f * crownRadius) * rng.uniform(0.75f, 0.95f));
        float r0 = radiusAt(upper, t * 0.9f) * 0.6f;
        Branch primary{start, start + dir * length, r0, r0 * 0.25f, 1};
        tree.branches.push_back(primary);
        for (int j = 0; j < shape.secondaryPerPrimary; ++j) {
            float s = rng.uniform(0.3f, 0.9f);
            glm::vec3 p = glm::mix(primary.start, primary.end, s);
            glm::vec3 d = childDirection(dir, rng.uniform(30.0f, 55.0f), 0.25f, rng);
            float len = std::min(envelope.reach(p, d, length) * 0.9f, length * 0.6f * rng.uniform(0.7f, 1.0f));
            len = std::max(len, 0.4f);
            float r1 = radiusAt(primary, s) * 0.6f;
            Branch secondary{p, p + d * len, r1, r1 * 0.3f, 2};
            tree.branches.push_back(secondary);
            for (int k = 0; k < shape.tertiaryPerSecondary; ++k) {
                float u = rng.uniform(0.35f, 0.95f);
                glm::vec3 q = glm::mix(secondary.start, secondary.end, u);
                glm::vec3 e = childDirection(d, rng.uniform(35.0f, 60.0f), 0.2f, rng);
                float l3 = std::max(0.3f, std::min(envelope.reach(q, e, len) * 0.9f, len * 0.55f));
                float r2 = radiusAt(secondary, u) * 0.6f;
                tree.branches.push_back({q, q + e * l3, r2, r2 * 0.4f, 3});
            }
        }
    }
    addLeaves(tree, shape, envelope, rng);
}

void growConifer(TreeSkeleton& tree, const SpeciesShape& shape, Rng& rng) {
    const float h = tree.height;
    const float trunkRadius = shape.trunkRadiusPerHeight * h;
    const float crownRadius = shape.crownRadiusPerHeight * h * rng.uniform(0.85f, 1.1f);
    Envelope envelope;
    envelope.cone = true;
    envelope.bottom = shape.crownBase * h;
    envelope.top = h;
    envelope.baseRadius = crownRadius;

    glm::vec3 mid(rng.uniform(-0.1f, 0.1f), 0.5f * h, rng.uniform(-0.1f, 0.1f));
    tree.branches.push_back({{0.0f, -0.5f, 0.0f}, mid, trunkRadius * 1.1f, trunkRadius * 0.6f, 0});
    tree.branches.push_back({mid, {0.0f, h, 0.0f}, trunkRadius * 0.6f, 0.02f, 0});

    const int whorls = rng.uniformInt(shape.primaryMin, shape.primaryMax);
    for (int w = 0; w < whorls; ++w) {
        float f = float(w) / float(whorls - 1);  // 0 at the crown base, 1 near the top
        float y = glm::mix(envelope.bottom, h * 0.95f, f) + rng.uniform(-0.15f, 0.15f);
        glm::vec3 start(y < mid.y ? mid.x * y / mid.y : mid.x * (h - y) / (h - mid.y), y,
                        y < mid.y ? mid.z * y / mid.y : mid.z * (h - y) / (h - mid.y));
        float trunkHere = y < mid.y ? glm::mix(trunkRadius * 1.1f, trunkRadius * 0.6f, y / mid.y)
                                    : glm::mix(trunkRadius * 0.6f, 0.02f, (y - mid.y) / (h - mid.y));
        for (int j = 0; j < shape.perWhorl; ++j) {
            float azimuth = glm::two_pi<float>() * (float(j) + 0.5f * float(w % 2)) / float(shape.perWhorl) +
                            rng.uniform(-0.25f, 0.25f);
            float elevation =
                glm::radians(glm::mix(shape.elevationMin, shape.elevationMax, f) + rng.uniform(-5.0f, 5.0f));
            glm::vec3 dir(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                          std::cos(elevation) * std::sin(azimuth));
            float length = crownRadius * (h - y) / (h - envelope.bottom) * rng.uniform(0.8f, 1.0f) + 0.3f;
            float r0 = std::max(0.02f, trunkHere * 0.35f);
            Branch primary{start, start + dir * length, r0, r0 * 0.3f, 1};
            tree.branches.push_back(primary);
            for (int k = 0; k < shape.secondaryPerPrimary; ++k) {
                float s = rng.uniform(0.35f, 0.85f);
                glm::vec3 p = glm::mix(primary.start, primary.end, s);
                // Twigs fan out sideways in the branch's plane, alternating sides.
                glm::vec3 sideways = glm::normalize(glm::cross(glm::vec3(0, 1, 0), dir) + glm::vec3(0.0f, 1e-4f, 0.0f));
                float a = glm::radians(rng.uniform(35.0f, 50.0f));
                glm::vec3 d = glm::normalize(dir * std::cos(a) + sideways * std::sin(a) * (k % 2 == 0 ? 1.0f : -1.0f) -
                                             glm::vec3(0.0f, 0.1f, 0.0f));
                float len = std::max(0.3f, length * (1.0f - s) * 0.8f);
                float r1 = radiusAt(primary, s) * 0.6f;
                tree.branches.push_back({p, p + d * len, r1, r1 * 0.4f, 2});
            }
        }
    }
    addLeaves(tree, shape, envelope, rng);
}

// Rotation taking +y to unit `direction` (right-handed basis).
glm::mat4 alignYTo(glm::vec3 origin, glm::vec3 direction) {
    glm::vec3 helper = std::abs(direction.y) < 0.95f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 x = glm::normalize(glm::cross(direction, helper));
    glm::vec3 z = glm::cross(x, direction);
    glm::mat4 m(1.0f);
    m[0] = glm::vec4(x, 0.0f);
    m[1] = glm::vec4(direction, 0.0f);
    m[2] = glm::vec4(z, 0.0f);
    m[3] = glm::vec4(origin, 1.0f);
    return m;
}

// Cylinder sides per branch order (trunk, 1, 2, 3) at levels 0, 1, 2; 0 = pruned.
constexpr int kBranchSegments[3][4] = {{10, 6, 4, 3}, {8, 5, 3, 0}, {6, 4, 0, 0}};

Mesh meshBranches(const TreeSkeleton& tree, int level, int material) {
    MeshBuilder builder(material);
    for (const Branch& branch : tree.branches) {
        int segments = kBranchSegments[level][std::min(branch.order, 3)];
        if (segments == 0) continue;
        glm::vec3 axis = branch.end - branch.start;
        float length = glm::length(axis);
        if (length <= 1e-4f) continue;
        builder.setTransform(alignYTo(branch.start, axis / length));
        builder.addCylinder(glm::vec3(0.0f), length, branch.radiusStart, branch.radiusEnd, segments, false);
    }
    return builder.finish();
}

// Leaf cards, one quad each (front facing away from the crown centre; the renderer lights
// back faces with the flipped normal), with normals bent away from the crown centre: a crown
// of randomly turned cards would shade like noise; bending makes it shade like the volume
// it is (lit on top, darker underneath), the usual foliage trick. The geometry (and DONG15's
// cos term) keeps the true card plane.
Mesh meshLeaves(const std::vector<Leaf>& leaves, glm::vec3 crownCenter, int material) {
    Mesh mesh;
    mesh.material = material;
    mesh.positions.reserve(leaves.size() * 4);
    for (const Leaf& leaf : leaves) {
        glm::vec3 a = leaf.base;
        glm::vec3 tip = leaf.base + leaf.axis * leaf.length;
        glm::vec3 widest = leaf.base + leaf.axis * (0.4f * leaf.length);
        glm::vec3 right = widest + leaf.side * (0.5f * leaf.width);
        glm::vec3 left = widest - leaf.side * (0.5f * leaf.width);
        std::size_t first = mesh.positions.size();
        procedural::appendQuad(mesh, a, right, tip, left, {0.5f, 0.0f}, {1.0f, 0.4f}, {0.5f, 1.0f}, {0.0f, 0.4f});
        glm::vec3 outward = leafCenter(leaf) - crownCenter;
        outward = glm::length(outward) > 1e-4f ? glm::normalize(outward) : glm::vec3(0, 1, 0);
        for (std::size_t v = first; v < mesh.positions.size(); ++v) {
            mesh.normals[v] = glm::normalize(0.4f * mesh.normals[v] + outward + glm::vec3(0.0f, 0.15f, 0.0f));
        }
    }
    return mesh;
}

// Hulls and billboards fill a fraction of the leaf cards' bounding box: a solid hull reads
// larger than the gappy crown it replaces.
constexpr float kHullShrink = 0.8f;

struct CrownBox {
    glm::vec3 min, max;
    glm::vec3 center() const { return 0.5f * (min + max); }
};

CrownBox crownBox(const std::vector<Leaf>& leaves) {
    CrownBox box{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(-std::numeric_limits<float>::max())};
    for (const Leaf& leaf : leaves) {
        for (glm::vec3 p : {leaf.base, leaf.base + leaf.axis * leaf.length}) {
            box.min = glm::min(box.min, p);
            box.max = glm::max(box.max, p);
        }
    }
    return box;
}

float trunkBaseRadius(const TreeSkeleton& tree) {
    return tree.branches.empty() ? 0.2f : tree.branches.front().radiusStart;
}

Level crownHullLevel(const TreeSkeleton& tree, const CrownBox& crown, const TreeMaterials& materials) {
    const bool conifer = tree.species == Species::Pine;
    const float r0 = trunkBaseRadius(tree);
    glm::vec3 c = crown.center();
    glm::vec3 half = 0.5f * (crown.max - crown.min);
    MeshBuilder crownMesh(materials.crown);
    if (conifer) {
        float radius = kHullShrink * std::max(std::max(std::abs(crown.min.x), crown.max.x),
                                              std::max(std::abs(crown.min.z), crown.max.z));
        float height = crown.max.y - crown.min.y;
        crownMesh.addCylinder({0.0f, crown.min.y, 0.0f}, 0.65f * height, radius, 0.0f, 10, true);
        crownMesh.addCylinder({0.0f, crown.min.y + 0.4f * height, 0.0f}, 0.6f * height, 0.65f * radius, 0.0f, 10, true);
    } else {
        crownMesh.addEllipsoid(c, kHullShrink * half, 10, 6);
    }
    MeshBuilder trunk(materials.hullTrunk);
    float trunkTop = conifer ? crown.min.y + 0.3f * (crown.max.y - crown.min.y) : c.y;
    trunk.addCylinder({0.0f, -0.5f, 0.0f}, trunkTop + 0.5f, r0, r0 * 0.5f, 6, false);
    Level level;
    level.meshes.push_back(trunk.finish());
    level.meshes.push_back(crownMesh.finish());
    return level;
}

// A billboard crown normal: mostly the vertical part of the hull normal (lit on top) with a
// little of the horizontal part, because the horizontal parts of two crossed cards differ
// and would split the crown into a light and a dark half along the cards' crossing.
glm::vec3 billboardNormal(glm::vec3 faceNormal, glm::vec3 radial) {
    return glm::normalize(0.3f * faceNormal + glm::vec3(0.4f * radial.x, 0.5f * radial.y + 0.6f, 0.4f * radial.z));
}

// Two crossed vertical cards (x-y and z-y planes) holding the crown's outline (an ellipse
// fan, or three stacked triangles for a conifer) and a trunk strip. Crown normals are bent
// like a hull's so the billboard shades like the level it replaces; since the renderer flips
// the normal of a back face, the crown has two faces 8 cm apart, each with its own bent
// normals, so the face towards the camera always wins the depth test.
Level billboardLevel(const TreeSkeleton& tree, const CrownBox& crown, const TreeMaterials& materials) {
    const bool conifer = tree.species == Species::Pine;
    const float r0 = trunkBaseRadius(tree);
    const glm::vec3 c = crown.center();
    const glm::vec3 half = kHullShrink * 0.5f * (crown.max - crown.min);
    Mesh crownMesh, trunkMesh;
    crownMesh.material = materials.crown;
    trunkMesh.material = materials.flatTrunk;
    for (int card = 0; card < 2; ++card) {
        // Card axes: `along` horizontal in the card, `normal` its face normal.
        // along x up = normal, so counter-clockwise in (along, up) faces +normal.
        glm::vec3 along = card == 0 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, -1);
        glm::vec3 normal = card == 0 ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
        float centerAlong = glm::dot(c, along);
        float radiusAlong = std::max(std::abs(glm::dot(half, along)), 0.3f);
        auto at = [&](float s, float y) { return along * s + glm::vec3(0.0f, y, 0.0f) + normal * glm::dot(c, normal); };
        auto atFace = [&](float s, float y, float facing) { return at(s, y) + normal * (0.04f * facing); };
        auto uv = [&](glm::vec3 p) {
            return glm::vec2(0.5f + 0.5f * (glm::dot(p, along) - centerAlong) / radiusAlong,
                             (p.y - crown.min.y) / std::max(crown.max.y - crown.min.y, 0.1f));
        };
        for (int face = 0; face < 2; ++face) {
            const float facing = face == 0 ? 1.0f : -1.0f;
            auto addCrownTriangle = [&](glm::vec3 a, glm::vec3 b, glm::vec3 d) {
                if (face == 1) std::swap(b, d);
                std::size_t first = crownMesh.positions.size();
                procedural::appendTriangle(crownMesh, a, b, d, uv(a), uv(b), uv(d));
                for (std::size_t v = first; v < crownMesh.positions.size(); ++v) {
                    glm::vec3 radial = (crownMesh.positions[v] - c) / glm::max(half, glm::vec3(0.1f));
                    crownMesh.normals[v] = billboardNormal(facing * normal, radial);
                }
            };
            if (conifer) {
                float height = crown.max.y - crown.min.y;
                for (int tier = 0; tier < 3; ++tier) {
                    float bottom = crown.min.y + 0.28f * height * float(tier);
                    float width = radiusAlong * (1.0f - 0.28f * float(tier));
                    float top = bottom + height * (0.55f - 0.05f * float(tier)) + (tier == 2 ? 0.1f * height : 0.0f);
                    addCrownTriangle(atFace(centerAlong - width, bottom, facing),
                                     atFace(centerAlong + width, bottom, facing),
                                     atFace(centerAlong, std::min(top, crown.max.y), facing));
                }
            } else {
                // An indexed fan: centre plus a ring, so the billboard stays cheaper in vertices
                // than the hull it follows.
                const int sides = 12;
                std::vector<glm::vec3> ring;
                ring.push_back(atFace(centerAlong, c.y, facing));
                for (int i = 0; i < sides; ++i) {
                    float a = glm::two_pi<float>() * float(i) / float(sides);
                    ring.push_back(atFace(centerAlong + radiusAlong * std::cos(a), c.y + half.y * std::sin(a), facing));
                }
                const auto first = std::uint32_t(crownMesh.positions.size());
                for (glm::vec3 p : ring) {
                    glm::vec3 radial = (p - c) / glm::max(half, glm::vec3(0.1f));
                    crownMesh.positions.push_back(p);
                    crownMesh.normals.push_back(billboardNormal(facing * normal, radial));
                    crownMesh.uvs.push_back(uv(p));
                }
                for (int i = 0; i < sides; ++i) {
                    std::uint32_t b = first + 1 + std::uint32_t(i), d = first + 1 + std::uint32_t((i + 1) % sides);
                    if (face == 1) std::swap(b, d);
                    crownMesh.indices.insert(crownMesh.indices.end(), {first, b, d});
                }
            }
        }
        // The trunk strip is one face through the trunk axis: flat normals flip correctly.
        glm::vec3 a = along * -r0 + glm::vec3(0.0f, -0.5f, 0.0f), b = along * r0 + glm::vec3(0.0f, -0.5f, 0.0f);
        glm::vec3 top = glm::vec3(0.0f, crown.min.y + 0.3f * (c.y - crown.min.y) + 0.5f, 0.0f);
        procedural::appendQuad(trunkMesh, a, b, b + top, a + top, {0, 0}, {1, 0}, {1, 1}, {0, 1});
    }
    Level level;
    level.meshes.push_back(std::move(trunkMesh));
    level.meshes.push_back(std::move(crownMesh));
    return level;
}

}  // namespace

TreeSkeleton growTree(Species species, Rng& rng) {
    const SpeciesShape shape = shapeOf(species);
    TreeSkeleton tree;
    tree.species = species;
    tree.height = rng.uniform(shape.heightMin, shape.heightMax);
    if (shape.conifer)
        growConifer(tree, shape, rng);
    else
        growBroadleaf(tree, shape, rng);
    return tree;
}

std::vector<Level> buildTreeLevels(const TreeSkeleton& tree, const TreeMaterials& materials) {
    std::vector<Level> levels;
    levels.reserve(kTreeLevels);
    const CrownBox crown = crownBox(tree.leaves);
    for (int level = 0; level < 3; ++level) {
        Level result;
        result.meshes.push_back(meshBranches(tree, level, materials.bark));
        result.meshes.push_back(
            meshLeaves(pruneLeaves(tree.leaves, kLevelLambda[level]), crown.center(), materials.leaves));
        levels.push_back(std::move(result));
    }
    levels.push_back(crownHullLevel(tree, crown, materials));
    levels.push_back(billboardLevel(tree, crown, materials));
    return levels;
}

}  // namespace lodopt::scenes::forest
