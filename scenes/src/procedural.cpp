#include "procedural.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <glm/gtc/constants.hpp>

namespace lodopt::scenes::procedural {

Rng::Rng(std::uint32_t seed, std::uint64_t stream) : mState(0) {
    // Two splitmix64 rounds decorrelate neighbouring (seed, stream) pairs.
    Rng mixer(std::uint64_t(seed) * 0x9E3779B97F4A7C15ull ^ (stream + 0x632BE59BD9B4E019ull));
    mixer.next();
    mState = mixer.next();
}

std::uint64_t Rng::next() {
    std::uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

float Rng::uniform() {
    return float(next() >> 40) * (1.0f / 16777216.0f);
}

float Rng::uniform(float lo, float hi) {
    return lo + (hi - lo) * uniform();
}

int Rng::uniformInt(int lo, int hi) {
    assert(lo <= hi);
    std::uint64_t range = std::uint64_t(std::int64_t(hi) - std::int64_t(lo)) + 1u;
    std::uint64_t r = ((next() >> 32) * range) >> 32;
    return int(std::int64_t(lo) + std::int64_t(r));
}

bool Rng::chance(float p) {
    return uniform() < p;
}

glm::vec3 Rng::unitVector() {
    float z = uniform(-1.0f, 1.0f);
    float phi = glm::two_pi<float>() * uniform();
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

std::uint32_t hashLattice(std::int32_t x, std::int32_t y, std::uint32_t seed) {
    std::uint32_t h = seed * 0x27D4EB2Du ^ std::uint32_t(x) * 0x85EBCA6Bu ^ std::uint32_t(y) * 0xC2B2AE35u;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    h ^= h >> 15;
    return h;
}

namespace {

float latticeValue(std::int32_t x, std::int32_t y, int periodX, int periodY, std::uint32_t seed) {
    x %= periodX;
    y %= periodY;
    if (x < 0) x += periodX;
    if (y < 0) y += periodY;
    return float(hashLattice(x, y, seed) >> 8) * (1.0f / 16777216.0f);
}

float smooth(float t) {
    return t * t * (3.0f - 2.0f * t);
}

}  // namespace

float valueNoise(float x, float y, int periodX, int periodY, std::uint32_t seed) {
    assert(periodX >= 1 && periodY >= 1);
    float fx = std::floor(x), fy = std::floor(y);
    auto ix = std::int32_t(fx), iy = std::int32_t(fy);
    float tx = smooth(x - fx), ty = smooth(y - fy);
    float a = latticeValue(ix, iy, periodX, periodY, seed), b = latticeValue(ix + 1, iy, periodX, periodY, seed);
    float c = latticeValue(ix, iy + 1, periodX, periodY, seed);
    float d = latticeValue(ix + 1, iy + 1, periodX, periodY, seed);
    return glm::mix(glm::mix(a, b, tx), glm::mix(c, d, tx), ty);
}

float fractalNoise(float x, float y, int periodX, int periodY, int octaves, std::uint32_t seed) {
    assert(octaves >= 1);
    float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        float scale = float(1 << o);
        sum +=
            amplitude * valueNoise(x * scale, y * scale, periodX << o, periodY << o, seed + std::uint32_t(o) * 1013u);
        total += amplitude;
        amplitude *= 0.5f;
    }
    return std::min(sum / total, 0.99999994f);
}

Texture makeTexture(std::string name, int width, int height, const std::function<glm::vec3(float, float)>& color) {
    assert(width > 0 && height > 0);
    Texture texture;
    texture.name = std::move(name);
    texture.width = width;
    texture.height = height;
    texture.rgba.resize(std::size_t(width) * std::size_t(height) * 4u);
    for (int r = 0; r < height; ++r) {
        for (int c = 0; c < width; ++c) {
            glm::vec3 rgb = glm::clamp(color((float(c) + 0.5f) / float(width), (float(r) + 0.5f) / float(height)),
                                       glm::vec3(0.0f), glm::vec3(1.0f));
            std::uint8_t* p = &texture.rgba[(std::size_t(r) * std::size_t(width) + std::size_t(c)) * 4u];
            p[0] = std::uint8_t(std::lround(rgb.r * 255.0f));
            p[1] = std::uint8_t(std::lround(rgb.g * 255.0f));
            p[2] = std::uint8_t(std::lround(rgb.b * 255.0f));
            p[3] = 255;
        }
    }
    return texture;
}

namespace {

std::uint32_t pushVertex(Mesh& mesh, glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
    mesh.uvs.push_back(uv);
    return std::uint32_t(mesh.positions.size() - 1);
}

glm::vec3 faceNormal(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float length = glm::length(n);
    return length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
}

}  // namespace

void appendQuad(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec2 ta, glm::vec2 tb,
                glm::vec2 tc, glm::vec2 td) {
    // The diagonal a-c: for a trapezoid the cross of (c - a) with (d - b) is the plane normal
    // even when one edge is degenerate (a triangle given as a quad).
    glm::vec3 n = faceNormal(a, b, c);
    glm::vec3 nd = glm::cross(c - a, d - b);
    if (glm::length(nd) > 0.0f) n = glm::normalize(nd);
    std::uint32_t ia = pushVertex(mesh, a, n, ta), ib = pushVertex(mesh, b, n, tb);
    std::uint32_t ic = pushVertex(mesh, c, n, tc), id = pushVertex(mesh, d, n, td);
    mesh.indices.insert(mesh.indices.end(), {ia, ib, ic, ia, ic, id});
}

void appendTriangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec2 ta, glm::vec2 tb, glm::vec2 tc) {
    glm::vec3 n = faceNormal(a, b, c);
    std::uint32_t ia = pushVertex(mesh, a, n, ta), ib = pushVertex(mesh, b, n, tb), ic = pushVertex(mesh, c, n, tc);
    mesh.indices.insert(mesh.indices.end(), {ia, ib, ic});
}

void appendMesh(Mesh& mesh, const Mesh& source) {
    auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), source.positions.begin(), source.positions.end());
    mesh.normals.insert(mesh.normals.end(), source.normals.begin(), source.normals.end());
    if (source.uvs.size() == source.positions.size()) {
        mesh.uvs.insert(mesh.uvs.end(), source.uvs.begin(), source.uvs.end());
    } else {
        mesh.uvs.resize(mesh.positions.size(), glm::vec2(0.0f));
    }
    for (std::uint32_t index : source.indices) mesh.indices.push_back(base + index);
}

namespace {

// Centripetal Catmull-Rom (alpha = 0.5) between p1 and p2, t in [0, 1]: no cusps or
// self-intersections for unevenly spaced control points (Yuksel et al. 2011).
glm::vec3 catmullRom(glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, float t) {
    auto knot = [](glm::vec3 a, glm::vec3 b) { return std::max(std::sqrt(glm::length(b - a)), 1e-4f); };
    float t0 = 0.0f, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2), t3 = t2 + knot(p2, p3);
    float s = glm::mix(t1, t2, t);
    glm::vec3 a1 = (t1 - s) / (t1 - t0) * p0 + (s - t0) / (t1 - t0) * p1;
    glm::vec3 a2 = (t2 - s) / (t2 - t1) * p1 + (s - t1) / (t2 - t1) * p2;
    glm::vec3 a3 = (t3 - s) / (t3 - t2) * p2 + (s - t2) / (t3 - t2) * p3;
    glm::vec3 b1 = (t2 - s) / (t2 - t0) * a1 + (s - t0) / (t2 - t0) * a2;
    glm::vec3 b2 = (t3 - s) / (t3 - t1) * a2 + (s - t1) / (t3 - t1) * a3;
    return (t2 - s) / (t2 - t1) * b1 + (s - t1) / (t2 - t1) * b2;
}

}  // namespace

std::vector<glm::vec3> sampleSplineEvenly(const std::vector<glm::vec3>& points, int count) {
    assert(points.size() >= 2 && count >= 2);
    // Dense polyline first (64 steps per span), then walk it at constant arc length.
    const int steps = 64;
    std::vector<glm::vec3> dense;
    const std::size_t spans = points.size() - 1;
    for (std::size_t i = 0; i < spans; ++i) {
        glm::vec3 p1 = points[i], p2 = points[i + 1];
        glm::vec3 p0 = i > 0 ? points[i - 1] : 2.0f * p1 - p2;
        glm::vec3 p3 = i + 2 < points.size() ? points[i + 2] : 2.0f * p2 - p1;
        for (int s = 0; s < steps; ++s) dense.push_back(catmullRom(p0, p1, p2, p3, float(s) / float(steps)));
    }
    dense.push_back(points.back());
    std::vector<float> arc(dense.size(), 0.0f);
    for (std::size_t i = 1; i < dense.size(); ++i) arc[i] = arc[i - 1] + glm::length(dense[i] - dense[i - 1]);
    std::vector<glm::vec3> result;
    result.reserve(std::size_t(count));
    std::size_t segment = 1;
    for (int k = 0; k < count; ++k) {
        float target = arc.back() * float(k) / float(count - 1);
        while (segment + 1 < dense.size() && arc[segment] < target) ++segment;
        float span = arc[segment] - arc[segment - 1];
        float t = span > 0.0f ? std::clamp((target - arc[segment - 1]) / span, 0.0f, 1.0f) : 0.0f;
        result.push_back(glm::mix(dense[segment - 1], dense[segment], t));
    }
    return result;
}

CameraPath makeLookAheadPath(std::string name, float framesPerSecond, const std::vector<glm::vec3>& eyes, int lookAhead,
                             float pitchDrop, const Camera& lens) {
    assert(eyes.size() >= 2 && lookAhead >= 1);
    CameraPath path;
    path.name = std::move(name);
    path.framesPerSecond = framesPerSecond;
    path.frames.reserve(eyes.size());
    const std::size_t n = eyes.size();
    for (std::size_t i = 0; i < n; ++i) {
        Camera camera = lens;
        camera.name = path.name + "_" + std::to_string(i);
        camera.position = eyes[i];
        std::size_t ahead = std::min(n - 1, i + std::size_t(lookAhead));
        glm::vec3 direction = eyes[ahead] - eyes[i];
        if (ahead - i < std::size_t(lookAhead)) {
            // Near the end: keep the last full look-ahead direction, scaled to the same reach.
            std::size_t from = n - 1 > std::size_t(lookAhead) ? n - 1 - std::size_t(lookAhead) : 0;
            direction = eyes[n - 1] - eyes[from];
        }
        camera.target = eyes[i] + direction - glm::vec3(0.0f, pitchDrop, 0.0f);
        path.frames.push_back(camera);
    }
    return path;
}

int addTexture(Scene& scene, Texture texture) {
    scene.textures.push_back(std::move(texture));
    return int(scene.textures.size() - 1);
}

int addDiffuseMaterial(Scene& scene, std::string name, glm::vec3 color, int baseColorTexture) {
    scene.materials.push_back(diffuseMaterial(std::move(name), color, baseColorTexture));
    return int(scene.materials.size() - 1);
}

}  // namespace lodopt::scenes::procedural
