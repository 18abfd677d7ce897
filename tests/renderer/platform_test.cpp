// The Renderer draws through the Platform it is given (renderer.hpp): a test or another backend
// injects one.
#include <gtest/gtest.h>

#include <memory>

#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"

using namespace lodopt;

namespace {

// OSMesa underneath, counting how often the renderer makes its context current.
class CountingPlatform final : public renderer::Platform {
public:
    explicit CountingPlatform(int* calls) : mInner(renderer::createOsMesaPlatform()), mCalls(calls) {}
    void makeCurrent() override {
        ++*mCalls;
        mInner->makeCurrent();
    }
    std::string description() const override { return "counting " + mInner->description(); }
    void* getProcAddress(const char* name) const override { return mInner->getProcAddress(name); }

private:
    std::unique_ptr<renderer::Platform> mInner;
    int* mCalls;
};

renderer::RenderSettings smallSettings() {
    renderer::RenderSettings settings;
    settings.width = 96;
    settings.height = 96;
    return settings;
}

}  // namespace

TEST(RendererPlatform, DrawsThroughTheInjectedPlatform) {
    const scenes::Scene scene = scenes::makeHarborScene();
    int calls = 0;
    renderer::Renderer injected(scene, smallSettings(), std::make_unique<CountingPlatform>(&calls));
    EXPECT_EQ(injected.platformDescription().rfind("counting ", 0), 0u) << injected.platformDescription();
    const int afterSetUp = calls;
    EXPECT_GT(afterSetUp, 0);
    const renderer::Frame frame = injected.render({0, 1, 2}, scene.views[0]);
    EXPECT_GT(calls, afterSetUp);

    // The same pixels as the default backend.
    renderer::Renderer ordinary(scene, smallSettings());
    const renderer::Frame expected = ordinary.render({0, 1, 2}, scene.views[0]);
    EXPECT_EQ(frame.rgba, expected.rgba);
    EXPECT_EQ(frame.depth, expected.depth);
    EXPECT_EQ(ordinary.platformDescription(), renderer::createOsMesaPlatform()->description());
}

TEST(RendererPlatform, RefusesANullPlatform) {
    const scenes::Scene scene = scenes::makeHarborScene();
    EXPECT_THROW(renderer::Renderer(scene, smallSettings(), nullptr), renderer::RenderError);
}
