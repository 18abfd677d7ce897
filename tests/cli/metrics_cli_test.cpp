// lodopt metrics: exit codes and JSON output on tiny hand-written PPM/PGM images (lodopt
// reads binary PNM, so the test needs no image library).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_lodopt.hpp"
#include "lodopt_test_paths.hpp"

namespace {

using lodopt::cli_test::CommandResult;
using lodopt::cli_test::runLodopt;

class MetricsCli : public ::testing::Test {
protected:
    void SetUp() override {
        mDir = std::filesystem::temp_directory_path() / ("lodopt-metrics-cli-" + std::to_string(::getpid()));
        std::filesystem::create_directories(mDir);
    }
    void TearDown() override { std::filesystem::remove_all(mDir); }

    // Binary PPM (channels 3) or PGM (channels 1); pixel(x, y, c) gives the bytes.
    template <class Pixel>
    std::string write(const std::string& name, int width, int height, int channels, Pixel pixel) {
        const std::filesystem::path path = mDir / name;
        std::ofstream file(path, std::ios::binary);
        file << (channels == 3 ? "P6" : "P5") << "\n" << width << " " << height << "\n255\n";
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                for (int c = 0; c < channels; ++c) file.put(char(pixel(x, y, c)));
            }
        }
        return path.string();
    }

    // Sky (158, 194, 230) with a square "object" whose color depends on `shade`.
    std::string scene(const std::string& name, int size, int shade) {
        return write(name, size, size, 3, [=](int x, int y, int c) {
            const bool object = x >= size / 4 && x < size / 2 && y >= size / 4 && y < (3 * size) / 4;
            const int sky[3] = {158, 194, 230};
            return object ? (40 + 37 * c + shade * ((x + y) % 5)) % 256 : sky[c];
        });
    }

    std::filesystem::path mDir;
};

TEST_F(MetricsCli, JsonReportsEveryComponent) {
    const std::string a = scene("a.ppm", 32, 3), b = scene("b.ppm", 32, 7);
    const CommandResult run = runLodopt("metrics " + a + " " + b + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json result = nlohmann::json::parse(run.output);
    for (const char* key : {"ssim", "boundary_entropy", "information_entropy"}) {
        ASSERT_TRUE(result.contains(key)) << key;
        EXPECT_TRUE(result[key]["computed"].get<bool>());
        for (const char* field : {"candidate", "reference", "fidelity"}) {
            EXPECT_TRUE(result[key][field].is_number()) << key << "." << field;
        }
        EXPECT_GE(result[key]["fidelity"].get<double>(), 0.0);
        EXPECT_LE(result[key]["fidelity"].get<double>(), 1.0);
    }
    EXPECT_LT(result["ssim"]["candidate"].get<double>(), 1.0);
    EXPECT_EQ(result["ssim"]["reference"].get<double>(), 1.0);
    for (const char* key : {"precision", "recall", "fitness"}) {
        ASSERT_TRUE(result[key].is_number()) << key;
        EXPECT_GE(result[key].get<double>(), 0.0);
        EXPECT_LE(result[key].get<double>(), 1.0);
    }
    EXPECT_LT(result["fitness"].get<double>(), 1.0);
    EXPECT_EQ(result["width"], 32);
}

TEST_F(MetricsCli, IdenticalImagesScoreOne) {
    const std::string a = scene("a.ppm", 24, 3);
    const nlohmann::json result = nlohmann::json::parse(runLodopt("metrics " + a + " " + a + " --json").output);
    EXPECT_EQ(result["fitness"].get<double>(), 1.0);
    EXPECT_EQ(result["ssim"]["candidate"].get<double>(), 1.0);
    EXPECT_EQ(result["precision"].get<double>(), 1.0);
}

TEST_F(MetricsCli, WeightsSelectAndSkipComponents) {
    const std::string a = scene("a.ppm", 32, 3), b = scene("b.ppm", 32, 7);
    const CommandResult run = runLodopt("metrics " + a + " " + b + " --weights 1,0,0 --json");
    ASSERT_EQ(run.exitCode, 0);
    const nlohmann::json result = nlohmann::json::parse(run.output);
    EXPECT_FALSE(result["boundary_entropy"]["computed"].get<bool>());
    EXPECT_TRUE(result["boundary_entropy"]["candidate"].is_null());
    EXPECT_EQ(result["fitness"].get<double>(), result["ssim"]["fidelity"].get<double>());
}

TEST_F(MetricsCli, GrayImagesAreUsedAsTheyAre) {
    const std::string a = write("a.pgm", 20, 20, 1, [](int x, int y, int) { return (x * 13 + y * 7) % 256; });
    const std::string b = write("b.pgm", 20, 20, 1, [](int x, int y, int) { return (x * 13 + y * 5) % 256; });
    const CommandResult run = runLodopt("metrics " + a + " " + b + " --json");
    ASSERT_EQ(run.exitCode, 0);
    const nlohmann::json result = nlohmann::json::parse(run.output);
    EXPECT_EQ(result["channels"], 1);
    EXPECT_GT(result["information_entropy"]["candidate"].get<double>(), 0.0);
}

TEST_F(MetricsCli, TextOutputListsTheComponents) {
    const std::string a = scene("a.ppm", 32, 3), b = scene("b.ppm", 32, 7);
    const CommandResult run = runLodopt("metrics " + a + " " + b);
    ASSERT_EQ(run.exitCode, 0);
    const nlohmann::json json = nlohmann::json::parse(runLodopt("metrics " + a + " " + b + " --json").output);
    // Each component's row: its name, then candidate, reference and fidelity as numbers equal to
    // the JSON's (a NaN or a missing value fails here).
    for (const char* word : {"ssim", "boundary_entropy", "information_entropy"}) {
        const std::size_t at = run.output.find(std::string(word) + " ");
        ASSERT_NE(at, std::string::npos) << word;
        std::istringstream row(run.output.substr(at + std::string(word).size()));
        double candidate = 0, reference = 0, fidelity = 0;
        ASSERT_TRUE(row >> candidate >> reference >> fidelity) << word;
        EXPECT_NEAR(fidelity, json[word]["fidelity"].get<double>(), 1e-6) << word;
        EXPECT_NEAR(candidate, json[word]["candidate"].get<double>(), 1e-6) << word;
    }
    for (const char* word : {"precision", "recall", "fitness"}) {
        const std::size_t at = run.output.find(std::string(word) + " ");
        ASSERT_NE(at, std::string::npos) << word;
        double value = -1;
        std::istringstream(run.output.substr(at + std::string(word).size())) >> value;
        EXPECT_NEAR(value, json[word].get<double>(), 1e-6) << word;
    }
    const std::size_t judge = run.output.find("judge: butteraugli 3-norm ");
    ASSERT_NE(judge, std::string::npos) << run.output;
    double distance = -1;
    std::istringstream(run.output.substr(judge + 26)) >> distance;
    EXPECT_NEAR(distance, json["judge"]["butteraugli"].get<double>(), 1e-6);
}

// The judge in process gives what Debian's butteraugli_main prints for the same two files.
TEST_F(MetricsCli, JudgeEqualsButteraugliMain) {
    const std::string reference = scene("reference.ppm", 64, 3), candidate = scene("candidate.ppm", 64, 9);
    const CommandResult run = runLodopt("metrics " + candidate + " " + reference + " --json");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json judge = nlohmann::json::parse(run.output)["judge"];
    EXPECT_EQ(judge["pnorm"], 3.0);
    EXPECT_EQ(judge["intensity_target_nits"], 80.0);
    const CommandResult tool = lodopt::cli_test::runShell("butteraugli_main " + reference + " " + candidate +
                                                          " --pnorm 3 2>/dev/null");
    ASSERT_EQ(tool.exitCode, 0) << "butteraugli_main (libjxl-devtools, the quick start installs it): " << tool.output;
    std::istringstream lines(tool.output);
    double maxDistance = -1, pnorm = -1;
    std::string label;
    ASSERT_TRUE(lines >> maxDistance >> label >> pnorm) << tool.output;
    EXPECT_EQ(label, "3-norm:");
    EXPECT_GT(pnorm, 0.0);
    EXPECT_NEAR(judge["butteraugli"].get<double>(), pnorm, 1e-5 * pnorm);
    EXPECT_NEAR(judge["butteraugli_max"].get<double>(), maxDistance, 1e-5 * maxDistance);
    const nlohmann::json same =
        nlohmann::json::parse(runLodopt("metrics " + reference + " " + reference + " --json").output)["judge"];
    EXPECT_EQ(same["butteraugli"].get<double>(), 0.0);
    const nlohmann::json brighter = nlohmann::json::parse(
        runLodopt("metrics " + candidate + " " + reference + " --judge-nits 250 --json").output)["judge"];
    EXPECT_EQ(brighter["intensity_target_nits"], 250.0);
    EXPECT_NE(brighter["butteraugli"].get<double>(), judge["butteraugli"].get<double>());
}

TEST_F(MetricsCli, BadInputIsExitCode2) {
    const std::string a = scene("a.ppm", 32, 3), small = scene("small.ppm", 31, 3);
    const std::string gray = write("g.pgm", 32, 32, 1, [](int, int, int) { return 9; });
    const std::string garbage = (mDir / "garbage.png").string();
    std::ofstream(garbage) << "not a png";
    EXPECT_EQ(runLodopt("metrics " + a + " " + small).exitCode, 2);                         // size mismatch
    EXPECT_EQ(runLodopt("metrics " + a + " " + gray).exitCode, 2);                          // gray vs color
    EXPECT_EQ(runLodopt("metrics " + a + " " + garbage).exitCode, 2);                       // unreadable
    EXPECT_EQ(runLodopt("metrics " + a + " " + (mDir / "none.png").string()).exitCode, 2);  // missing
    EXPECT_EQ(runLodopt("metrics " + a + " " + a + " --weights 1,1").exitCode, 2);
    EXPECT_EQ(runLodopt("metrics " + a + " " + a + " --weights 0,0,0").exitCode, 2);
    EXPECT_EQ(runLodopt("metrics " + a + " " + a + " --weights 1,-1,1").exitCode, 2);
    EXPECT_EQ(runLodopt("metrics " + a + " " + a + " --weights 1,nan,1").exitCode, 2);
    EXPECT_EQ(runLodopt("metrics " + a + " " + a + " --gray hsv").exitCode, 2);
    EXPECT_EQ(runLodopt("metrics " + a).exitCode, 2);
    for (const char* bad : {"--judge-nits 0", "--judge-nits -5", "--judge-pnorm 0.5", "--judge-display-scale 0",
                            "--judge-display-scale 17"}) {
        const CommandResult run = lodopt::cli_test::runShell(std::string(LODOPT_EXECUTABLE) + " metrics " + a + " " +
                                                             a + " " + bad + " 2>&1");
        EXPECT_EQ(run.exitCode, 2) << bad;
        EXPECT_NE(run.output.find("judge"), std::string::npos) << bad << ": " << run.output;
    }
    // A command that scores no image takes no judge option; one that does refuses a bad one.
    EXPECT_EQ(runLodopt("estimate --scene harbor --view overview --levels 0,0,0 --judge-nits 80").exitCode, 2);
    const CommandResult optimize = lodopt::cli_test::runShell(
        std::string(LODOPT_EXECUTABLE) + " optimize --scene harbor --budget-ms 7 --size 32x32 --judge-nits -3 --out " +
        (mDir / "optimize").string() + " 2>&1");
    EXPECT_EQ(optimize.exitCode, 2) << optimize.output;
    EXPECT_NE(optimize.output.find("judge parameter intensityTargetNits"), std::string::npos) << optimize.output;
    EXPECT_FALSE(std::filesystem::exists(mDir / "optimize" / "result.json"));
}

}  // namespace
