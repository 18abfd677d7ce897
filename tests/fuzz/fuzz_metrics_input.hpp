// The `lodopt metrics A B` input path for fuzzing: image files (PNG, JPEG, PNM), channel and
// size matching, then every metric. Shared by tests/fuzz/fuzz_metrics_input.cpp (libFuzzer)
// and the corpus replay in tests/cli/robustness_test.cpp.
//
// Input layout (so that the fuzzer can build two images of the same size):
//   byte 0        option bits: 1 --gray bt601, 2 --boundary-entropy paper,
//                 4 --information-entropy paper, 8 --weights 1,0,1; bits 4-5 pick the file
//                 extension (.png, .jpg, .tga, .ppm); the reader goes by the bytes
//   bytes 1-4     n, little-endian: the size of image A (clamped to what is left)
//   n bytes       image A (the candidate)
//   the rest      image B (the reference); when empty, A is compared with itself
#pragma once

#include <CLI/CLI.hpp>

#include <iostream>

#include "cli_common.hpp"
#include "fuzz_inputs.hpp"

namespace lodopt::fuzz {

inline void runMetricsInput(const std::uint8_t* data, std::size_t size) {
    if (size < 5) return;
    const std::uint8_t flags = data[0];
    std::uint32_t lengthA = 0;
    std::memcpy(&lengthA, data + 1, 4);
    const std::size_t available = size - 5;
    const std::size_t sizeA = std::min<std::size_t>(lengthA, available);
    static const char* const kExtensions[4] = {".png", ".jpg", ".tga", ".ppm"};
    const std::string extension = kExtensions[(flags >> 4) & 3];
    const std::string pathA = writeScratch("candidate" + extension, data + 5, sizeA);
    const std::string pathB =
        sizeA == available ? pathA : writeScratch("reference" + extension, data + 5 + sizeA, available - sizeA);

    std::vector<std::string> arguments = {"lodopt", "metrics", pathA, pathB, "--json"};
    if (flags & 1) arguments.insert(arguments.end(), {"--gray", "bt601"});
    if (flags & 2) arguments.insert(arguments.end(), {"--boundary-entropy", "paper"});
    if (flags & 4) arguments.insert(arguments.end(), {"--information-entropy", "paper"});
    if (flags & 8) arguments.insert(arguments.end(), {"--weights", "1,0,1"});
    std::vector<char*> argv;
    for (std::string& argument : arguments) argv.push_back(argument.data());

    CLI::App app{"lodopt", "lodopt"};
    app.require_subcommand(1);
    cli::addMetricsCommand(app);
    // The JSON result is of no interest here; a stream in a failed state discards it cheaply.
    struct SilentStdout {
        std::ios::iostate state = std::cout.rdstate();
        SilentStdout() { std::cout.setstate(std::ios::badbit); }
        ~SilentStdout() { std::cout.clear(state); }
    } silent;
    try {
        app.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const cli::UsageError&) {
        // the documented refusal: exit code 2 with a message naming the file
    }
}

}  // namespace lodopt::fuzz
