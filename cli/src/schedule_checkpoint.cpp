#include "schedule_checkpoint.hpp"

#include <fstream>
#include <limits>

#include "cli_common.hpp"

namespace lodopt::cli {
namespace {

constexpr const char* kFormat = "lodopt-schedule-checkpoint/1";

}  // namespace

std::vector<evaluation::RecordedFrame> loadScheduleCheckpoint(const std::string& path, const nlohmann::json& identity) {
    std::vector<evaluation::RecordedFrame> frames;
    try {
        std::ifstream in(path);
        const nlohmann::json saved = nlohmann::json::parse(in);
        if (saved.at("format") != kFormat) throw std::invalid_argument("unknown format");
        checkIdentity(path, saved.at("options"), identity);
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
    } catch (const UsageError&) {
        throw;
    } catch (const std::exception& error) {
        throw UsageError(path + ": not a readable schedule checkpoint (" + error.what() + "); delete it to start over");
    }
    return frames;
}

void saveScheduleCheckpoint(const std::string& path, const nlohmann::json& identity,
                            const std::vector<evaluation::RecordedFrame>& frames) {
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
    writeJsonFile(path, {{"format", kFormat}, {"options", identity}, {"frames", list}});
}

}  // namespace lodopt::cli
