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

// The frames of a schedule checkpoint (CheckpointFile "schedule", units "frames").
std::vector<evaluation::RecordedFrame> framesFromCheckpoint(const nlohmann::json& saved);
// {"frames": [...]}, for CheckpointFile::save.
nlohmann::json framesToCheckpoint(const std::vector<evaluation::RecordedFrame>& frames);

}  // namespace lodopt::cli
