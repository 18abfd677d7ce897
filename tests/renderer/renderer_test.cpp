// Renderer: determinism, layers + composite == full render, timing sanity, image files.
#include <gtest/gtest.h>

#include <cmath>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <random>

#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "scenes/mesh_builder.hpp"

using namespace lodopt;

namespace {

renderer::RenderSettings smallSettings() {
    renderer::RenderSettings settings;
    settings.width = 256;
    settings.height = 256;
    return settings;
}

// Fraction of pixels whose color differs between two frames.
double differingFraction(const renderer::Frame& a, const renderer::Frame& b) {
    EXPECT_EQ(a.rgba.size(), b.rgba.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.rgba.size(); i += 4) {
        if (!std::equal(&a.rgba[i], &a.rgba[i] + 4, &b.rgba[i])) ++differ;
    }
    return double(differ) / double(a.rgba.size() / 4);
}

// Writes both frames and their difference for a person to look at when a test fails.
void dumpOnFailure(const std::string& name, const renderer::Frame& expected, const renderer::Frame& actual) {
    auto dir = std::filesystem::temp_directory_path() / "lodopt-test-failures";
    renderer::writeColorImage((dir / (name + "_expected.png")).string(), expected);
    renderer::writeColorImage((dir / (name + "_actual.png")).string(), actual);
    renderer::Frame diff = actual;
    for (std::size_t i = 0; i < diff.rgba.size(); i += 4) {
        bool same = std::equal(&expected.rgba[i], &expected.rgba[i] + 4, &actual.rgba[i]);
        diff.rgba[i] = same ? 0 : 255;
        diff.rgba[i + 1] = diff.rgba[i + 2] = 0;
        diff.rgba[i + 3] = 255;
    }
    renderer::writeColorImage((dir / (name + "_diff.png")).string(), diff);
    std::cerr << "wrote expected/actual/diff images to " << dir << "\n";
}

}  // namespace

TEST(Renderer, ReportsCoreProfileContext) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    const std::string version = renderer.glVersionString();
    ASSERT_FALSE(version.empty());
    EXPECT_GE(version[0], '3') << version;  // "4.5 (Core Profile) Mesa ..."
    EXPECT_NE(version.find("Core"), std::string::npos) << version;
}

TEST(Renderer, SameInputsGiveBitIdenticalPixels) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    const scenes::Camera& camera = scene.views[0];
    renderer::Frame first = renderer.render({0, 1, 2}, camera);
    renderer.render({4, 4, 4}, camera);  // something else in between
    renderer::Frame second = renderer.render({0, 1, 2}, camera);
    EXPECT_EQ(first.rgba, second.rgba);
    EXPECT_EQ(first.depth, second.depth);
    // A second renderer (a new context) gives the same pixels too.
    renderer::Renderer other(scene, smallSettings());
    EXPECT_EQ(other.render({0, 1, 2}, camera).rgba, first.rgba);
}

TEST(Renderer, ReferenceShowsEveryObjectAndCoarseLevelsDiffer) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    for (const scenes::Camera& camera : scene.views) {
        renderer::Frame reference = renderer.render(scenes::referenceCombination(scene), camera);
        renderer::Frame coarse = renderer.render(scenes::coarsestCombination(scene), camera);
        EXPECT_GT(differingFraction(reference, coarse), 0.001) << camera.name;
    }
    // Overview: the sea covers the lower part, the sky the top rows.
    renderer::Frame overview = renderer.render(scenes::referenceCombination(scene), scene.views[0]);
    EXPECT_EQ(overview.depth[0], 1.0f);                                  // sky at the top-left corner
    EXPECT_LT(overview.depth[overview.depth.size() - 1], 1.0f);          // sea at the bottom-right
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        renderer::Layer layer = renderer.renderLayer(int(o), 0, scene.views[0]);
        EXPECT_GT(layer.coveredPixels, 50u) << scene.objects[o].name << " is not visible in the overview";
    }
}

TEST(Renderer, NotDrawnObjectsLeaveBackground) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    renderer::Frame empty = renderer.render({scenes::kNotDrawn, scenes::kNotDrawn, scenes::kNotDrawn}, scene.views[0]);
    std::uint8_t clear[4];
    renderer::clearColorBytes(smallSettings().clearColor, clear);
    for (std::size_t i = 0; i < empty.rgba.size(); i += 4) {
        ASSERT_TRUE(std::equal(clear, clear + 4, &empty.rgba[i])) << "pixel " << i / 4;
        ASSERT_EQ(empty.depth[i / 4], 1.0f);
    }
}

TEST(Renderer, CompositeOfLayersEqualsFullRender) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::RenderSettings settings = smallSettings();
    renderer::Renderer renderer(scene, settings);
    std::mt19937 random(7);
    for (std::size_t v = 0; v < scene.views.size(); ++v) {
        const scenes::Camera& camera = scene.views[v];
        std::vector<std::vector<renderer::Layer>> layers(scene.objects.size());
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            for (std::size_t l = 0; l < scene.objects[o].levels.size(); ++l) {
                layers[o].push_back(renderer.renderLayer(int(o), int(l), camera));
            }
        }
        for (int trial = 0; trial < 6; ++trial) {
            scenes::Combination combination;
            std::vector<const renderer::Layer*> chosen;
            for (std::size_t o = 0; o < scene.objects.size(); ++o) {
                int level = int(random() % scene.objects[o].levels.size());
                combination.push_back(level);
                chosen.push_back(&layers[o][level]);
            }
            renderer::Frame full = renderer.render(combination, camera);
            renderer::Frame composed;
            renderer::composite(chosen, settings.width, settings.height, settings.clearColor, composed);
            const double differ = differingFraction(full, composed);
            if (differ > 0.001) dumpOnFailure("composite_" + camera.name, full, composed);
            EXPECT_LE(differ, 0.001) << camera.name;
            EXPECT_EQ(full.depth, composed.depth) << camera.name;
        }
    }
}

// renderLayer clears, draws and reads back only the object's projected rectangle, and nothing
// for an object out of view: the layer must hold exactly the pixels of the object rendered
// alone over the whole frame. Cameras: every built-in view of the harbor and the forest, one
// inside object 1 (the harbor's ship, a tree; vertices behind the eye: the whole frame is read)
// and one looking away.
TEST(Renderer, LayerEqualsTheObjectRenderedAloneOverTheWholeFrame) {
    for (const char* name : {"harbor", "forest"}) {
        scenes::Scene scene = scenes::loadScene(name);
        renderer::RenderSettings settings;
        settings.width = 96;
        settings.height = 80;  // not square: rows and columns must not be swapped
        renderer::Renderer renderer(scene, settings);
        std::vector<scenes::Camera> cameras = scene.views;
        const scenes::Bounds object1 = scenes::worldBounds(scene.objects[1], 0);
        scenes::Camera inside = scene.views[0];
        inside.position = object1.sphereCenter;
        inside.target = object1.sphereCenter + glm::vec3(1.0f, -0.2f, 0.3f);
        cameras.push_back(inside);
        scenes::Camera away = scene.views[0];
        away.target = away.position + (away.position - scene.views[0].target);
        cameras.push_back(away);
        std::size_t emptyLayers = 0, layers = 0;
        for (const scenes::Camera& camera : cameras) {
            for (std::size_t o = 0; o < scene.objects.size(); ++o) {
                for (std::size_t l = 0; l < scene.objects[o].levels.size(); ++l) {
                    scenes::Combination alone(scene.objects.size(), scenes::kNotDrawn);
                    alone[o] = int(l);
                    const renderer::Frame whole = renderer.render(alone, camera);
                    const renderer::Layer layer = renderer.renderLayer(int(o), int(l), camera);
                    renderer::PixelRect expected{whole.width, whole.height, 0, 0};
                    std::uint64_t covered = 0;
                    for (int y = 0; y < whole.height; ++y) {
                        for (int x = 0; x < whole.width; ++x) {
                            if (!(whole.depth[std::size_t(y) * whole.width + x] < 1.0f)) continue;
                            ++covered;
                            expected = {std::min(expected.x0, x), std::min(expected.y0, y),
                                        std::max(expected.x1, x + 1), std::max(expected.y1, y + 1)};
                        }
                    }
                    const std::string where = std::string(name) + " " + camera.name + " object " +
                                              std::to_string(o) + " level " + std::to_string(l);
                    ++layers;
                    ASSERT_EQ(layer.coveredPixels, covered) << where;
                    if (covered == 0) {
                        ++emptyLayers;
                        EXPECT_TRUE(layer.rect.empty()) << where;
                        continue;
                    }
                    ASSERT_EQ(layer.rect.x0, expected.x0) << where;
                    ASSERT_EQ(layer.rect.y0, expected.y0) << where;
                    ASSERT_EQ(layer.rect.x1, expected.x1) << where;
                    ASSERT_EQ(layer.rect.y1, expected.y1) << where;
                    const int w = layer.rect.width();
                    for (int y = 0; y < layer.rect.height(); ++y) {
                        const std::size_t at = std::size_t(layer.rect.y0 + y) * whole.width + layer.rect.x0;
                        ASSERT_EQ(0, std::memcmp(&layer.rgba[std::size_t(y) * w * 4], &whole.rgba[at * 4],
                                                 std::size_t(w) * 4))
                            << where << " row " << y;
                        ASSERT_EQ(0, std::memcmp(&layer.depth[std::size_t(y) * w], &whole.depth[at],
                                                 std::size_t(w) * sizeof(float)))
                            << where << " row " << y;
                    }
                }
            }
        }
        EXPECT_GT(emptyLayers, 0u) << name << ": the camera looking away should see nothing";
        EXPECT_LT(emptyLayers, layers) << name;
    }
}

TEST(Renderer, CompositeRectUpdatesOnlyThatRectangle) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::RenderSettings settings = smallSettings();
    renderer::Renderer renderer(scene, settings);
    const scenes::Camera& camera = scene.views[1];
    std::vector<renderer::Layer> fine, coarse;
    for (std::size_t o = 0; o < scene.objects.size(); ++o) {
        fine.push_back(renderer.renderLayer(int(o), 0, camera));
        coarse.push_back(renderer.renderLayer(int(o), int(scene.objects[o].levels.size()) - 1, camera));
    }
    renderer::Frame frame;
    renderer::composite({&fine[0], &fine[1], &fine[2]}, settings.width, settings.height, settings.clearColor, frame);
    // Switch the ship to its coarsest level and update only the union of its two rectangles.
    renderer::PixelRect dirty = fine[1].rect;
    dirty.x0 = std::min(dirty.x0, coarse[1].rect.x0);
    dirty.y0 = std::min(dirty.y0, coarse[1].rect.y0);
    dirty.x1 = std::max(dirty.x1, coarse[1].rect.x1);
    dirty.y1 = std::max(dirty.y1, coarse[1].rect.y1);
    renderer::compositeRect({&fine[0], &coarse[1], &fine[2]}, dirty, settings.clearColor, frame);
    renderer::Frame expected;
    renderer::composite({&fine[0], &coarse[1], &fine[2]}, settings.width, settings.height, settings.clearColor,
                        expected);
    EXPECT_EQ(frame.rgba, expected.rgba);
    EXPECT_EQ(frame.depth, expected.depth);
}

TEST(Renderer, TimesEveryDrawOnEveryClockAndReadsTheFrameClock) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    const renderer::FrameTimes times = renderer.timeFrames(scenes::referenceCombination(scene), scene.views[0], 5, 1);
    ASSERT_EQ(times.wallMs.size(), 5u);
    ASSERT_EQ(times.cpuMs.size(), 5u);
    for (double ms : times.wallMs) {
        EXPECT_GT(ms, 0.0);
        EXPECT_LT(ms, 60'000.0);
    }
    // Mesa has GL_TIME_ELAPSED: recorded beside the wall time, but on llvmpipe it ends before the
    // rasterizer's threads do, so auto reads the wall clock there.
    EXPECT_TRUE(renderer.hasTimerQueries());
    EXPECT_EQ(times.gpuMs.size(), 5u);
    std::vector<double> timerMs = times.gpuMs;
    std::sort(timerMs.begin(), timerMs.end());
    EXPECT_GT(timerMs[2], 0.0);  // the timer counts something: the queued draw
    EXPECT_TRUE(renderer::isSoftwareRasterizer(renderer.glRendererString()));
    EXPECT_EQ(renderer.frameClock(), renderer::FrameClock::Wall);
    EXPECT_EQ(times.clock, renderer::FrameClock::Wall);
    EXPECT_EQ(&times.frameMs(), &times.wallMs);
    std::vector<double> sorted = times.wallMs;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(times.median(), sorted[2]);
    EXPECT_EQ(times.least(), sorted[0]);
    EXPECT_THROW(renderer.timeFrames(scenes::referenceCombination(scene), scene.views[0], 0, 1), renderer::RenderError);

    renderer::RenderSettings gpu = smallSettings();
    gpu.frameClock = renderer::FrameClock::GpuTimer;  // asked for: read, whatever it measures
    renderer::Renderer timer(scene, gpu);
    const renderer::FrameTimes timed = timer.timeFrames(scenes::referenceCombination(scene), scene.views[0], 3, 0);
    EXPECT_EQ(timed.clock, renderer::FrameClock::GpuTimer);
    EXPECT_EQ(&timed.frameMs(), &timed.gpuMs);
}

TEST(Renderer, FrameClockNamesRoundTripAndSoftwareRasterizersAreKnown) {
    for (renderer::FrameClock clock :
         {renderer::FrameClock::Auto, renderer::FrameClock::Wall, renderer::FrameClock::GpuTimer}) {
        EXPECT_EQ(renderer::parseFrameClock(renderer::frameClockName(clock)), clock);
    }
    EXPECT_THROW(renderer::parseFrameClock("cpu"), renderer::RenderError);
    EXPECT_TRUE(renderer::isSoftwareRasterizer("Mesa / llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_TRUE(renderer::isSoftwareRasterizer("Google Inc. / ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device))"));
    EXPECT_FALSE(renderer::isSoftwareRasterizer("NVIDIA Corporation / NVIDIA H100 80GB HBM3/PCIe/SSE2"));
    renderer::FrameTimes none;
    EXPECT_EQ(none.median(), 0.0);
    EXPECT_EQ(none.least(), 0.0);
}

TEST(Renderer, RejectsBadSizesAndCombinations) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::RenderSettings settings = smallSettings();
    settings.width = 0;
    EXPECT_THROW(renderer::Renderer(scene, settings), renderer::RenderError);
    renderer::Renderer renderer(scene, smallSettings());
    EXPECT_THROW(renderer.render({0, 0}, scene.views[0]), scenes::SceneError);
    EXPECT_THROW(renderer.render({0, 9, 0}, scene.views[0]), scenes::SceneError);
    EXPECT_THROW(renderer.renderLayer(5, 0, scene.views[0]), renderer::RenderError);
}

TEST(ImageFiles, RenderedFrameRoundTripsThroughPngAndAtomicWrite) {
    scenes::Scene scene = scenes::makeHarborScene();
    renderer::Renderer renderer(scene, smallSettings());
    renderer::Frame frame = renderer.render(scenes::referenceCombination(scene), scene.views[0]);
    auto dir = std::filesystem::temp_directory_path() / ("lodopt-image-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "frame.png").string();
    renderer::writeColorImage(path, frame);
    renderer::LoadedImage loaded = renderer::readImage(path);
    EXPECT_EQ(loaded.width, frame.width);
    EXPECT_EQ(loaded.height, frame.height);
    ASSERT_EQ(loaded.channels, 4);
    EXPECT_EQ(loaded.pixels, frame.rgba);
    renderer::writeDepthImage((dir / "depth.exr").string(), frame);
    EXPECT_TRUE(std::filesystem::exists(dir / "depth.exr"));
    // Only the two final files: no temporary left behind.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}), 2);
    EXPECT_THROW(renderer::readImage((dir / "missing.png").string()), renderer::RenderError);
    std::filesystem::remove_all(dir);
}
