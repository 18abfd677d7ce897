// The harnesses under tests/harness (docs/harness.md): the three.js reference renderer in
// headless Chromium, the validator property ("what the Khronos glTF-Validator accepts, lodopt
// reads") and lodopt against three.js. They need node, the npm packages of tests/harness and
// Chromium, and FAIL (never skip) without them: scripts/quickstart.sh installs all three. They
// skip only when the shared third-party models (../shared/data) are absent.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "harness_support.hpp"
#include "renderer/renderer.hpp"
#include "lodopt_test_paths.hpp"

namespace lodopt::harness_test {
namespace {

namespace fs = std::filesystem;

const fs::path kShared = LODOPT_SHARED_DATA_DIR;
const fs::path kBoxTextured = kShared / "gltf/render-tests/BoxTextured/glTF/BoxTextured.gltf";
// Ours: a white quad (metallic 0, roughness 1) facing the key light, its camera on the light's side.
const fs::path kWhiteSurface = kHarness / "probe" / "white_facing_key_light.gltf";
// What three.js writes for it (docs/harness.md "What three.js computes").
constexpr int kWhiteSurfaceByte = 242;

// The bytes of the pixel at (x, y) of `image` (rows top to bottom).
const std::uint8_t* pixelAt(const renderer::LoadedImage& image, int x, int y) {
    return &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * image.channels];
}

constexpr std::uint8_t kSky[3] = {158, 194, 230};

// The first of the views `lodopt scene info MODEL --json` gives.
nlohmann::json firstView(const fs::path& model) {
    const auto info = cli_test::runLodopt("scene info " + quoted(model) + " --json");
    EXPECT_EQ(info.exitCode, 0) << model;
    return nlohmann::json::parse(info.output)["views"].at(0);
}

class Harness : public HarnessFolderTest {
protected:
    void SetUp() override {
        HarnessFolderTest::SetUp();
        if (HasFatalFailure()) return;
        if (!fs::exists(kShared / "gltf")) GTEST_SKIP() << "shared glTF data not found at " << kShared;
    }
};

// The three.js side alone, in one Chromium run: BoxTextured from lodopt's first default view,
// the lighting probe and the white-surface file (docs/harness.md "What three.js computes"), and
// DenseSphere (Draco).
TEST_F(Harness, ThreeJsDrawsBoxTexturedOverTheExactSky) {
    const fs::path image = mDir / "box.png";
    const fs::path white = mDir / "white.png";
    nlohmann::json jobs = nlohmann::json::array();
    jobs.push_back({{"model", kBoxTextured.string()},
                    {"view", firstView(kBoxTextured)},
                    {"width", 96},
                    {"height", 80},
                    {"out", image.string()}});
    jobs.push_back({{"kind", "probe"}});
    jobs.push_back({{"model", kWhiteSurface.string()},
                    {"view", firstView(kWhiteSurface)},
                    {"width", 16},
                    {"height", 16},
                    {"out", white.string()}});
    // Draco, decoded by three's wasm decoder served from node_modules (nothing fetched elsewhere).
    const fs::path sphere = mDir / "sphere.png";
    const nlohmann::json front = {{"position", {0, 0, 4}}, {"target", {0, 0, 0}}, {"up", {0, 1, 0}},
                                  {"fov_y_degrees", 45},   {"near", 0.1},         {"far", 100}};
    jobs.push_back({{"model", (kShared / "gltf/models/gltf-transform/DenseSphere.glb").string()},
                    {"view", front},
                    {"width", 32},
                    {"height", 32},
                    {"out", sphere.string()}});
    std::ofstream(mDir / "jobs.json") << jobs.dump();

    const NodeRun run = runNode(mDir / "err.txt", "render_threejs.mjs",
                                "--jobs " + quoted(mDir / "jobs.json") + " --json --job-timeout 60");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_LT(run.seconds, 120.0) << "Chromium start and four jobs";

    const renderer::LoadedImage png = renderer::readImage(image.string());
    ASSERT_EQ(png.width, 96);
    ASSERT_EQ(png.height, 80);
    ASSERT_GE(png.channels, 3);
    const auto pixel = [&](int x, int y) { return pixelAt(png, x, y); };
    for (const auto& [x, y] : {std::pair{0, 0}, {95, 0}, {0, 79}, {95, 79}}) {
        const std::uint8_t* p = pixel(x, y);
        EXPECT_EQ(p[0], kSky[0]) << "corner " << x << "," << y;
        EXPECT_EQ(p[1], kSky[1]) << "corner " << x << "," << y;
        EXPECT_EQ(p[2], kSky[2]) << "corner " << x << "," << y;
        if (png.channels == 4) {
            EXPECT_EQ(p[3], 255);
        }
    }
    int notSky = 0;
    for (int y = 0; y < png.height; ++y) {
        for (int x = 0; x < png.width; ++x) {
            const std::uint8_t* p = pixel(x, y);
            notSky += p[0] != kSky[0] || p[1] != kSky[1] || p[2] != kSky[2];
        }
    }
    // lodopt's default views frame the model: the box covers a good part of the frame.
    EXPECT_GT(notSky, png.width * png.height / 10);
    EXPECT_LT(notSky, png.width * png.height);

    // The probe: a white surface (metallic 0, roughness 1) facing the key light, seen from the
    // light. Linear radiance before tone mapping, pinned to what three.js 0.187 computes
    // (docs/harness.md): key 2.5/pi * (1 - F) + GGX, hemisphere 0.96305/pi * (1 - E_spec);
    // 1e-4 covers float differences between GPUs, a change in three's lighting is far larger.
    const nlohmann::json results = nlohmann::json::parse(run.out);
    const nlohmann::json& probe = results.at(1).at("probes").at(0);
    ASSERT_EQ(probe.at("roughness").get<double>(), 1.0);
    EXPECT_NEAR(probe.at("linear_key").at(0).get<double>(), 0.77241, 1e-4);
    EXPECT_NEAR(probe.at("linear_hemisphere").at(0).get<double>(), 0.30204, 1e-4);
    EXPECT_NEAR(probe.at("linear_both").at(0).get<double>(), 1.07445, 1e-4);
    EXPECT_EQ(probe.at("srgb_bytes_both"), nlohmann::json::array({242, 242, 242}));

    // The same surface loaded by GLTFLoader from the glTF file lodopt's PBR test renders.
    const renderer::LoadedImage whitePng = renderer::readImage(white.string());
    ASSERT_EQ(whitePng.width, 16);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pixelAt(whitePng, 8, 8)[k], kWhiteSurfaceByte);

    const renderer::LoadedImage spherePng = renderer::readImage(sphere.string());
    const std::uint8_t* centre = pixelAt(spherePng, 16, 16);
    EXPECT_FALSE(centre[0] == kSky[0] && centre[1] == kSky[1] && centre[2] == kSky[2]) << "the Draco sphere is missing";
    EXPECT_EQ(pixelAt(spherePng, 0, 0)[0], kSky[0]);
}

// Every file of the shared corpus (and BoxTextured and DenseSphere packed by gltfpack, gltfpack
// -cc, gltf-transform draco and webp) that the Khronos validator passes with 0 errors loads in
// lodopt, or is refused (exit 2) naming exactly one required extension lodopt cannot decode.
TEST_F(Harness, EveryFileTheValidatorAcceptsLoadsOrNamesOneRequiredExtension) {
    const NodeRun run = runNode(mDir / "err.txt", "validate_corpus.mjs",
                                "--data " + quoted(kShared) + " --lodopt " + quoted(LODOPT_EXECUTABLE) +
                                    " --pack some --out " + quoted(mDir / "out") + " --json");
    ASSERT_TRUE(run.exitCode == 0 || run.exitCode == 1) << run.err;
    const nlohmann::json result = nlohmann::json::parse(run.out);
    for (const auto& violation : result.at("violations")) {
        ADD_FAILURE() << violation.at("file").get<std::string>() << ": the validator reports 0 errors, lodopt exits "
                      << violation.at("lodopt_exit") << ": " << violation.at("lodopt_message").get<std::string>();
    }
    for (const auto& problem : result.at("problems")) ADD_FAILURE() << "packer: " << problem.get<std::string>();
    for (const auto& name : result.at("known_now_passing")) {
        ADD_FAILURE() << name.get<std::string>() << " loads now: remove it from known_refusals.json";
    }
    EXPECT_EQ(run.exitCode, 0);
    int valid = 0, loads = 0, packed = 0;
    for (const auto& file : result.at("files")) {
        if (file.at("validator_errors").get<int>() != 0) continue;
        ++valid;
        loads += file.at("lodopt").get<std::string>() == "loads";
        packed += !file.at("packed_by").get<std::string>().empty();
    }
    // The corpus: 18 + 11 shared models, about 70 valid files of the validator's own suite, 8 packed.
    EXPECT_GE(valid, 80);
    EXPECT_GE(loads, 60);
    EXPECT_EQ(packed, 8);
}

// The comparison's pipeline with lodopt's default shading (no --shading option): it renders,
// scores and writes its tables, and the default (pbr) matches three.js's MeshStandardMaterial.
TEST_F(Harness, VersusThreeJsRendersScoresAndWritesItsTables) {
    const NodeRun run =
        runNode(mDir / "err.txt", "versus_threejs.mjs",
                "--data " + quoted(kShared) + " --lodopt " + quoted(LODOPT_EXECUTABLE) + " --out " +
                    quoted(mDir / "out") + " --shading default --size 64x64 --only BoxTextured/glTF/ --json");
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const nlohmann::json result = nlohmann::json::parse(run.out);
    ASSERT_EQ(result.at("rows").size(), 3u) << "three default views";
    for (const auto& row : result.at("rows")) {
        EXPECT_EQ(row.at("status"), "ok");
        const double ssim = row.at("ssim").get<double>();
        EXPECT_GT(ssim, 0.9) << "view " << row.at("view");
        EXPECT_LE(ssim, 1.0);
        EXPECT_TRUE(fs::exists(row.at("images").at("diff").get<std::string>()));
    }
    for (const char* table : {"versus.csv", "versus.md", "versus.json"}) EXPECT_TRUE(fs::exists(mDir / "out" / table));
}

// lodopt's glTF PBR (`--shading pbr`) against three.js at 256x256: mean SSIM >= 0.95 over the
// views of these models, >= 0.90 per model (docs/harness.md has the full table).
TEST_F(Harness, PbrMatchesThreeJs) {
    const NodeRun run = runNode(
        mDir / "err.txt", "versus_threejs.mjs",
        "--data " + quoted(kShared) + " --lodopt " + quoted(LODOPT_EXECUTABLE) + " --out " + quoted(mDir / "out") +
            " --shading pbr --size 256x256 --only BoxTextured/glTF/,MetalRoughSpheresNoTextures/glTF/,"
            "OrientationTest/glTF/,TextureCoordinateTest/glTF/ --json");
    ASSERT_TRUE(run.exitCode == 0 || run.exitCode == 1) << run.err;
    const nlohmann::json result = nlohmann::json::parse(run.out);
    for (const auto& row : result.at("rows")) {
        EXPECT_EQ(row.at("status"), "ok") << row.at("asset").get<std::string>() << " view " << row.at("view");
    }
    ASSERT_EQ(run.exitCode, 0);
    for (const auto& [asset, mean] : result.at("asset_mean_ssim").items()) {
        EXPECT_GE(mean.get<double>(), 0.90) << asset << " (see " << (mDir / "out" / "versus.md") << ")";
    }
    EXPECT_GE(result.at("mean_ssim").get<double>(), 0.95) << "see " << (mDir / "out" / "versus.md");
}

// lodopt's side of the lighting number: its PBR render of the white surface facing the key light
// is the byte three.js writes (242; the glTF Appendix B BRDF gives 0.9495 after tone mapping and
// sRGB, also 242), within one step. Needs no node or Chromium.
TEST(HarnessLighting, PbrWhiteSurfaceFacingTheKeyLightIsThreeJsByte) {
    const fs::path dir = fs::temp_directory_path() / ("lodopt-harness-" + std::to_string(::getpid()) + "-white");
    fs::create_directories(dir);
    const fs::path image = dir / "white.png";
    const auto render = cli_test::runLodopt("render --scene " + quoted(kWhiteSurface) +
                                            " --view 0 --size 16x16 --shading pbr --out " + quoted(image));
    ASSERT_EQ(render.exitCode, 0);
    const renderer::LoadedImage png = renderer::readImage(image.string());
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(pixelAt(png, 8, 8)[k], kWhiteSurfaceByte, 1);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lodopt::harness_test
