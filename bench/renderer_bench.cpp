// Overdraw probe: what a fragment costs llvmpipe when it passes or fails the depth test, with and
// without a texture (docs/timemodel.md "Overdraw probe"). Eight screen-filling quads stacked in
// depth, drawn nearest first (seven of eight fragments fail the depth test) or farthest first
// (every fragment passes), against one quad alone: the same rasterized area, different shading.
//
//   build/bench/renderer_bench --benchmark_min_time=1 --benchmark_repetitions=3
//   LP_NUM_THREADS=1 build/bench/renderer_bench ...   # one rasterizer thread
//
// Arguments: layers (1 or 8), order (0 nearest first, 1 farthest first), textured (0/1),
// subdivisions per quad side (1: two triangles; 48: 4,608 triangles, edges everywhere).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>

#include "renderer/renderer.hpp"
#include "scenes/scene.hpp"

using namespace lodopt;

namespace {

// A square of side 2·half in the plane z, cut into sub x sub cells of two triangles.
scenes::Mesh gridQuad(float z, int sub, float half) {
    scenes::Mesh mesh;
    mesh.material = 0;
    for (int j = 0; j <= sub; ++j) {
        for (int i = 0; i <= sub; ++i) {
            const float x = -half + 2 * half * float(i) / float(sub), y = -half + 2 * half * float(j) / float(sub);
            mesh.positions.push_back({x, y, z});
            mesh.normals.push_back({0, 0, 1});
            mesh.uvs.push_back({x, y});
        }
    }
    for (int j = 0; j < sub; ++j) {
        for (int i = 0; i < sub; ++i) {
            const std::uint32_t a = std::uint32_t(j * (sub + 1) + i), b = a + 1, c = a + std::uint32_t(sub) + 1,
                                d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
        }
    }
    return mesh;
}

scenes::Scene stackedQuads(int layers, bool farthestFirst, bool textured, int sub) {
    scenes::Scene scene;
    scene.name = "overdraw_probe";
    scenes::Texture texture;
    texture.name = "noise";
    texture.width = texture.height = 256;
    texture.rgba.resize(256 * 256 * 4);
    for (std::size_t i = 0; i < texture.rgba.size(); ++i) texture.rgba[i] = std::uint8_t((i * 7919u) >> 3);
    scene.textures.push_back(texture);
    scenes::Material material;
    material.name = "quad";
    material.baseColorTexture.texture = textured ? 0 : -1;
    scene.materials.push_back(material);
    for (int k = 0; k < layers; ++k) {
        const int depthRank = farthestFirst ? layers - 1 - k : k;  // 0 = nearest
        scenes::Object object;
        object.name = "quad" + std::to_string(k);
        scenes::Level level;
        level.meshes.push_back(gridQuad(-0.1f * float(depthRank), sub, 1.3f));
        object.levels.push_back(std::move(level));
        scene.objects.push_back(std::move(object));
    }
    scenes::updateStatistics(scene);
    return scene;
}

void BM_StackedQuads(benchmark::State& state) {
    const int layers = int(state.range(0));
    const bool farthestFirst = state.range(1) != 0;
    const bool textured = state.range(2) != 0;
    const int sub = int(state.range(3));
    const scenes::Scene scene = stackedQuads(layers, farthestFirst, textured, sub);
    scenes::Camera camera;
    camera.position = {0.0f, 0.0f, 1.2f};
    camera.target = {0.0f, 0.0f, 0.0f};
    camera.fovYDegrees = 90.0f;
    renderer::Renderer renderer(scene, {});
    const scenes::Combination all(scene.objects.size(), 0);
    renderer.drawAndFinish(all, camera);  // warm-up: shader variants compiled, textures resident
    for (auto _ : state) renderer.drawAndFinish(all, camera);
    state.counters["layers"] = layers;
    state.counters["triangles_per_quad"] = 2.0 * sub * sub;
}

}  // namespace

BENCHMARK(BM_StackedQuads)
    ->ArgNames({"layers", "farthest_first", "textured", "sub"})
    ->ArgsProduct({{1}, {0}, {0, 1}, {1, 48}})
    ->ArgsProduct({{8}, {0, 1}, {0, 1}, {1, 48}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
