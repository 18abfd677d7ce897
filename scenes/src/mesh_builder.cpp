#include "scenes/mesh_builder.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace lodopt::scenes {

void MeshBuilder::setTransform(const glm::mat4& transform) {
    mTransform = transform;
    mNormalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
}

std::uint32_t MeshBuilder::addVertex(glm::vec3 position, glm::vec3 normal, glm::vec2 uv) {
    mMesh.positions.push_back(glm::vec3(mTransform * glm::vec4(position, 1.0f)));
    glm::vec3 n = mNormalMatrix * normal;
    float length = glm::length(n);
    mMesh.normals.push_back(length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f));
    mMesh.uvs.push_back(uv);
    return static_cast<std::uint32_t>(mMesh.positions.size() - 1);
}

void MeshBuilder::addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    std::uint32_t ia = addVertex(a, n, {0.0f, 0.0f});
    std::uint32_t ib = addVertex(b, n, {1.0f, 0.0f});
    std::uint32_t ic = addVertex(c, n, {0.5f, 1.0f});
    mMesh.indices.insert(mMesh.indices.end(), {ia, ib, ic});
}

void MeshBuilder::addQuad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    glm::vec3 n = glm::cross(b - a, d - a);
    float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    std::uint32_t ia = addVertex(a, n, {0.0f, 0.0f});
    std::uint32_t ib = addVertex(b, n, {1.0f, 0.0f});
    std::uint32_t ic = addVertex(c, n, {1.0f, 1.0f});
    std::uint32_t id = addVertex(d, n, {0.0f, 1.0f});
    mMesh.indices.insert(mMesh.indices.end(), {ia, ib, ic, ia, ic, id});
}

void MeshBuilder::addBox(glm::vec3 center, glm::vec3 h) {
    glm::vec3 p[8];
    for (int i = 0; i < 8; ++i) {
        p[i] = center + glm::vec3((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z);
    }
    addQuad(p[0], p[4], p[6], p[2]);  // -x
    addQuad(p[1], p[3], p[7], p[5]);  // +x
    addQuad(p[0], p[1], p[5], p[4]);  // -y
    addQuad(p[2], p[6], p[7], p[3]);  // +y
    addQuad(p[0], p[2], p[3], p[1]);  // -z
    addQuad(p[4], p[5], p[7], p[6]);  // +z
}

void MeshBuilder::addCylinder(glm::vec3 base, float height, float radiusBottom, float radiusTop,
                              int segments, bool capped) {
    segments = std::max(segments, 3);
    const float slope = (radiusBottom - radiusTop) / std::max(height, 1e-6f);
    const std::uint32_t first = static_cast<std::uint32_t>(mMesh.positions.size());
    for (int i = 0; i <= segments; ++i) {
        float angle = glm::two_pi<float>() * float(i) / float(segments);
        glm::vec3 radial(std::cos(angle), 0.0f, std::sin(angle));
        glm::vec3 normal = glm::normalize(radial + glm::vec3(0.0f, slope, 0.0f));
        float u = float(i) / float(segments);
        addVertex(base + radial * radiusBottom, normal, {u, 0.0f});
        addVertex(base + radial * radiusTop + glm::vec3(0.0f, height, 0.0f), normal, {u, 1.0f});
    }
    for (int i = 0; i < segments; ++i) {
        std::uint32_t b0 = first + 2 * i, t0 = b0 + 1, b1 = b0 + 2, t1 = b0 + 3;
        mMesh.indices.insert(mMesh.indices.end(), {b0, t0, t1, b0, t1, b1});
    }
    if (!capped) return;
    for (int cap = 0; cap < 2; ++cap) {
        float radius = cap == 0 ? radiusBottom : radiusTop;
        if (radius <= 0.0f) continue;
        glm::vec3 center = base + glm::vec3(0.0f, cap == 0 ? 0.0f : height, 0.0f);
        glm::vec3 normal(0.0f, cap == 0 ? -1.0f : 1.0f, 0.0f);
        std::uint32_t c = addVertex(center, normal, {0.5f, 0.5f});
        for (int i = 0; i <= segments; ++i) {
            float angle = glm::two_pi<float>() * float(i) / float(segments);
            glm::vec3 radial(std::cos(angle), 0.0f, std::sin(angle));
            addVertex(center + radial * radius, normal, {0.5f + 0.5f * radial.x, 0.5f + 0.5f * radial.z});
        }
        for (int i = 0; i < segments; ++i) {
            std::uint32_t a = c + 1 + i, b = c + 2 + i;
            if (cap == 0) mMesh.indices.insert(mMesh.indices.end(), {c, a, b});
            else mMesh.indices.insert(mMesh.indices.end(), {c, b, a});
        }
    }
}

void MeshBuilder::addEllipsoid(glm::vec3 center, glm::vec3 radii, int segments, int rings) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    const std::uint32_t first = static_cast<std::uint32_t>(mMesh.positions.size());
    for (int r = 0; r <= rings; ++r) {
        float phi = glm::pi<float>() * float(r) / float(rings);
        for (int s = 0; s <= segments; ++s) {
            float theta = glm::two_pi<float>() * float(s) / float(segments);
            glm::vec3 unit(std::sin(phi) * std::cos(theta), std::cos(phi), std::sin(phi) * std::sin(theta));
            glm::vec3 normal = glm::normalize(unit / glm::max(radii, glm::vec3(1e-6f)));
            addVertex(center + unit * radii, normal, {float(s) / float(segments), 1.0f - float(r) / float(rings)});
        }
    }
    const std::uint32_t stride = static_cast<std::uint32_t>(segments + 1);
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            std::uint32_t a = first + r * stride + s, b = a + 1, c = a + stride, d = c + 1;
            if (r != 0) mMesh.indices.insert(mMesh.indices.end(), {a, b, c});
            if (r != rings - 1) mMesh.indices.insert(mMesh.indices.end(), {b, d, c});
        }
    }
}

void MeshBuilder::addHeightGrid(glm::vec3 center, glm::vec2 size, int cellsX, int cellsZ,
                                const std::function<float(float, float)>& height) {
    cellsX = std::max(cellsX, 1);
    cellsZ = std::max(cellsZ, 1);
    const std::uint32_t first = static_cast<std::uint32_t>(mMesh.positions.size());
    auto pointAt = [&](int i, int j) {
        float x = center.x - 0.5f * size.x + size.x * float(i) / float(cellsX);
        float z = center.z - 0.5f * size.y + size.y * float(j) / float(cellsZ);
        return glm::vec3(x, center.y + height(x, z), z);
    };
    const float dx = size.x / float(cellsX), dz = size.y / float(cellsZ);
    for (int j = 0; j <= cellsZ; ++j) {
        for (int i = 0; i <= cellsX; ++i) {
            glm::vec3 p = pointAt(i, j);
            // Central differences of the height field give a smooth normal.
            float hl = height(p.x - dx, p.z), hr = height(p.x + dx, p.z);
            float hd = height(p.x, p.z - dz), hu = height(p.x, p.z + dz);
            glm::vec3 normal = glm::normalize(glm::vec3((hl - hr) / (2.0f * dx), 1.0f, (hd - hu) / (2.0f * dz)));
            addVertex(p, normal, {float(i) / float(cellsX), float(j) / float(cellsZ)});
        }
    }
    const std::uint32_t stride = static_cast<std::uint32_t>(cellsX + 1);
    for (int j = 0; j < cellsZ; ++j) {
        for (int i = 0; i < cellsX; ++i) {
            std::uint32_t a = first + j * stride + i, b = a + 1, c = a + stride, d = c + 1;
            mMesh.indices.insert(mMesh.indices.end(), {a, c, d, a, d, b});
        }
    }
}

void MeshBuilder::addDoubleSidedCard(glm::vec3 a, glm::vec3 b, glm::vec3 up, float height) {
    glm::vec3 c = b + up * height, d = a + up * height;
    addQuad(a, b, c, d);
    addQuad(b, a, d, c);
}

Mesh MeshBuilder::finish() {
    Mesh result = std::move(mMesh);
    mMesh = Mesh{};
    mMesh.material = result.material;
    return result;
}

}  // namespace lodopt::scenes
