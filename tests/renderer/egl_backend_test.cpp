// The EGL backend (renderer.hpp createEglPlatform): on this machine's Mesa it draws what OSMesa
// draws, and renderers on the two backends can be used in turn (each call goes through its own
// context's GL functions).
#include <gtest/gtest.h>

#include <string>

#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"

using namespace lodopt;

namespace {

renderer::RenderSettings settingsFor(renderer::Backend backend) {
    renderer::RenderSettings settings;
    settings.width = 128;
    settings.height = 96;
    settings.backend = backend;
    return settings;
}

}  // namespace

TEST(EglBackend, DrawsOsMesasPixelsOnMesa) {
    const scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer osmesa(scene, settingsFor(renderer::Backend::OsMesa));
    renderer::Renderer egl(scene, settingsFor(renderer::Backend::Egl));
    EXPECT_EQ(egl.platformDescription().rfind("EGL ", 0), 0u) << egl.platformDescription();
    EXPECT_NE(egl.glVersionString().find("Core Profile"), std::string::npos) << egl.glVersionString();
    // In turn, twice: each renderer's calls reach its own context.
    for (int round = 0; round < 2; ++round) {
        for (const scenes::Combination& levels : {scenes::Combination{0, 0, 0}, scenes::Combination{1, 2, 1}}) {
            const renderer::Frame expected = osmesa.render(levels, scene.views[0]);
            const renderer::Frame frame = egl.render(levels, scene.views[0]);
            ASSERT_EQ(frame.rgba.size(), expected.rgba.size());
            if (egl.glRendererString().find("llvmpipe") != std::string::npos) {
                // The same rasterizer behind both: the same bytes (docs/renderer.md).
                EXPECT_EQ(frame.rgba, expected.rgba) << "round " << round;
                EXPECT_EQ(frame.depth, expected.depth) << "round " << round;
            }
        }
    }
    EXPECT_GT(egl.timeFrames({0, 0, 0}, scene.views[0], 3, 1).median(), 0.0);
    EXPECT_EQ(egl.hasTimerQueries(), !egl.timeFrames({0, 0, 0}, scene.views[0], 1, 0).gpuMs.empty());
}

TEST(EglBackend, BackendNamesRoundTripAndUnknownOnesAreRefused) {
    for (renderer::Backend backend : {renderer::Backend::OsMesa, renderer::Backend::Egl}) {
        EXPECT_EQ(renderer::parseBackend(renderer::backendName(backend)), backend);
    }
    EXPECT_THROW(renderer::parseBackend("vulkan"), renderer::RenderError);
}
