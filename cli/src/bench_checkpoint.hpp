// The checkpoint of `lodopt bench`: <out>/bench.checkpoint.json holds every finished unit of
// an interrupted bench (docs/robustness.md, "Interrupts and --resume"). The units are each grid
// run (algorithm, evaluation budget, seed), then the best-known search, the evaluation paths,
// the metrics timing and the time-model check, in that order. Doubles round-trip exactly
// through the JSON (NaN is written as null and read back as NaN).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bench_run.hpp"

namespace lodopt::cli {

inline constexpr const char* kBenchCheckpoint = "bench.checkpoint.json";

struct TimeModelSection {
    std::vector<TimeModelRow> rows;
    std::vector<std::string> warnings;  // the profile's mismatch sentences
};

struct BenchCheckpoint {
    std::vector<AlgorithmRun> runs;      // finished grid runs, in the order they finished
    std::optional<BestKnown> bestKnown;  // searchBestKnown's answer, before applyBestKnown
    std::optional<std::vector<EvalPathRow>> evalPaths;
    std::optional<std::vector<MetricsRow>> metrics;
    std::optional<TimeModelSection> timeModels;
};

// The checkpoint at `path`, written with the options `identity` (option name without "--" →
// value). Throws UsageError naming the first option whose value differs, or saying that the
// file is not a readable bench checkpoint.
BenchCheckpoint loadBenchCheckpoint(const std::string& path, const nlohmann::json& identity);

// Writes `checkpoint` atomically to `path`.
void saveBenchCheckpoint(const std::string& path, const nlohmann::json& identity, const BenchCheckpoint& checkpoint);

}  // namespace lodopt::cli
