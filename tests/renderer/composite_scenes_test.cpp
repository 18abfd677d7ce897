// Layers composited by depth equal the full render on every built-in scene and view, and on a
// multi-object scene assembled from third-party glTF models.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "lodopt_test_paths.hpp"

using namespace lodopt;

namespace {

// Renders random combinations of `scene` from every view fully and by compositing layers;
// returns the worst fraction of differing pixels.
double worstCompositeMismatch(const scenes::Scene& scene, int size, int trials) {
    renderer::RenderSettings settings;
    settings.width = settings.height = size;
    renderer::Renderer renderer(scene, settings);
    std::mt19937 random(17);
    double worst = 0.0;
    for (const scenes::Camera& camera : scene.views) {
        std::vector<std::vector<renderer::Layer>> layers(scene.objects.size());
        for (std::size_t o = 0; o < scene.objects.size(); ++o) {
            for (std::size_t l = 0; l < scene.objects[o].levels.size(); ++l) {
                layers[o].push_back(renderer.renderLayer(int(o), int(l), camera));
            }
        }
        for (int trial = 0; trial < trials; ++trial) {
            scenes::Combination combination;
            std::vector<const renderer::Layer*> chosen;
            for (std::size_t o = 0; o < scene.objects.size(); ++o) {
                const int level = int(random() % scene.objects[o].levels.size());
                combination.push_back(level);
                chosen.push_back(&layers[o][level]);
            }
            renderer::Frame full = renderer.render(combination, camera);
            renderer::Frame composed;
            renderer::composite(chosen, size, size, settings.clearColor, composed);
            std::size_t differ = 0;
            for (std::size_t i = 0; i < full.rgba.size(); i += 4) {
                differ += !std::equal(&full.rgba[i], &full.rgba[i] + 4, &composed.rgba[i]);
            }
            const double fraction = double(differ) / double(size * size);
            worst = std::max(worst, fraction);
            EXPECT_LE(fraction, 0.001) << scene.name << " / " << camera.name;
        }
    }
    return worst;
}

}  // namespace

TEST(CompositeScenes, ForestAndCityEveryView) {
    for (const char* name : {"forest", "city"}) {
        scenes::Scene scene = scenes::loadScene(name);
        const double worst = worstCompositeMismatch(scene, 96, 2);
        std::cout << name << ": worst composite mismatch " << worst * 100.0 << "% of pixels\n";
    }
}

TEST(CompositeScenes, SceneAssembledFromThirdPartyModels) {
    const std::filesystem::path data(LODOPT_SHARED_DATA_DIR);
    const std::vector<std::string> files = {"gltf/models/kenney/alien.glb", "gltf/models/kenney/cakeBirthday.glb",
                                            "gltf/models/babylon/cannon.glb"};
    for (const std::string& file : files) {
        if (!std::filesystem::exists(data / file)) GTEST_SKIP() << "shared data absent: " << (data / file);
    }
    // Place the models side by side, overlapping in depth, in one scene.
    scenes::Scene scene;
    scene.name = "assembled";
    float offset = 0.0f;
    for (const std::string& file : files) {
        scenes::Scene part = scenes::loadGltf((data / file).string());
        const int materialBase = int(scene.materials.size()), textureBase = int(scene.textures.size());
        for (scenes::Material material : part.materials) {
            if (material.baseColorTexture.present()) material.baseColorTexture.texture += textureBase;
            scene.materials.push_back(material);
        }
        for (scenes::Texture& texture : part.textures) scene.textures.push_back(std::move(texture));
        for (scenes::Object& object : part.objects) {
            for (scenes::Level& level : object.levels) {
                for (scenes::Mesh& mesh : level.meshes) {
                    if (mesh.material >= 0) mesh.material += materialBase;
                }
            }
            // Normalise each model to about one unit and line them up along x.
            const scenes::Bounds bounds = scenes::worldBounds(object, 0);
            const float scale = 1.0f / std::max(bounds.sphereRadius, 1e-3f);
            glm::mat4 place(1.0f);
            place[0][0] = place[1][1] = place[2][2] = scale;
            place[3] = glm::vec4(offset - scale * bounds.sphereCenter.x, -scale * bounds.sphereCenter.y,
                                 -scale * bounds.sphereCenter.z, 1.0f);
            object.transform = place * object.transform;
            scene.objects.push_back(std::move(object));
        }
        offset += 1.2f;
    }
    scenes::updateStatistics(scene);
    scenes::addDefaultViews(scene);
    ASSERT_GE(scene.objects.size(), 3u);
    const double worst = worstCompositeMismatch(scene, 128, 3);
    std::cout << "assembled (" << scene.objects.size() << " objects): worst composite mismatch " << worst * 100.0
              << "% of pixels\n";
}
