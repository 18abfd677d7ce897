// The fast path with blended surfaces (glTF alphaMode BLEND under --shading pbr): real models
// that hold opaque, masked and blended materials (AlphaBlendModeTest, FlightHelmet's lenses),
// with generated LOD chains. Along random walks of level changes the fast path's scores equal a
// from-scratch evaluation of a fresh composite to the bit, whichever part caching it uses, and
// its composite equals the full render to the bit, blended pixels included: FlightHelmet's side
// view puts one lens behind the other's frame, where only a fragment-by-fragment blend is right
// (docs/renderer.md "Layers and blending").
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <random>

#include "evaluation/evaluation.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "walk_helpers.hpp"
#include "lodopt_test_paths.hpp"

using namespace lodopt;
using namespace lodopt::test_walks;

namespace {

std::vector<const renderer::Layer*> layersOf(const evaluation::ViewSetup& setup, const scenes::Combination& levels) {
    std::vector<const renderer::Layer*> layers;
    for (std::size_t o = 0; o < levels.size(); ++o) layers.push_back(&setup.layer(int(o), levels[o]));
    return layers;
}

// Whether a layer of `layers` draws blended coverage at (x, y).
bool underBlend(const std::vector<const renderer::Layer*>& layers, int x, int y) {
    for (const renderer::Layer* layer : layers) {
        const renderer::PixelRect& r = layer->rect;
        if (!layer->blends() || x < r.x0 || x >= r.x1 || y < r.y0 || y >= r.y1) continue;
        if (layer->blendRgba[(std::size_t(y - r.y0) * r.width() + (x - r.x0)) * 4 + 3] != 0) return true;
    }
    return false;
}

struct Mismatch {
    std::size_t opaquePixels = 0, blendedPixels = 0;  // differing
    int worstBlended = 0;
    std::size_t blendedCovered = 0;
};

// Compares the composite of `levels` with the full render, pixel by pixel.
void compare(const evaluation::ViewSetup& setup, const scenes::Combination& levels, const renderer::Frame& composed,
             const renderer::Frame& full, Mismatch& mismatch) {
    const std::vector<const renderer::Layer*> layers = layersOf(setup, levels);
    for (int y = 0; y < full.height; ++y) {
        for (int x = 0; x < full.width; ++x) {
            const std::size_t at = (std::size_t(y) * full.width + x) * 4;
            int difference = 0;
            for (int c = 0; c < 4; ++c) difference = std::max(difference, std::abs(int(full.rgba[at + c]) - int(composed.rgba[at + c])));
            if (underBlend(layers, x, y)) {
                ++mismatch.blendedCovered;
                mismatch.blendedPixels += difference != 0;
                mismatch.worstBlended = std::max(mismatch.worstBlended, difference);
            } else {
                mismatch.opaquePixels += difference != 0;
            }
        }
    }
}

std::filesystem::path sharedModel(const std::string& relative) {
    return std::filesystem::path(LODOPT_SHARED_DATA_DIR) / relative;
}

void checkModel(const std::filesystem::path& path, int size, int steps) {
    scenes::Scene scene = scenes::loadGltf(path.string());
    scenes::addDefaultViews(scene);
    ASSERT_FALSE(scene.objects.empty());
    renderer::RenderSettings settings;
    settings.shading = renderer::Shading::Pbr;
    settings.width = settings.height = size;
    renderer::Renderer renderer(scene, settings);
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    Mismatch mismatch;
    std::size_t searchedBlended = 0;
    for (const scenes::Camera& camera : scene.views) {
        evaluation::ViewSetup setup(scene, camera, renderer);
        const std::vector<int> counts = setup.levelCounts();
        if (counts.empty()) continue;
        for (int object : setup.variableObjects()) searchedBlended += setup.layer(object, 0).blends();
        evaluation::LayerEvaluator automatic(setup, parameters);
        evaluation::LayerEvaluator grouped(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                           evaluation::LayerEvaluator::kDefaultStates,
                                           evaluation::PartCaching::Groups);
        evaluation::LayerEvaluator owned(setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels,
                                         evaluation::LayerEvaluator::kDefaultStates, evaluation::PartCaching::On);
        evaluation::FullRenderEvaluator full(setup, renderer, parameters);
        const std::vector<optimizer::Combination> walk = randomWalk(counts, steps, 5);
        for (std::size_t k = 0; k < walk.size(); ++k) {
            const std::string what = path.filename().string() + " / " + camera.name + " step " + std::to_string(k);
            const optimizer::Score score = automatic.evaluate(walk[k]);
            expectSameScore(score, grouped.evaluate(walk[k]), what + " vs window groups");
            expectSameScore(score, owned.evaluate(walk[k]), what + " vs owned windows");
            const renderer::Frame expected = freshComposite(setup, walk[k]);
            ASSERT_EQ(grouped.imageOf(walk[k]).rgba, expected.rgba) << what;
            expectSameScore(score,
                            evaluation::toScore(metrics::evaluate(viewOf(expected), viewOf(setup.reference()), parameters)),
                            what + " vs from scratch");
            if (k % 4 == 0) {
                const scenes::Combination levels = setup.toScene(walk[k]);
                compare(setup, levels, expected, renderer.render(levels, camera), mismatch);
                EXPECT_LT(std::abs(score.fitness - full.evaluate(walk[k]).fitness), 1e-3) << what << " vs full render";
            }
        }
    }
    std::cout << path.filename().string() << ": " << searchedBlended << " searched blended objects over the views; composite vs full "
              << "render: " << mismatch.opaquePixels << " differing pixels without blending, " << mismatch.blendedPixels
              << " of " << mismatch.blendedCovered << " with (worst " << mismatch.worstBlended << " levels)\n";
    EXPECT_GT(searchedBlended, 0u) << path << ": the blended objects must be searched, not skipped";
    EXPECT_GT(mismatch.blendedCovered, 0u);
    EXPECT_EQ(mismatch.opaquePixels, 0u);
    EXPECT_EQ(mismatch.blendedPixels, 0u) << "worst " << mismatch.worstBlended << " levels";
}

}  // namespace

TEST(BlendedFastPath, AlphaBlendModeTestMatchesTheFullRender) {
    const std::filesystem::path path = sharedModel("gltf/render-tests/AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    checkModel(path, 160, 24);
}

TEST(BlendedFastPath, FlightHelmetLensesMatchTheFullRender) {
    const std::filesystem::path path = sharedModel("gltf/models/FlightHelmet/FlightHelmet.gltf");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    checkModel(path, 128, 16);
}
