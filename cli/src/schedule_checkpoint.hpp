// Checkpoint of `lodopt schedule` (docs/robustness.md, "Interrupts and --resume"): after each
// batch of frames, <out>/schedule.checkpoint.json holds what cannot be recomputed cheaply or at
// all (wall times, measured times, fitness) for every finished frame. --resume replays the
// saved frames' decisions without rendering and feeds the saved measured times back, so the
// scheduler's switch-control state and the time model's feedback scale are exactly those of
// the interrupted run; the saved predicted time, levels and feedback scale of each frame check
// that the replay agrees, frame by frame.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "evaluation/schedule_walk.hpp"

namespace lodopt::cli {

// The frames saved by an interrupted schedule whose options equal `identity` (keyed by option
// name). Throws UsageError naming the option that differs, or saying that the file is unreadable.
std::vector<evaluation::RecordedFrame> loadScheduleCheckpoint(const std::string& path, const nlohmann::json& identity);
// Writes `frames` with `identity` atomically.
void saveScheduleCheckpoint(const std::string& path, const nlohmann::json& identity,
                            const std::vector<evaluation::RecordedFrame>& frames);

}  // namespace lodopt::cli
