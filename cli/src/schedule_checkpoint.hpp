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

#include "scenes/scene.hpp"

namespace lodopt::cli {

struct SavedFrame {
    int frame = 0;  // index in the camera path
    double decisionMicroseconds = 0.0;
    double measuredMs = 0.0;  // NaN when not rendered
    double baselineMeasuredMs = 0.0;
    double fitness = 0.0;
    double baselineFitness = 0.0;
    double exactPredictedMs = 0.0;  // NaN without --check-features
    // Checks of the replay: it must reproduce these exactly.
    double predictedMs = 0.0;
    double feedbackScale = 1.0;  // after this frame's feedback
    std::uint64_t levelsHash = 0;
};

// FNV-1a over the levels: the replay's decision must hash alike.
std::uint64_t levelsHash(const scenes::Combination& levels);

// The frames saved by an interrupted schedule whose options equal `identity` (keyed by option
// name). Throws UsageError naming the option that differs, or saying that the file is unreadable.
std::vector<SavedFrame> loadScheduleCheckpoint(const std::string& path, const nlohmann::json& identity);
// Writes `frames` with `identity` atomically.
void saveScheduleCheckpoint(const std::string& path, const nlohmann::json& identity,
                            const std::vector<SavedFrame>& frames);

}  // namespace lodopt::cli
