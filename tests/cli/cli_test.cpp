// The lodopt executable: exit codes, JSON output, files written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "run_lodopt.hpp"

namespace {

using lodopt::cli_test::CommandResult;
using lodopt::cli_test::runLodopt;

std::filesystem::path tempDir(const std::string& name) {
    auto dir = std::filesystem::temp_directory_path() / ("lodopt-cli-" + name + "-" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace

TEST(CliScene, InfoJsonListsObjectsLevelsAndViews) {
    CommandResult result = runLodopt("scene info harbor --json");
    ASSERT_EQ(result.exitCode, 0);
    nlohmann::json info = nlohmann::json::parse(result.output);
    ASSERT_EQ(info["objects"].size(), 3u);
    EXPECT_EQ(info["objects"][1]["name"], "ship");
    EXPECT_EQ(info["objects"][1]["levels"].size(), 5u);
    EXPECT_GT(info["objects"][1]["levels"][0]["triangles"].get<int>(), 0);
    EXPECT_GE(info["views"].size(), 3u);
}

TEST(CliScene, UnknownSceneIsBadInput) {
    EXPECT_EQ(runLodopt("scene info atlantis").exitCode, 2);
    EXPECT_EQ(runLodopt("scene info /nonexistent/model.gltf").exitCode, 2);
    EXPECT_EQ(runLodopt("scene export harbor /tmp/x.obj").exitCode, 2);
}

// `scene export` then `scene info` of the file: the same objects, levels, per-level statistics,
// views and camera paths as `scene info` of the built-in scene, for every built-in scene.
class CliSceneRoundTrip : public testing::TestWithParam<const char*> {};

TEST_P(CliSceneRoundTrip, ExportThenInfoGivesTheSameStatistics) {
    const std::string scene = GetParam();
    auto dir = tempDir("export-" + scene);
    const std::string path = (dir / (scene + ".glb")).string();
    ASSERT_EQ(runLodopt("scene export " + scene + " " + path).exitCode, 0);
    ASSERT_TRUE(std::filesystem::exists(path));
    const CommandResult before = runLodopt("scene info " + scene + " --json");
    const CommandResult after = runLodopt("scene info " + path + " --json");
    ASSERT_EQ(before.exitCode, 0);
    ASSERT_EQ(after.exitCode, 0);
    nlohmann::json original = nlohmann::json::parse(before.output);
    nlohmann::json reloaded = nlohmann::json::parse(after.output);
    ASSERT_GT(original["objects"].size(), 0u);
    ASSERT_EQ(original["objects"].size(), reloaded["objects"].size());
    int mismatches = 0;
    for (std::size_t o = 0; o < original["objects"].size() && mismatches < 20; ++o) {
        const auto& a = original["objects"][o];
        const auto& b = reloaded["objects"][o];
        EXPECT_EQ(a["name"], b["name"]);
        ASSERT_EQ(a["levels"].size(), b["levels"].size()) << a["name"];
        for (std::size_t l = 0; l < a["levels"].size(); ++l) {
            for (const char* key : {"vertices", "triangles", "texture_bytes", "draw_calls"}) {
                if (a["levels"][l][key] != b["levels"][l][key]) {
                    ++mismatches;
                    ADD_FAILURE() << a["name"] << " level " << l << " " << key << ": " << a["levels"][l][key] << " became "
                                  << b["levels"][l][key];
                }
            }
        }
    }
    ASSERT_EQ(original["views"].size(), reloaded["views"].size());
    for (std::size_t v = 0; v < original["views"].size(); ++v) {
        EXPECT_EQ(original["views"][v]["name"], reloaded["views"][v]["name"]);
    }
    ASSERT_EQ(original["paths"].size(), reloaded["paths"].size());
    for (std::size_t p = 0; p < original["paths"].size(); ++p) {
        EXPECT_EQ(original["paths"][p], reloaded["paths"][p]) << "path " << p;
    }
    EXPECT_EQ(original["materials"], reloaded["materials"]);
    EXPECT_EQ(original["textures"], reloaded["textures"]);
    std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(BuiltInScenes, CliSceneRoundTrip, testing::Values("harbor", "forest", "city"));

TEST(CliRender, WritesPngAndReportsTime) {
    auto dir = tempDir("render");
    const std::string out = (dir / "coarse.png").string();
    CommandResult result =
        runLodopt("render --scene harbor --view ship_close --levels 5,4,4 --size 128x96 --time --repeats 2 --out " +
                  out + " --depth-out " + (dir / "depth.exr").string() + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    nlohmann::json json = nlohmann::json::parse(result.output);
    EXPECT_GT(json["render_ms"].get<double>(), 0.0);
    EXPECT_EQ(json["width"], 128);
    EXPECT_EQ(json["height"], 96);
    EXPECT_EQ(json["levels"], nlohmann::json({5, 4, 4}));
    EXPECT_TRUE(std::filesystem::exists(out));
    EXPECT_TRUE(std::filesystem::exists(dir / "depth.exr"));
    EXPECT_EQ(json["backend"], "osmesa");
    // The EGL backend (headless, here Mesa's llvmpipe again): the same image file.
    const std::string eglOut = (dir / "coarse_egl.png").string();
    result = runLodopt("render --scene harbor --view ship_close --levels 5,4,4 --size 128x96 --backend egl --time "
                       "--repeats 2 --out " + eglOut + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.output;
    json = nlohmann::json::parse(result.output);
    EXPECT_EQ(json["backend"], "egl");
    EXPECT_EQ(json["platform"].get<std::string>().rfind("EGL ", 0), 0u) << json["platform"];
    EXPECT_GT(json["render_ms"].get<double>(), 0.0);
    if (json["renderer"].get<std::string>().find("llvmpipe") != std::string::npos) {
        std::ifstream a(out, std::ios::binary), b(eglOut, std::ios::binary);
        const std::string bytesA((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
        const std::string bytesB((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
        EXPECT_EQ(bytesA, bytesB);
    }
    std::filesystem::remove_all(dir);
}

TEST(CliRender, BadArgumentsExitWithTwoAndWriteNothing) {
    auto dir = tempDir("render-bad");
    const std::string out = (dir / "x.png").string();
    EXPECT_EQ(runLodopt("render --levels 0,9,0 --out " + out).exitCode, 2);
    EXPECT_EQ(runLodopt("render --levels 0,0 --out " + out).exitCode, 2);
    EXPECT_EQ(runLodopt("render --backend vulkan --out " + out).exitCode, 2);
    EXPECT_EQ(runLodopt("render --levels a,b,c --out " + out).exitCode, 2);
    EXPECT_EQ(runLodopt("render --view nowhere --out " + out).exitCode, 2);
    EXPECT_EQ(runLodopt("render --size 0x10 --out " + out).exitCode, 2);
    // Output types lodopt cannot write: refused before anything is rendered or written.
    const std::string tif = (dir / "x.tif").string();
    EXPECT_EQ(runLodopt("render --size 32x32 --out " + tif).exitCode, 2);
    EXPECT_EQ(runLodopt("render --size 32x32 --out " + out + " --depth-out " + (dir / "d.png").string()).exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(tif));
    EXPECT_EQ(runLodopt("render --no-such-flag").exitCode, 2);
    EXPECT_EQ(runLodopt("").exitCode, 2);
    EXPECT_FALSE(std::filesystem::exists(out));
    std::filesystem::remove_all(dir);
}
