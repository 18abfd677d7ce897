// The README's first quick-start command ends in the main job: `scripts/quickstart.sh run`'s
// optimize line, run here as written (with its output folder), must succeed on the default scene.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "child_process.hpp"
#include "run_lodopt.hpp"
#include "lodopt_test_paths.hpp"

namespace lodopt::cli_test {
namespace {

TEST(QuickStart, MainJobRuns) {
    std::ifstream script(std::filesystem::path(LODOPT_SOURCE_DIR) / "scripts" / "quickstart.sh");
    std::string arguments;
    for (std::string line; std::getline(script, line);) {
        const std::string marker = "/cli/lodopt optimize ";
        const std::size_t at = line.find(marker);
        if (at != std::string::npos) arguments = line.substr(at + marker.size() - std::string("optimize ").size());
    }
    ASSERT_FALSE(arguments.empty()) << "no 'cli/lodopt optimize' line in scripts/quickstart.sh";
    const std::filesystem::path out =
        std::filesystem::temp_directory_path() / ("lodopt_quickstart_" + std::to_string(::getpid()));
    const std::size_t variable = arguments.find("\"$out\"");
    ASSERT_NE(variable, std::string::npos) << arguments;
    arguments.replace(variable, 6, out.string());
    const CommandResult run = runLodopt(arguments + " --quiet");
    EXPECT_EQ(run.exitCode, 0) << "lodopt " << arguments;
    EXPECT_TRUE(std::filesystem::exists(out / "result.json"));
    EXPECT_TRUE(std::filesystem::exists(out / "optimized.png"));
    std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace lodopt::cli_test
