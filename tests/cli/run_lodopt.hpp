// The lodopt executable run through the shell, for the CLI tests that need its exit status and
// stdout only (child_process.hpp runs it as a child process for the tests that signal it).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>
#include "lodopt_test_paths.hpp"

namespace lodopt::cli_test {

struct CommandResult {
    int exitCode = -1;   // -1 when it did not exit normally
    std::string output;  // stdout only
};

// Runs `command` with /bin/sh and collects its stdout.
inline CommandResult runShell(const std::string& command) {
    CommandResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

// `lodopt ARGUMENTS` with stderr discarded; `environment` ("LODOPT_GNUPLOT=none") goes before it.
inline CommandResult runLodopt(const std::string& arguments, const std::string& environment = "") {
    return runShell((environment.empty() ? "" : environment + " ") + std::string(LODOPT_EXECUTABLE) + " " + arguments +
                    " 2>/dev/null");
}

}  // namespace lodopt::cli_test
