// Two-sided surface deviation (Metro): hand-worked shapes, transforms, empty and degenerate
// levels, determinism, and the per-level errors of a scene.
#include "scenes/geometric_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/builtin.hpp"
#include "scenes/lod_generation.hpp"
#include "scenes/mesh_builder.hpp"

namespace lodopt::scenes {
namespace {

// The cube [-1, 1]^3: 12 triangles.
std::vector<Mesh> cube() {
    MeshBuilder builder(0);
    builder.addBox({0, 0, 0}, {1, 1, 1});
    return {builder.finish()};
}

// The square z = 0 over [-1, 1]^2: 2 triangles.
std::vector<Mesh> square() {
    MeshBuilder builder(0);
    builder.addQuad({-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
    return {builder.finish()};
}

// A UV sphere of radius 1: its vertices lie on the unit sphere, including (+-1, 0, 0),
// (0, +-1, 0) and (0, 0, +-1) (segments a multiple of 4, rings even).
std::vector<Mesh> sphere(int segments, int rings) {
    MeshBuilder builder(0);
    builder.addEllipsoid({0, 0, 0}, {1, 1, 1}, segments, rings);
    return {builder.finish()};
}

// The octahedron with vertices +-e_i, inscribed in the unit sphere.
std::vector<Mesh> octahedron() {
    MeshBuilder builder(0);
    for (float sx : {-1.0f, 1.0f}) {
        for (float sy : {-1.0f, 1.0f}) {
            for (float sz : {-1.0f, 1.0f}) {
                builder.addTriangle({sx, 0, 0}, {0, sy, 0}, {0, 0, sz});
            }
        }
    }
    return {builder.finish()};
}

Level levelOf(std::vector<Mesh> meshes) {
    Level level;
    level.meshes = std::move(meshes);
    return level;
}

Object objectOf(std::vector<std::vector<Mesh>> levels, const glm::mat4& transform = glm::mat4(1.0f)) {
    Object object;
    object.transform = transform;
    for (std::vector<Mesh>& meshes : levels) object.levels.push_back(levelOf(std::move(meshes)));
    return object;
}

TEST(GeometricError, CubeAgainstItselfIsZero) {
    const SurfaceDeviation same = surfaceDeviation(cube(), cube(), glm::mat4(1.0f));
    // Every sample lies on a triangle of the other side: only rounding is left.
    EXPECT_LE(same.maximum, 1e-12);
    EXPECT_LE(same.mean, 1e-12);
    EXPECT_GE(same.mean, 0.0);
}

// Cube [-1,1]^3 (A) against the square z = 0 over [-1,1]^2 (B):
//   A → B: a point (x, y, +-1) of the top or bottom face lies 1 above (x, y, 0); a side face
//   point (1, y, z) lies |z| <= 1 from (1, y, 0). The corners (+-1, +-1, +-1), vertex samples,
//   are exactly 1 from the square's corners. Max 1; mean (8 x 1 + 16 x 1/2) / 24 = 2/3.
//   B → A: (x, y, 0) is 1 - max(|x|, |y|) from the nearest side face (up or down is 1 away),
//   at most 1 at the centre. max(|x|, |y|) has density 2r on [0, 1], mean 2/3: mean 1/3.
//   Two-sided: maximum 1, mean (2/3 + 1/3) / 2 = 1/2 (both sides have the same sample count).
TEST(GeometricError, CubeAgainstSquareIsOne) {
    const SurfaceDeviation deviation = surfaceDeviation(cube(), square(), glm::mat4(1.0f));
    EXPECT_NEAR(deviation.maximum, 1.0, 1e-12);
    // 1024 stratified samples per side (the minimum): the means of these piecewise-linear
    // distances come within a few 1e-4 of the integrals.
    EXPECT_NEAR(deviation.mean, 0.5, 2e-3);
    // Both one-sided measurements are the same whichever side is first: the same bits.
    const SurfaceDeviation swapped = surfaceDeviation(square(), cube(), glm::mat4(1.0f));
    EXPECT_EQ(swapped.maximum, deviation.maximum);
    EXPECT_EQ(swapped.mean, deviation.mean);
}

// The farthest point of the unit sphere from the inscribed octahedron is along (1,1,1)/sqrt(3),
// 1 - 1/sqrt(3) from the face x + y + z = 1 (at distance 1/sqrt(3) from the centre); the face's
// centre is as far from the sphere. The UV sphere lies inside the unit ball and outside the
// octahedron, so no point of either is farther: 1 - 1/sqrt(3) is an upper bound. The UV
// sphere's faces sag inside the unit sphere by at most 1 - cos(pi / 128) + 1 - cos(pi / 64)
// ~ 1.5e-3 at 128 x 64 (half a ring's and half a segment's angle), and the peak search on the
// sampled side finds the local maximum to far better than that: within 2e-3 below.
TEST(GeometricError, SphereAgainstInscribedOctahedronIsOneMinusInverseSqrtThree) {
    const double analytic = 1.0 - 1.0 / std::sqrt(3.0);
    const SurfaceDeviation deviation = surfaceDeviation(sphere(128, 64), octahedron(), glm::mat4(1.0f));
    EXPECT_LE(deviation.maximum, analytic + 1e-9);
    EXPECT_GE(deviation.maximum, analytic - 2e-3);
    EXPECT_GT(deviation.mean, 0.05);
    EXPECT_LT(deviation.mean, analytic);
}

TEST(GeometricError, ScalingByTwoDoublesTheErrorAndRigidMotionsKeepIt) {
    const std::vector<Mesh> fine = sphere(48, 24);
    const std::vector<Mesh> coarse = octahedron();
    const SurfaceDeviation plain = surfaceDeviation(fine, coarse, glm::mat4(1.0f));
    // A power of two scales every coordinate, distance and area exactly: the same samples at
    // twice the distance, bit for bit.
    const SurfaceDeviation doubled = surfaceDeviation(fine, coarse, glm::scale(glm::mat4(1.0f), glm::vec3(2.0f)));
    EXPECT_EQ(doubled.maximum, 2.0 * plain.maximum);
    EXPECT_EQ(doubled.mean, 2.0 * plain.mean);
    // A rotation and a far translation move the samples by rounding only.
    const glm::mat4 rigid = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1000.0f, -250.0f, 40.0f)), 0.7f,
                                        glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));
    const SurfaceDeviation moved = surfaceDeviation(fine, coarse, rigid);
    EXPECT_NEAR(moved.maximum, plain.maximum, 1e-4 * plain.maximum);
    EXPECT_NEAR(moved.mean, plain.mean, 1e-3 * plain.mean);
}

TEST(GeometricError, EmptyLevelDeviatesByTheOtherSidesDiagonal) {
    const std::vector<Mesh> nothing = {Mesh{}};
    const SurfaceDeviation missing = surfaceDeviation(cube(), nothing, glm::mat4(1.0f));
    EXPECT_DOUBLE_EQ(missing.maximum, 2.0 * std::sqrt(3.0));  // the diagonal of [-1, 1]^3
    EXPECT_DOUBLE_EQ(missing.mean, 2.0 * std::sqrt(3.0));
    const SurfaceDeviation otherWay = surfaceDeviation({}, cube(), glm::scale(glm::mat4(1.0f), glm::vec3(3.0f)));
    EXPECT_DOUBLE_EQ(otherWay.maximum, 6.0 * std::sqrt(3.0));
    const SurfaceDeviation bothEmpty = surfaceDeviation(nothing, {}, glm::mat4(1.0f));
    EXPECT_EQ(bothEmpty.maximum, 0.0);
    EXPECT_EQ(bothEmpty.mean, 0.0);
}

// The square z = 0 over [-1,1]^2 against one zero-area triangle along its diagonal from
// (-1,-1) to (1,1) (the midpoint as third corner). The triangle gets no area samples but is
// still measured to, as a segment: the square's corners (1,-1) and (-1,1), vertex samples, are
// sqrt(2) from it, the farthest; a square point is |x - y| / sqrt(2) away, whose mean over the
// square is (2/3) / sqrt(2) = 0.4714 (|x - y| of two uniform [-1,1] has mean 2/3). The
// triangle's three vertices lie on the square (distance 0) and are its side's only samples.
TEST(GeometricError, DegenerateTrianglesAreMeasuredToButNotSampled) {
    MeshBuilder builder(0);
    builder.addTriangle({-1, -1, 0}, {0, 0, 0}, {1, 1, 0});
    const std::vector<Mesh> sliver = {builder.finish()};
    const SurfaceDeviation deviation = surfaceDeviation(square(), sliver, glm::mat4(1.0f));
    EXPECT_NEAR(deviation.maximum, std::sqrt(2.0), 1e-12);
    EXPECT_NEAR(deviation.mean, (2.0 / 3.0) / std::sqrt(2.0), 3e-3);
    EXPECT_TRUE(std::isfinite(deviation.mean));
}

TEST(GeometricError, SameResultEveryTime) {
    const std::vector<Mesh> fine = sphere(64, 32);
    Object object = objectOf({fine});
    generateLodChain(object);
    ASSERT_GE(object.levels.size(), 3u);
    const SurfaceDeviation first = surfaceDeviation(object.levels[2].meshes, fine, glm::mat4(1.0f));
    const SurfaceDeviation second = surfaceDeviation(object.levels[2].meshes, fine, glm::mat4(1.0f));
    EXPECT_EQ(first.maximum, second.maximum);
    EXPECT_EQ(first.mean, second.mean);
    EXPECT_GT(first.maximum, 0.0);
}

TEST(GeometricError, ResultsDoNotDependOnTheThreadCount) {
    Scene one = makeBuiltinScene("harbor");
    Scene three = one;
    Scene again = one;
    GeometricErrorParameters parameters;
    parameters.threads = 1;
    computeGeometricErrors(one, parameters);
    computeGeometricErrors(again, parameters);
    parameters.threads = 3;
    computeGeometricErrors(three, parameters);
    for (std::size_t o = 0; o < one.objects.size(); ++o) {
        for (std::size_t k = 0; k < one.objects[o].levels.size(); ++k) {
            ASSERT_TRUE(one.objects[o].levels[k].geometricError.has_value());
            EXPECT_EQ(*three.objects[o].levels[k].geometricError, *one.objects[o].levels[k].geometricError)
                << one.objects[o].name << " level " << k;
            EXPECT_EQ(*again.objects[o].levels[k].geometricError, *one.objects[o].levels[k].geometricError)
                << one.objects[o].name << " level " << k;
        }
    }
}

TEST(GeometricError, FillsLevelZeroWithZeroAndCoarserLevelsGrow) {
    Scene scene;
    scene.objects.push_back(objectOf({sphere(64, 32)}));
    generateLodChain(scene.objects[0]);
    const std::size_t levels = scene.objects[0].levels.size();
    ASSERT_GE(levels, 4u);
    computeGeometricErrors(scene);
    const std::vector<Level>& chain = scene.objects[0].levels;
    ASSERT_TRUE(chain[0].geometricError.has_value());
    EXPECT_EQ(*chain[0].geometricError, 0.0f);
    for (std::size_t k = 1; k < levels; ++k) {
        ASSERT_TRUE(chain[k].geometricError.has_value());
        EXPECT_GT(*chain[k].geometricError, 0.0f) << k;
        // Both surfaces lie in the unit ball. (The coarsest level, meshoptimizer's clustering at a
        // sixteenth of the triangles, is off by about 1: it is no longer a sphere.)
        EXPECT_LE(*chain[k].geometricError, 2.0f) << k;
        // Each level halves the triangles: its error may not fall much below the previous one's.
        if (k > 1) {
            EXPECT_GT(*chain[k].geometricError, 0.8f * *chain[k - 1].geometricError) << k;
        }
    }
    EXPECT_GT(*chain[levels - 1].geometricError, 2.0f * *chain[1].geometricError);
}

TEST(GeometricError, LevelsAlreadySetAndMaterialOnlyLevelsAreNotMeasured) {
    Scene scene;
    scene.objects.push_back(objectOf({cube(), square(), cube(), square()}));
    scene.objects[0].levels[1].geometricError = 123.0f;
    computeGeometricErrors(scene);
    const std::vector<Level>& levels = scene.objects[0].levels;
    EXPECT_EQ(*levels[0].geometricError, 0.0f);
    EXPECT_EQ(*levels[1].geometricError, 123.0f);  // kept
    EXPECT_EQ(*levels[2].geometricError, 0.0f);    // level 0's geometry: exactly 0
    EXPECT_NEAR(*levels[3].geometricError, 1.0f, 1e-6f);
}

// Three copies of one object (cube, square): as it is, turned, moved and scaled by 2 (measured
// once in object space and scaled), and stretched 3x along z (measured in world space: the top
// face is 3 above the square, the square's centre 1 from the sides, maximum 3).
TEST(GeometricError, ObjectTransformsGiveWorldUnits) {
    Scene scene;
    scene.objects.push_back(objectOf({cube(), square()}));
    const glm::mat4 similar = glm::scale(
        glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(50.0f, 0.0f, -20.0f)), 1.1f, glm::vec3(0, 1, 0)),
        glm::vec3(2.0f));
    scene.objects.push_back(objectOf({cube(), square()}, similar));
    scene.objects.push_back(objectOf({cube(), square()}, glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 1.0f, 3.0f))));
    scene.objects.push_back(objectOf({cube(), {Mesh{}}}));  // its coarse level has no triangles
    computeGeometricErrors(scene);
    EXPECT_NEAR(*scene.objects[0].levels[1].geometricError, 1.0f, 1e-6f);
    EXPECT_NEAR(*scene.objects[1].levels[1].geometricError, 2.0f, 1e-5f);
    EXPECT_NEAR(*scene.objects[2].levels[1].geometricError, 3.0f, 1e-6f);
    EXPECT_NEAR(*scene.objects[3].levels[1].geometricError, 2.0f * std::sqrt(3.0f), 1e-6f);
}

TEST(GeometricError, EveryHarborLevelGetsAFiniteError) {
    Scene scene = makeBuiltinScene("harbor");
    computeGeometricErrors(scene);
    for (const Object& object : scene.objects) {
        ASSERT_GE(object.levels.size(), 2u);
        EXPECT_EQ(object.levels[0].geometricError, 0.0f) << object.name;
        for (std::size_t k = 1; k < object.levels.size(); ++k) {
            const std::optional<float>& error = object.levels[k].geometricError;
            ASSERT_TRUE(error.has_value()) << object.name << " level " << k;
            EXPECT_TRUE(std::isfinite(*error)) << object.name << " level " << k;
            EXPECT_GT(*error, 0.0f) << object.name << " level " << k;
            // No level is off by more than the object's own size.
            EXPECT_LE(*error,
                      2.0f * object.levels[0].stats.bounds.sphereRadius * glm::length(glm::vec3(object.transform[0])))
                << object.name << " level " << k;
        }
    }
}

}  // namespace
}  // namespace lodopt::scenes
