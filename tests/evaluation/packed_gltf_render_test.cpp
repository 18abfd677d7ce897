// Shared models packed by the pinned npm tools (tests/harness: gltfpack 1.3.0 default and -cc,
// glTF-Transform 3.10.1 draco and webp) load with the same triangles and bounds as their
// originals and render with SSIM >= 0.99 against the original's render from the same views
// (docs/gltf.md, "Packed models"). Packed files are made once per build tree, under
// <build>/packed-gltf/<packer>/, and made again when the original is newer; the renders of a
// view under the bound are written beside them.
//
// The representative cases run in the suite; DISABLED_FullTable prints the whole table of
// docs/results.md §10 (docs/gltf.md "Packed models" says what it shows):
//   build/tests/evaluation_tests --gtest_also_run_disabled_tests --gtest_filter='PackedGltf.DISABLED_FullTable'
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <unistd.h>

#include "metrics/metrics.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "scenes/gltf_io.hpp"
#include "lodopt_test_paths.hpp"

using namespace lodopt;
namespace fs = std::filesystem;

namespace {

struct Packer {
    const char* name;
    const char* tool;  // in tests/harness/node_modules/.bin
    const char* before;  // arguments before the input
    const char* between;  // between the input and the output
};

const Packer kPackers[] = {{"gltfpack", "gltfpack", "-i", "-o"},
                           {"gltfpack-cc", "gltfpack", "-cc -i", "-o"},
                           {"draco", "gltf-transform", "draco", ""},
                           {"webp", "gltf-transform", "webp", ""}};

const Packer& packer(const std::string& name) {
    for (const Packer& p : kPackers) {
        if (name == p.name) return p;
    }
    throw std::runtime_error("no packer " + name);
}

const double kMinSsim = 0.99;

// Both shadings: the papers' Lambert (base color and its texture transform only) and PBR.
constexpr renderer::Shading kShadings[] = {renderer::Shading::Lambert, renderer::Shading::Pbr};

std::string sharedModel(const std::string& relative) {
    if (relative.find("render-tests") == 0) return std::string(LODOPT_SHARED_DATA_DIR) + "/gltf/" + relative;
    return std::string(LODOPT_SHARED_DATA_DIR) + "/gltf/models/" + relative;
}

std::string quoted(const std::string& text) { return "'" + text + "'"; }

// The packed file for `model` (made when missing or older than the model), or "" with
// `error` set.
std::string packedFile(const std::string& model, const Packer& packer, std::string& error) {
    const std::string tool = std::string(LODOPT_HARNESS_DIR) + "/node_modules/.bin/" + packer.tool;
    if (!fs::exists(tool)) {
        error = tool + " is missing: run npm ci --prefix tests/harness (the pinned gltfpack and glTF-Transform)";
        return "";
    }
    std::string stem = fs::path(model).lexically_relative(std::string(LODOPT_SHARED_DATA_DIR) + "/gltf").string();
    std::replace(stem.begin(), stem.end(), '/', '_');
    const fs::path folder = fs::path(LODOPT_BINARY_DIR) / "packed-gltf" / packer.name;
    const fs::path out = folder / (fs::path(stem).replace_extension(".glb"));
    std::error_code ec;
    if (fs::exists(out, ec) && fs::last_write_time(out, ec) >= fs::last_write_time(model, ec)) return out.string();
    fs::create_directories(folder, ec);
    // Another test process may pack the same model: write a private name, then rename.
    const std::string temporary = out.string() + "." + std::to_string(::getpid()) + ".glb";
    const std::string log = temporary + ".log";
    const std::string command = quoted(tool) + " " + packer.before + " " + quoted(model) + " " + packer.between + " " +
                                quoted(temporary) + " > " + quoted(log) + " 2>&1";
    if (std::system(command.c_str()) != 0 || !fs::exists(temporary, ec)) {
        std::ostringstream text;
        text << std::ifstream(log).rdbuf();
        error = command + " failed: " + text.str();
        fs::remove(log, ec);
        fs::remove(temporary, ec);
        return "";
    }
    fs::remove(log, ec);
    fs::rename(temporary, out, ec);
    if (ec) {
        error = "cannot rename " + temporary + ": " + ec.message();
        return "";
    }
    return out.string();
}

struct Comparison {
    std::string error;  // empty when both loaded
    std::size_t objectsOriginal = 0, objectsPacked = 0;
    std::uint64_t trianglesOriginal = 0, trianglesPacked = 0;
    double boundsError = 0.0;  // largest world-bound difference over the original's diagonal
    double minSsim[2] = {1.0, 1.0};  // per kShadings, over the original's default views
};

scenes::Bounds sceneBounds(const scenes::Scene& scene) {
    scenes::Bounds bounds;
    bounds.min = glm::vec3(std::numeric_limits<float>::max());
    bounds.max = glm::vec3(-std::numeric_limits<float>::max());
    for (const scenes::Object& object : scene.objects) {
        const scenes::Bounds world = scenes::worldBounds(object, 0);
        if (world.empty()) continue;
        bounds.min = glm::min(bounds.min, world.min);
        bounds.max = glm::max(bounds.max, world.max);
    }
    return bounds;
}

std::uint64_t triangles(const scenes::Scene& scene) {
    std::uint64_t total = 0;
    for (const scenes::Object& object : scene.objects) total += object.levels[0].stats.triangles;
    return total;
}

std::vector<renderer::Frame> renderViews(const scenes::Scene& scene, const std::vector<scenes::Camera>& views,
                                         renderer::Shading shading) {
    renderer::RenderSettings settings;
    settings.width = settings.height = 256;
    settings.shading = shading;
    renderer::Renderer renderer(scene, settings);
    std::vector<renderer::Frame> frames;
    for (const scenes::Camera& view : views) frames.push_back(renderer.render(scenes::referenceCombination(scene), view));
    return frames;
}

// `imagePrefix`: when not empty, the frames of views under kMinSsim are written as
// <imagePrefix>_<view>_original.png and _packed.png, so that a person can look.
Comparison compare(const std::string& original, const std::string& packed, const std::string& imagePrefix = "") {
    Comparison result;
    scenes::GltfLoadOptions options;
    options.generateLods = false;
    scenes::Scene reference, candidate;
    try {
        reference = scenes::loadGltf(original, options);
        candidate = scenes::loadGltf(packed, options);
    } catch (const std::exception& e) {
        result.error = e.what();
        return result;
    }
    result.objectsOriginal = reference.objects.size();
    result.objectsPacked = candidate.objects.size();
    result.trianglesOriginal = triangles(reference);
    result.trianglesPacked = triangles(candidate);
    const scenes::Bounds a = sceneBounds(reference), b = sceneBounds(candidate);
    const float diagonal = glm::length(a.max - a.min);
    result.boundsError = std::max(glm::length(a.min - b.min), glm::length(a.max - b.max)) / std::max(diagonal, 1e-12f);
    // The same cameras for both: the original's own views, else its default views.
    scenes::Scene framed = reference;
    framed.views.clear();
    scenes::addDefaultViews(framed);
    metrics::MetricParameters parameters;
    for (std::size_t s = 0; s < std::size(kShadings); ++s) {
        const std::vector<renderer::Frame> before = renderViews(reference, framed.views, kShadings[s]);
        const std::vector<renderer::Frame> after = renderViews(candidate, framed.views, kShadings[s]);
        for (std::size_t v = 0; v < before.size(); ++v) {
            const auto view = [](const renderer::Frame& frame) {
                return metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4);
            };
            const double ssim = metrics::ssim(view(after[v]), view(before[v]), parameters);
            result.minSsim[s] = std::min(result.minSsim[s], ssim);
            if (!imagePrefix.empty() && ssim < kMinSsim) {
                const std::string stem =
                    imagePrefix + "_" + framed.views[v].name + "_" + renderer::shadingName(kShadings[s]);
                renderer::writeColorImage(stem + "_original.png", before[v]);
                renderer::writeColorImage(stem + "_packed.png", after[v]);
            }
        }
    }
    return result;
}

// Draco and WebP keep the node structure; gltfpack merges meshes and nodes, so only the
// totals are compared. Positions are quantized (gltfpack 14 bits, Draco 11-14 bits): the world
// bounds move by at most a few thousandths of the diagonal.
void checkCase(const std::string& model, const std::string& packerName) {
    const std::string key = model + " " + packerName;
    const std::string original = sharedModel(model);
    if (!fs::exists(original)) GTEST_SKIP() << original << " is absent (shared test data)";
    std::string error;
    const std::string packed = packedFile(original, packer(packerName), error);
    ASSERT_FALSE(packed.empty()) << error;
    const Comparison result = compare(original, packed, packed.substr(0, packed.size() - 4));
    ASSERT_TRUE(result.error.empty()) << key << ": " << result.error;
    EXPECT_EQ(result.trianglesPacked, result.trianglesOriginal) << key;
    if (packerName == "draco" || packerName == "webp") {
        EXPECT_EQ(result.objectsPacked, result.objectsOriginal) << key;
    }
    EXPECT_LT(result.boundsError, 5e-3) << key;
    for (std::size_t s = 0; s < std::size(kShadings); ++s) {
        EXPECT_GE(result.minSsim[s], kMinSsim) << key << ", --shading " << renderer::shadingName(kShadings[s]);
    }
}

TEST(PackedGltf, CannonGltfpack) { checkCase("babylon/cannon.glb", "gltfpack"); }
TEST(PackedGltf, CannonMeshopt) { checkCase("babylon/cannon.glb", "gltfpack-cc"); }
TEST(PackedGltf, CannonDraco) { checkCase("babylon/cannon.glb", "draco"); }
TEST(PackedGltf, CannonWebp) { checkCase("babylon/cannon.glb", "webp"); }
// Fox has neither normals nor indices; gltfpack welds its vertices (1,728 -> 434). Flat
// normals (spec §3.7.2.1) draw both alike; generated smooth normals did not (SSIM 0.972).
TEST(PackedGltf, FoxWeldedByGltfpack) { checkCase("Fox/Fox.glb", "gltfpack"); }
TEST(PackedGltf, ShapeCollectionGltfpack) { checkCase("gltf-transform/ShapeCollection.glb", "gltfpack"); }
TEST(PackedGltf, ShapeCollectionMeshopt) { checkCase("gltf-transform/ShapeCollection.glb", "gltfpack-cc"); }
TEST(PackedGltf, ShapeCollectionDraco) { checkCase("gltf-transform/ShapeCollection.glb", "draco"); }

// Every shared model × every packer, as a Markdown table (docs/results.md §10).
TEST(PackedGltf, DISABLED_FullTable) {
    const std::vector<std::string> models = {
        "FlightHelmet/FlightHelmet.gltf", "Fox/Fox.glb", "CesiumMan/CesiumMan.glb", "kenney/alien.glb",
        "kenney/cakeBirthday.glb", "kenney/tile.glb", "gltf-transform/many-cubes.gltf",
        "gltf-transform/DenseSphere.glb", "gltf-transform/ShapeCollection.glb", "babylon/ExplodingBarrel.glb",
        "babylon/cannon.glb", "render-tests/AlphaBlendModeTest/glTF/AlphaBlendModeTest.gltf",
        "render-tests/BoxTextured/glTF/BoxTextured.gltf", "render-tests/EmissiveStrengthTest/glTF/EmissiveStrengthTest.gltf",
        "render-tests/MetalRoughSpheresNoTextures/glTF/MetalRoughSpheresNoTextures.gltf",
        "render-tests/NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf",
        "render-tests/NormalTangentTest/glTF/NormalTangentTest.gltf", "render-tests/OrientationTest/glTF/OrientationTest.gltf",
        "render-tests/TextureCoordinateTest/glTF/TextureCoordinateTest.gltf",
        "render-tests/TextureSettingsTest/glTF/TextureSettingsTest.gltf",
        "render-tests/TextureTransformTest/glTF/TextureTransformTest.gltf",
        "render-tests/VertexColorTest/glTF/VertexColorTest.gltf"};
    // One row per model, one cell per packer: the lowest SSIM over the default views (bold
    // under the bound), the triangle change when the packer dropped some, or why it did not load.
    std::printf("| model | gltfpack | gltfpack -cc | glTF-Transform draco | glTF-Transform webp |\n|---|---|---|---|---|\n");
    for (const std::string& model : models) {
        const std::string original = sharedModel(model);
        if (!fs::exists(original)) continue;
        std::printf("| %s |", fs::path(model).stem().string().c_str());
        for (const Packer& p : kPackers) {
            std::string error;
            const std::string packed = packedFile(original, p, error);
            if (packed.empty()) {
                std::printf(" packer failed |");
                continue;
            }
            const Comparison r = compare(original, packed, packed.substr(0, packed.size() - 4));
            if (!r.error.empty()) {
                std::string message = r.error.substr(r.error.find(": ") == std::string::npos ? 0 : r.error.find(": ") + 2);
                std::replace(message.begin(), message.end(), '|', '/');
                std::printf(" no: %s |", message.c_str());
                continue;
            }
            for (std::size_t s = 0; s < std::size(kShadings); ++s) {
                std::printf(r.minSsim[s] < kMinSsim ? "%s**%.4f**" : "%s%.4f", s == 0 ? " " : " / ", r.minSsim[s]);
            }
            if (r.trianglesPacked != r.trianglesOriginal) {
                std::printf(" (%+lld triangles)", static_cast<long long>(r.trianglesPacked) -
                                                      static_cast<long long>(r.trianglesOriginal));
            }
            if (r.boundsError >= 5e-3) std::printf(" (bounds moved %.1e)", r.boundsError);
            std::printf(" |");
            std::fflush(stdout);
        }
        std::printf("\n");
    }
}

}  // namespace
