// meshoptimizer LOD chains: triangle ratios, vertex compaction, the 10% rule, errors.
#include <gtest/gtest.h>

#include "scenes/lod_generation.hpp"
#include "scenes/mesh_builder.hpp"

namespace lodopt::scenes {
namespace {

// A smooth sphere: 64 segments x 32 rings, welded along rings, so it simplifies well.
Mesh sphere() {
    MeshBuilder builder(0);
    builder.addEllipsoid({0, 0, 0}, {1, 1, 1}, 64, 32);
    return builder.finish();
}

std::size_t triangles(const Mesh& mesh) { return mesh.indices.size() / 3; }

TEST(LodGeneration, SimplifyMeshReachesAboutTheRatioAndCompactsVertices) {
    const Mesh source = sphere();
    ASSERT_GT(triangles(source), 3000u);
    for (float ratio : {0.5f, 0.25f, 0.0625f}) {
        Mesh out;
        const float error = simplifyMesh(source, ratio, out);
        const double achieved = double(triangles(out)) / double(triangles(source));
        EXPECT_LE(achieved, 2.0 * ratio) << ratio;
        EXPECT_GE(achieved, 0.5 * ratio) << ratio;
        EXPECT_GT(error, 0.0f);
        EXPECT_LT(error, 0.5f);
        EXPECT_LT(out.positions.size(), source.positions.size());
        EXPECT_EQ(out.normals.size(), out.positions.size());
        EXPECT_EQ(out.uvs.size(), out.positions.size());
        EXPECT_EQ(out.material, source.material);
        for (std::uint32_t index : out.indices) ASSERT_LT(index, out.positions.size());
        // Every kept vertex is used (compacted).
        std::vector<bool> used(out.positions.size(), false);
        for (std::uint32_t index : out.indices) used[index] = true;
        EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);
    }
}

TEST(LodGeneration, RatioOneCopiesAndTinyTargetEmpties) {
    const Mesh source = sphere();
    Mesh same;
    EXPECT_EQ(simplifyMesh(source, 1.0f, same), 0.0f);
    EXPECT_EQ(same.indices, source.indices);
    MeshBuilder builder(3);
    builder.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    Mesh empty;
    EXPECT_GE(simplifyMesh(builder.finish(), 0.1f, empty), 1.0f);
    EXPECT_TRUE(empty.indices.empty());
    EXPECT_EQ(empty.material, 3);
}

TEST(LodGeneration, ChainHasDecreasingLevelsWithErrors) {
    Object object;
    object.name = "ball";
    object.levels.emplace_back();
    object.levels[0].meshes.push_back(sphere());
    object.levels[0].screenCoverage = 0.3f;
    generateLodChain(object);
    ASSERT_EQ(object.levels.size(), kDefaultLodRatios.size());
    EXPECT_EQ(object.levels[0].simplificationError, 0.0f);
    EXPECT_EQ(object.levels[0].meshes[0].indices, sphere().indices);  // level 0 untouched
    const double base = double(triangles(object.levels[0].meshes[0]));
    for (std::size_t k = 1; k < object.levels.size(); ++k) {
        const double count = double(triangles(object.levels[k].meshes[0]));
        EXPECT_LE(count, 0.9 * double(triangles(object.levels[k - 1].meshes[0]))) << k;
        EXPECT_NEAR(count / base, kDefaultLodRatios[k], 0.5 * kDefaultLodRatios[k]) << k;
        EXPECT_GT(object.levels[k].simplificationError, 0.0f) << k;
        EXPECT_GE(object.levels[k].simplificationError, object.levels[k - 1].simplificationError * 0.5f) << k;
    }
}

// A cube of 12 flat triangles cannot lose triangles without collapsing: the 10% rule keeps
// the chain from holding copies, so only level 0 (or genuinely smaller levels) remain.
TEST(LodGeneration, LevelsThatDoNotShrinkAreDropped) {
    Object object;
    MeshBuilder builder(-1);
    builder.addBox({0, 0, 0}, {1, 1, 1});
    object.levels.emplace_back();
    object.levels[0].meshes.push_back(builder.finish());
    generateLodChain(object, {1.0f, 0.95f, 0.9f});
    ASSERT_GE(object.levels.size(), 1u);
    for (std::size_t k = 1; k < object.levels.size(); ++k) {
        std::size_t count = 0, previous = 0;
        for (const Mesh& mesh : object.levels[k].meshes) count += triangles(mesh);
        for (const Mesh& mesh : object.levels[k - 1].meshes) previous += triangles(mesh);
        EXPECT_LE(double(count), 0.9 * double(previous));
    }
    // 0.95 of 12 triangles rounds to 11: not 10% fewer, so that level cannot be there.
    for (const Level& level : object.levels) {
        std::size_t count = 0;
        for (const Mesh& mesh : level.meshes) count += triangles(mesh);
        EXPECT_NE(count, 11u);
    }
}

TEST(LodGeneration, MultiMeshLevelsKeepMaterialsAndErrorIsRelativeToTheObject) {
    Object object;
    object.levels.emplace_back();
    Mesh big = sphere();
    MeshBuilder small(7);
    small.addEllipsoid({5, 0, 0}, {0.5f, 0.5f, 0.5f}, 32, 16);
    object.levels[0].meshes = {big, small.finish()};
    generateLodChain(object, {1.0f, 0.5f});
    ASSERT_EQ(object.levels.size(), 2u);
    ASSERT_EQ(object.levels[1].meshes.size(), 2u);
    EXPECT_EQ(object.levels[1].meshes[0].material, 0);
    EXPECT_EQ(object.levels[1].meshes[1].material, 7);
    EXPECT_GT(object.levels[1].simplificationError, 0.0f);
    EXPECT_LT(object.levels[1].simplificationError, 0.1f);
}

}  // namespace
}  // namespace lodopt::scenes
