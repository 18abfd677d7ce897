// lodopt thresholds: per-object switch thresholds from a sweep, written for the engines, and the
// exported file read back by lodopt itself.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "child_process.hpp"
#include "run_lodopt.hpp"

namespace lodopt::cli_test {
namespace {

namespace fs = std::filesystem;

struct Folder {
    fs::path root = fs::temp_directory_path() / ("lodopt_thresholds_" + std::to_string(::getpid()) + "_" +
                                                 ::testing::UnitTest::GetInstance()->current_test_info()->name());
    Folder() {
        fs::remove_all(root);
        fs::create_directories(root);
    }
    ~Folder() { fs::remove_all(root); }
    std::string operator/(const std::string& name) const { return (root / name).string(); }
};

TEST(ThresholdsCli, FromASweepWritesEngineFilesThatLodoptReadsBack) {
    Folder folder;
    // Views sampled around the harbor's own: the ship and the aircraft are searched in most.
    ASSERT_EQ(runLodopt("sweep --scene harbor --view-count 12 --size 64x64 --budget-ms 1.0 --max-evals 60 --threads 1 "
                        "--quiet --out " + (folder / "sweep"))
                  .exitCode,
              0);
    const CommandResult run =
        runLodopt("thresholds --from " + (folder / "sweep") + " --out " + (folder / "out") + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json summary = nlohmann::json::parse(run.output);
    EXPECT_GE(summary["fitted_objects"].get<int>(), 1);
    EXPECT_EQ(summary["holdout_every"], 4);
    EXPECT_EQ(summary["pricing"], "measured");
    // The tuned rule and the defaults (the built-in harbor has no thresholds of its own), each
    // with its bias, on the held-out views.
    std::vector<std::string> rules;
    for (const nlohmann::json& row : summary["held_out"]) {
        rules.push_back(row["rule"].get<std::string>());
        for (const char* key : {"mean_fitness", "over_budget_share", "lod_bias", "mean_predicted_ms"}) {
            EXPECT_TRUE(row[key].is_number()) << row["rule"] << " " << key;
        }
        // Null only when no held-out view has a gain to share out.
        EXPECT_EQ(row["gain_fraction"].is_number(), summary["held_out_reference"]["gain_views"].get<int>() > 0);
        EXPECT_GT(row["lod_bias"].get<double>(), 0.0);
        EXPECT_GT(row["mean_fitness"].get<double>(), 0.0);
        EXPECT_LE(row["mean_fitness"].get<double>(), 1.0);
        const double share = row["over_budget_share"].get<double>();
        EXPECT_TRUE(share >= 0.0 && share <= 1.0) << share;
    }
    EXPECT_EQ(rules, (std::vector<std::string>{"tuned", "msft_default", "unitygltf_halving", "unreal_075",
                                               "pixelerror", "unreal_auto"}));
    const double bias = summary["lod_bias"]["lod_bias"].get<double>();
    EXPECT_EQ(summary["held_out"][0]["lod_bias"].get<double>(), bias);
    if (summary["lod_bias"]["meets_budget"].get<bool>()) {
        EXPECT_LE(summary["lod_bias"]["fitting_mean_predicted_ms"].get<double>(), 1.0);
    }
    const nlohmann::json document = readJson(folder / "out/thresholds.json");
    EXPECT_EQ(document["format"], "lodopt-thresholds");
    ASSERT_EQ(document["objects"].size(), 3u);
    for (const nlohmann::json& object : document["objects"]) {
        const auto sizes = object["screen_size"].get<std::vector<double>>();
        // The bias is baked in: screen_size = fitted_screen_size / lod_bias.
        const auto fitted = object["fitted_screen_size"].get<std::vector<double>>();
        ASSERT_EQ(fitted.size(), sizes.size());
        for (std::size_t k = 0; k < sizes.size(); ++k) {
            EXPECT_NEAR(sizes[k] * bias / fitted[k], 1.0, 1e-12);
        }
        ASSERT_EQ(int(sizes.size()), object["levels"].get<int>() - 1) << object["name"];
        EXPECT_TRUE(std::is_sorted(sizes.rbegin(), sizes.rend())) << object["name"];
        const auto unity = object["unity_relative_height"].get<std::vector<double>>();
        const auto distance = object["threejs_distance"].get<std::vector<double>>();
        for (std::size_t k = 0; k < sizes.size(); ++k) {
            EXPECT_LE(unity[k], sizes[k] * (1.0 + 1e-12));  // largest extent <= diameter
            EXPECT_GT(distance[k], 0.0);
            if (k > 0) {
                EXPECT_GE(distance[k], distance[k - 1]);  // coarser levels from farther away
            }
        }
    }
    // lodopt reads the exported file's thresholds back as the same screen sizes (floats).
    const std::string glb = folder / "out/harbor.lod.glb";
    const CommandResult info = runLodopt("scene info " + glb + " --json");
    ASSERT_EQ(info.exitCode, 0);
    const nlohmann::json scene = nlohmann::json::parse(info.output);
    for (std::size_t i = 0; i < scene["objects"].size(); ++i) {
        const auto sizes = document["objects"][i]["screen_size"].get<std::vector<double>>();
        const nlohmann::json& levels = scene["objects"][i]["levels"];
        for (std::size_t k = 0; k < sizes.size(); ++k) {
            EXPECT_NEAR(levels[k]["screen_coverage"].get<double>() / sizes[k], 1.0, 1e-5) << i << " " << k;
        }
        EXPECT_EQ(levels[sizes.size()]["screen_coverage"].get<double>(), 0.0);  // the coarsest is never culled
    }
    // The engine baseline runs on them.
    EXPECT_EQ(runLodopt("optimize --scene " + glb + " --view overview --algo screensize --budget-ms 7 --size 64x64 "
                        "--quiet --out " + (folder / "optimize"))
                  .exitCode,
              0);
    // Without --from, thresholds sweeps the same views itself (into <out>/sweep): the same fit.
    const CommandResult sampled = runLodopt("thresholds --scene harbor --view-count 12 --size 64x64 --budget-ms 1.0 "
                                            "--max-evals 60 --threads 1 --quiet --out " + (folder / "sampled"));
    ASSERT_EQ(sampled.exitCode, 0) << sampled.output;
    EXPECT_TRUE(fs::exists(folder / "sampled/sweep/sweep.json"));
    EXPECT_EQ(readJson(folder / "sampled/thresholds.json")["objects"], document["objects"]);
    // The report draws the rules' table and, per object, the choices with the switch points; the
    // plot's data are the sweep's choices of that object.
    const std::string html = folder / "report.html";
    ASSERT_EQ(runLodopt("report " + (folder / "out/thresholds.json") + " --out " + html).exitCode, 0);
    std::ifstream htmlStream(html);
    const std::string page((std::istreambuf_iterator<char>(htmlStream)), std::istreambuf_iterator<char>());
    EXPECT_NE(page.find("thresholds: harbor"), std::string::npos);
    EXPECT_NE(page.find("unitygltf_halving"), std::string::npos);
    EXPECT_NE(page.find("the exported switch points"), std::string::npos);
    int plotted = 0;
    for (const auto& entry : fs::directory_iterator(folder / "report_files")) {
        const std::string name = entry.path().filename().string();
        if (name.find("_fit.dat") == std::string::npos) continue;
        std::ifstream data(entry.path());
        std::string line;
        while (std::getline(data, line)) plotted += line.empty() || line[0] == '#' ? 0 : 1;
    }
    EXPECT_GT(plotted, 0);
    // A sweep of the exported file: its own thresholds are the "file" rule of the comparison.
    ASSERT_EQ(runLodopt("sweep --scene " + glb + " --view-count 12 --size 64x64 --budget-ms 1.0 --max-evals 60 "
                        "--threads 1 --quiet --out " + (folder / "sweep_glb"))
                  .exitCode,
              0);
    const CommandResult again =
        runLodopt("thresholds --from " + (folder / "sweep_glb") + " --out " + (folder / "out_glb") + " --json");
    ASSERT_EQ(again.exitCode, 0) << again.output;
    const nlohmann::json rows = nlohmann::json::parse(again.output)["held_out"];
    ASSERT_EQ(rows.size(), 7u);  // tuned, file, the three lists, the two geometric-error rules
    EXPECT_EQ(rows[1]["rule"], "file");
}

TEST(ThresholdsCli, BadInputIsRefusedWithExitCode2) {
    Folder folder;
    EXPECT_EQ(runLodopt("thresholds --from " + (folder / "missing") + " --out " + (folder / "out")).exitCode, 2);
    // A sweep source and --from, neither, or a sweep without a budget.
    EXPECT_EQ(runLodopt("thresholds --from " + (folder / "missing") + " --scene harbor --view-count 2 --budget-ms 1 "
                        "--out " + (folder / "out")).exitCode,
              2);
    EXPECT_EQ(runLodopt("thresholds --out " + (folder / "out")).exitCode, 2);
    EXPECT_EQ(runLodopt("thresholds --scene harbor --view-count 2 --out " + (folder / "out")).exitCode, 2);
    EXPECT_FALSE(fs::exists(folder / "out"));
    // Cameras with two fields of view: the distance conventions need --fov.
    std::ofstream(folder / "cameras.json")
        << R"([{"position": [0, 3, 30], "target": [0, 0, 0], "fov_y_degrees": 40},)"
        << R"( {"position": [20, 5, 20], "target": [0, 0, 0], "fov_y_degrees": 60}])";
    ASSERT_EQ(runLodopt("sweep --scene harbor --cameras " + (folder / "cameras.json") +
                        " --size 64x64 --budget-ms 1.0 --max-evals 30 --quiet --out " + (folder / "sweep"))
                  .exitCode,
              0);
    const Exit mixed = runLodoptChild(splitWords("thresholds --from " + (folder / "sweep") + " --out " + (folder / "o")),
                                      "/dev/null", folder / "err.txt");
    EXPECT_EQ(mixed.code, 2);
    EXPECT_NE(mixed.err.find("--fov"), std::string::npos) << mixed.err;
    EXPECT_FALSE(fs::exists(folder / "o/thresholds.json"));
    EXPECT_EQ(runLodopt("thresholds --from " + (folder / "sweep") + " --fov 50 --out " + (folder / "o")).exitCode, 0);
}

}  // namespace
}  // namespace lodopt::cli_test
