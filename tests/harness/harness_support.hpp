// What the harness tests share (harness_test.cpp, lod_threejs_test.cpp): the harness folder,
// a path quoted for /bin/sh, what is missing to run node and Chromium (the tests FAIL, never
// skip, without them: scripts/quickstart.sh installs them), and a node script run with its
// stdout and stderr kept apart.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "../cli/child_process.hpp"
#include "../cli/run_lodopt.hpp"
#include "lodopt_test_paths.hpp"

namespace lodopt::harness_test {

inline const std::filesystem::path kHarness = std::filesystem::path(LODOPT_SOURCE_DIR) / "tests" / "harness";

// `path` in single quotes for /bin/sh (the paths here hold no quote).
inline std::string quoted(const std::filesystem::path& path) {
    std::string text = path.string();
    text.insert(text.begin(), '\'');
    text.push_back('\'');
    return text;
}

// What is missing to run the harnesses, with what installs it; empty when nothing is.
inline std::string missingTools() {
    using cli_test::runShell;
    std::string missing;
    if (runShell("command -v node >/dev/null 2>&1").exitCode != 0) {
        missing += "node is not on the PATH (apt-get install nodejs npm, or scripts/quickstart.sh); ";
    }
    for (const char* package : {"three", "gltf-validator", "gltfpack", "@gltf-transform/cli"}) {
        if (!std::filesystem::exists(kHarness / "node_modules" / package / "package.json")) {
            missing += std::string("npm package ") + package +
                       " is not installed (npm ci --prefix tests/harness, or scripts/quickstart.sh); ";
        }
    }
    const char* chromium = std::getenv("LODOPT_CHROMIUM");
    const std::string probe = chromium
                                  ? "test -x " + quoted(chromium)
                                  : "command -v chromium || command -v chromium-browser || command -v google-chrome";
    if (runShell(probe + " >/dev/null 2>&1").exitCode != 0) {
        missing +=
            "Chromium is not installed (apt-get install chromium, or scripts/quickstart.sh; or set LODOPT_CHROMIUM); ";
    }
    return missing;
}

struct NodeRun {
    int exitCode = -1;
    std::string out, err;
    double seconds = 0.0;
};

// `node tests/harness/SCRIPT ARGUMENTS`, stdout and stderr kept apart.
inline NodeRun runNode(const std::filesystem::path& errFile, const std::string& script, const std::string& arguments) {
    const auto start = std::chrono::steady_clock::now();
    const auto result =
        cli_test::runShell("CI=1 node " + quoted(kHarness / script) + " " + arguments + " 2>" + quoted(errFile));
    NodeRun run;
    run.exitCode = result.exitCode;
    run.out = result.output;
    run.err = cli_test::slurp(errFile);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return run;
}

// A test that needs the harness tools (failing, never skipping, without them) and a fresh
// temporary folder, kept when the test fails.
class HarnessFolderTest : public testing::Test {
protected:
    void SetUp() override {
        const std::string missing = missingTools();
        ASSERT_TRUE(missing.empty()) << "the harness cannot run: " << missing;
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        mDir = std::filesystem::temp_directory_path() /
               ("lodopt-harness-" + std::to_string(::getpid()) + "-" + info->name());
        std::filesystem::remove_all(mDir);
        std::filesystem::create_directories(mDir);
    }
    void TearDown() override {
        if (!mDir.empty() && !HasFailure()) std::filesystem::remove_all(mDir);
    }
    std::filesystem::path mDir;
};

}  // namespace lodopt::harness_test
