// The installed package: `cmake --install` of this build into a scratch prefix, then a project
// outside the tree (tests/package/consumer) configured with find_package(lodopt) and built
// against it. Its frame loop must decide exactly what the same source built in the tree decides.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../cli/run_lodopt.hpp"
#include "scheduler/coefficients.hpp"
#include "lodopt_test_paths.hpp"

namespace lodopt {
namespace {

namespace fs = std::filesystem;
using cli_test::runShell;

// Appended rather than `"'" + ...`: GCC 12's -Wrestrict misfires on a literal-first chain.
std::string quoted(const fs::path& path) {
    std::string text = "'";
    text += path.string();
    text += "'";
    return text;
}

std::string readFile(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

class InstalledPackage : public testing::Test {
protected:
    static void SetUpTestSuite() {
        // Per process: CTest runs this suite's tests as separate processes, possibly at once.
        scratch = fs::path(LODOPT_BINARY_DIR) / ("package_test_" + std::to_string(getpid()));
        fs::remove_all(scratch);
        fs::create_directories(scratch);
        prefix = scratch / "prefix";
        installLog = runShell(std::string(LODOPT_CMAKE_COMMAND) + " --install " + quoted(LODOPT_BINARY_DIR) +
                              " --prefix " + quoted(prefix) + " 2>&1");
    }
    static void TearDownTestSuite() { fs::remove_all(scratch); }

    static inline fs::path scratch;
    static inline fs::path prefix;
    static inline cli_test::CommandResult installLog;
};

TEST_F(InstalledPackage, InstallsProgramLibrariesHeadersAndPackage) {
    ASSERT_EQ(installLog.exitCode, 0) << installLog.output;
    EXPECT_TRUE(fs::exists(prefix / "bin" / "lodopt"));
    for (const char* module : {"scenes", "renderer", "metrics", "timemodel", "optimizer", "evaluation", "scheduler"}) {
        bool found = false;
        for (const auto& entry : fs::recursive_directory_iterator(prefix)) {
            found = found || entry.path().filename() == std::string("liblodopt_") + module + ".a";
        }
        EXPECT_TRUE(found) << module;
    }
    EXPECT_TRUE(fs::exists(prefix / "include" / "scheduler" / "scheduler.hpp"));
    EXPECT_TRUE(fs::exists(prefix / "include" / "optimizer" / "problem.hpp"));
    // Nothing private: the CLI's library, module sources.
    EXPECT_FALSE(fs::exists(prefix / "include" / "cli_common.hpp"));
    bool packageFound = false;
    for (const auto& entry : fs::recursive_directory_iterator(prefix)) {
        if (entry.path().filename() != "lodoptTargets.cmake") continue;
        packageFound = true;
        // The exported targets point into the prefix, never back into the source tree.
        EXPECT_EQ(readFile(entry.path()).find(LODOPT_SOURCE_DIR), std::string::npos);
    }
    EXPECT_TRUE(packageFound);

    const cli_test::CommandResult version = runShell(quoted(prefix / "bin" / "lodopt") + " --version 2>&1");
    EXPECT_EQ(version.exitCode, 0) << version.output;
    EXPECT_NE(version.output.find("0.1.0"), std::string::npos) << version.output;
}

TEST_F(InstalledPackage, ConsumerBuiltAgainstItSchedulesLikeTheTree) {
    ASSERT_EQ(installLog.exitCode, 0) << installLog.output;
    const fs::path build = scratch / "consumer";
    const std::string cmake = LODOPT_CMAKE_COMMAND;
    const cli_test::CommandResult configure =
        runShell(cmake + " -S " + quoted(fs::path(LODOPT_SOURCE_DIR) / "tests/package/consumer") + " -B " +
                 quoted(build) + " -G " + quoted(LODOPT_CMAKE_GENERATOR) + " -DCMAKE_BUILD_TYPE=Release" +
                 " -DCMAKE_CXX_COMPILER=" + quoted(LODOPT_CXX_COMPILER) + " -DCMAKE_PREFIX_PATH=" + quoted(prefix) +
                 " 2>&1");
    ASSERT_EQ(configure.exitCode, 0) << configure.output;
    const cli_test::CommandResult compile = runShell(cmake + " --build " + quoted(build) + " 2>&1");
    ASSERT_EQ(compile.exitCode, 0) << compile.output;

    // Coefficients other than the defaults, so that reading the file shows in the decisions.
    scheduler::SchedulerCoefficients coefficients;
    coefficients.importance = {0.2, 0.8, 0.0, 0.0};
    coefficients.benchmark.scale = 2.0;
    coefficients.thresholds = scheduler::DistanceThresholds::geometric(3.0, 2.5, 4);
    const fs::path coefficientsFile = scratch / "coefficients.json";
    std::ofstream(coefficientsFile) << scheduler::coefficientsToJson(coefficients);

    std::string arguments = " ";
    arguments += coefficientsFile.string();
    arguments += " 30 40";
    const cli_test::CommandResult installed = runShell(quoted(build / "frame_loop") + arguments);
    const cli_test::CommandResult inTree = runShell(quoted(LODOPT_FRAME_LOOP) + arguments);
    ASSERT_EQ(installed.exitCode, 0) << installed.output;
    ASSERT_EQ(inTree.exitCode, 0) << inTree.output;
    EXPECT_EQ(installed.output, inTree.output);

    // The program that links every exported library runs: it draws, judges and scores the harbor.
    const cli_test::CommandResult every = runShell(quoted(build / "every_library") + " 2>&1");
    ASSERT_EQ(every.exitCode, 0) << every.output;
    EXPECT_NE(every.output.find("objects 3 judge "), std::string::npos) << every.output;

    // Forty frames, one line each; the feedback moved off 1 (drawing takes 10% longer).
    std::istringstream lines(installed.output);
    std::string line;
    int frames = 0;
    double lastScale = 1.0;
    while (std::getline(lines, line)) {
        std::istringstream fields(line);
        int frame = -1, met = -1;
        double predicted = 0.0;
        fields >> frame >> predicted >> met >> lastScale;
        EXPECT_EQ(frame, frames);
        EXPECT_GT(predicted, 0.0);
        if (met == 1) {
            EXPECT_LE(predicted, 30.0);
        }
        ++frames;
    }
    EXPECT_EQ(frames, 40);
    EXPECT_GT(lastScale, 1.0);

    // A coefficients file it cannot use: exit code 1 and a message naming the file.
    const fs::path bad = scratch / "bad.json";
    std::ofstream(bad) << "{\"format\": \"lodopt-scheduler-coefficients\"}";
    const cli_test::CommandResult refused = runShell(quoted(build / "frame_loop") + " " + quoted(bad) + " 30 1 2>&1");
    EXPECT_EQ(refused.exitCode, 1);
    EXPECT_NE(refused.output.find("bad.json"), std::string::npos) << refused.output;
}

}  // namespace
}  // namespace lodopt
