#include "schedule_checkpoint.hpp"


#include "cli_common.hpp"

namespace lodopt::cli {

std::vector<evaluation::RecordedFrame> framesFromCheckpoint(const nlohmann::json& saved) {
    std::vector<evaluation::RecordedFrame> frames;
    for (const nlohmann::json& item : saved.at("frames")) {
        evaluation::RecordedFrame f;
        f.frame = item.at("frame").get<int>();
        f.decisionMicroseconds = numberOrNaN(item.at("decision_us"));
        f.measuredMs = numberOrNaN(item.at("measured_ms"));
        f.baselineMeasuredMs = numberOrNaN(item.at("baseline_measured_ms"));
        f.fitness = numberOrNaN(item.at("fitness"));
        f.baselineFitness = numberOrNaN(item.at("baseline_fitness"));
        f.exactPredictedMs = numberOrNaN(item.at("exact_predicted_ms"));
        f.predictedMs = numberOrNaN(item.at("predicted_ms"));
        f.feedbackScale = numberOrNaN(item.at("feedback_scale"));
        f.levelsHash = item.at("levels_hash").get<std::uint64_t>();
        frames.push_back(f);
    }
    return frames;
}

nlohmann::json framesToCheckpoint(const std::vector<evaluation::RecordedFrame>& frames) {
    nlohmann::json list = nlohmann::json::array();
    for (const evaluation::RecordedFrame& f : frames) {
        list.push_back({{"frame", f.frame},
                        {"decision_us", f.decisionMicroseconds},
                        {"measured_ms", f.measuredMs},
                        {"baseline_measured_ms", f.baselineMeasuredMs},
                        {"fitness", f.fitness},
                        {"baseline_fitness", f.baselineFitness},
                        {"exact_predicted_ms", f.exactPredictedMs},
                        {"predicted_ms", f.predictedMs},
                        {"feedback_scale", f.feedbackScale},
                        {"levels_hash", f.levelsHash}});
    }
    return {{"frames", list}};
}

}  // namespace lodopt::cli
