// A sweep's options and its run (command_sweep.cpp), for the commands that sweep on the way to
// their own result (`thresholds --scene S --view-count N` without --from).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "optimize_run.hpp"

namespace lodopt::cli {

struct SweepOptions {
    OptimizeOptions optimize;
    int viewCount = 0;
    std::string path;
    std::string grid;
    std::string gridBox;
    std::string cameras;
    std::uint64_t sampleSeed = 1;
    std::string out = "out/sweep";
    bool resume = false;
    std::string shard;
    std::vector<std::string> merge;
    std::string scaling;  // a finished sweep folder to model the ranks of
    std::string scalingRanks = "1,2,4,8,16,32,64";
    long scalingViews = 0;  // 0: the folder's view count
    bool printSummary = true;  // false: a command sweeping on the way prints its own result only
};

// The camera sources (--grid, --grid-box, --path, --view-count, --sample-seed, --cameras) and the
// search options, --budget-ms not required (the caller checks it where it is needed).
void addSweepSources(CLI::App& command, SweepOptions& options);

// `lodopt sweep` with these options (under mpirun too).
void runSweepCommand(const SweepOptions& options, const OutputOptions& output);

}  // namespace lodopt::cli
