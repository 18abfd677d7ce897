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

#include "evaluation/benchmark.hpp"

namespace lodopt::cli {

inline constexpr const char* kBenchCheckpoint = "bench.checkpoint.json";

struct TimeModelSection {
    std::vector<evaluation::TimeModelRow> rows;
    std::vector<std::string> warnings;  // the profile's mismatch sentences
};

struct BenchCheckpoint {
    std::vector<evaluation::AlgorithmRun> runs;  // finished grid runs, in the order they finished
    std::optional<evaluation::BestKnown>
        bestKnown;  // evaluation::searchBestKnown's answer, before evaluation::applyBestKnown
    std::optional<std::vector<evaluation::EvalPathRow>> evalPaths;
    std::optional<std::vector<evaluation::MetricsRow>> metrics;
    std::optional<TimeModelSection> timeModels;
};

// One grid run as the checkpoint saves it and bench.json's "runs" lists it (with its
// improvement curve; NaN as null).
nlohmann::json runToJson(const evaluation::AlgorithmRun& run);

// The units of a bench checkpoint (CheckpointFile "bench", units "units").
BenchCheckpoint benchFromCheckpoint(const nlohmann::json& saved);
// Its units as the checkpoint's members, for CheckpointFile::save.
nlohmann::json benchToCheckpoint(const BenchCheckpoint& checkpoint);

}  // namespace lodopt::cli
