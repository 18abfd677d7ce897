#include "bench_checkpoint.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "cli_common.hpp"

namespace lodopt::cli {
namespace {

// JSON writes NaN (and infinities, which no field holds) as null: numberOrNaN reads it back.
nlohmann::json toJson(const evaluation::AlgorithmRun& run) {
    return {{"algorithm", run.algorithm},
            {"evaluation_budget", run.evaluationBudget},
            {"seed", run.seed},
            {"wall_seconds", run.wallSeconds},
            {"fitness", run.fitness},
            {"predicted_ms", run.predictedMs},
            {"evaluations", run.evaluations},
            {"improvements", run.improvements}};
}

evaluation::AlgorithmRun runFromJson(const nlohmann::json& saved) {
    evaluation::AlgorithmRun run;
    run.algorithm = saved.at("algorithm").get<std::string>();
    run.evaluationBudget = saved.at("evaluation_budget").get<std::int64_t>();
    run.seed = saved.at("seed").get<std::uint64_t>();
    run.wallSeconds = numberOrNaN(saved.at("wall_seconds"));
    run.fitness = numberOrNaN(saved.at("fitness"));
    run.predictedMs = numberOrNaN(saved.at("predicted_ms"));
    run.evaluations = saved.at("evaluations").get<std::int64_t>();
    for (const nlohmann::json& point : saved.at("improvements")) {
        run.improvements.emplace_back(point.at(0).get<std::int64_t>(), numberOrNaN(point.at(1)));
    }
    return run;
}

nlohmann::json toJson(const evaluation::BestKnown& best) {
    return {{"fitness", best.fitness},
            {"source", best.source},
            {"combinations", best.combinations},
            {"evaluations", best.evaluations},
            {"seconds", best.seconds}};
}

evaluation::BestKnown bestFromJson(const nlohmann::json& saved) {
    evaluation::BestKnown best;
    best.fitness = numberOrNaN(saved.at("fitness"));
    best.source = saved.at("source").get<std::string>();
    best.combinations = numberOrNaN(saved.at("combinations"));
    best.evaluations = saved.at("evaluations").get<std::int64_t>();
    best.seconds = numberOrNaN(saved.at("seconds"));
    return best;
}

nlohmann::json toJson(const evaluation::EvalPathRow& row) {
    return {{"path", row.path},
            {"workload", row.workload},
            {"mode", row.mode},
            {"threads", row.threads},
            {"candidates", row.candidates},
            {"seconds", row.seconds},
            {"evaluations_per_second", row.evaluationsPerSecond},
            {"mean_abs_fitness_diff", row.meanAbsFitnessDiff},
            {"max_abs_fitness_diff", row.maxAbsFitnessDiff}};
}

evaluation::EvalPathRow pathFromJson(const nlohmann::json& saved) {
    evaluation::EvalPathRow row;
    row.path = saved.at("path").get<std::string>();
    row.workload = saved.at("workload").get<std::string>();
    row.mode = saved.at("mode").get<std::string>();
    row.threads = saved.at("threads").get<int>();
    row.candidates = saved.at("candidates").get<int>();
    row.seconds = numberOrNaN(saved.at("seconds"));
    row.evaluationsPerSecond = numberOrNaN(saved.at("evaluations_per_second"));
    row.meanAbsFitnessDiff = numberOrNaN(saved.at("mean_abs_fitness_diff"));
    row.maxAbsFitnessDiff = numberOrNaN(saved.at("max_abs_fitness_diff"));
    return row;
}

nlohmann::json toJson(const evaluation::MetricsRow& row) {
    return {{"function", row.function},
            {"width", row.width},
            {"height", row.height},
            {"calls", row.calls},
            {"microseconds_per_call", row.microsecondsPerCall},
            {"reference", row.reference},
            {"reference_microseconds_per_call", row.referenceMicrosecondsPerCall},
            {"abs_deviation", row.absDeviation}};
}

evaluation::MetricsRow metricsFromJson(const nlohmann::json& saved) {
    evaluation::MetricsRow row;
    row.function = saved.at("function").get<std::string>();
    row.width = saved.at("width").get<int>();
    row.height = saved.at("height").get<int>();
    row.calls = saved.at("calls").get<std::int64_t>();
    row.microsecondsPerCall = numberOrNaN(saved.at("microseconds_per_call"));
    row.reference = saved.at("reference").get<std::string>();
    row.referenceMicrosecondsPerCall = numberOrNaN(saved.at("reference_microseconds_per_call"));
    row.absDeviation = numberOrNaN(saved.at("abs_deviation"));
    return row;
}

nlohmann::json toJson(const evaluation::TimeModelRow& row) {
    return {{"model", row.model},   {"source", row.source}, {"samples", row.samples}, {"mean", row.mean},
            {"median", row.median}, {"p90", row.p90},       {"max", row.max}};
}

evaluation::TimeModelRow timeModelFromJson(const nlohmann::json& saved) {
    evaluation::TimeModelRow row;
    row.model = saved.at("model").get<std::string>();
    row.source = saved.at("source").get<std::string>();
    row.samples = saved.at("samples").get<std::size_t>();
    row.mean = numberOrNaN(saved.at("mean"));
    row.median = numberOrNaN(saved.at("median"));
    row.p90 = numberOrNaN(saved.at("p90"));
    row.max = numberOrNaN(saved.at("max"));
    return row;
}

template <typename Row>
nlohmann::json arrayOf(const std::vector<Row>& rows) {
    nlohmann::json array = nlohmann::json::array();
    for (const Row& row : rows) array.push_back(toJson(row));
    return array;
}

template <typename Read>
auto rowsOf(const nlohmann::json& array, Read read) {
    std::vector<decltype(read(array))> rows;
    for (const nlohmann::json& item : array) rows.push_back(read(item));
    return rows;
}

}  // namespace

nlohmann::json runToJson(const evaluation::AlgorithmRun& run) {
    return toJson(run);
}

BenchCheckpoint benchFromCheckpoint(const nlohmann::json& saved) {
    BenchCheckpoint checkpoint;
    checkpoint.runs = rowsOf(saved.at("runs"), runFromJson);
    if (saved.contains("best_known")) checkpoint.bestKnown = bestFromJson(saved["best_known"]);
    if (saved.contains("eval_paths")) checkpoint.evalPaths = rowsOf(saved["eval_paths"], pathFromJson);
    if (saved.contains("metrics")) checkpoint.metrics = rowsOf(saved["metrics"], metricsFromJson);
    if (saved.contains("time_models")) {
        const nlohmann::json& section = saved["time_models"];
        checkpoint.timeModels = TimeModelSection{rowsOf(section.at("rows"), timeModelFromJson),
                                                 section.at("warnings").get<std::vector<std::string>>()};
    }
    return checkpoint;
}

nlohmann::json benchToCheckpoint(const BenchCheckpoint& checkpoint) {
    nlohmann::json units = {{"runs", arrayOf(checkpoint.runs)}};
    if (checkpoint.bestKnown) units["best_known"] = toJson(*checkpoint.bestKnown);
    if (checkpoint.evalPaths) units["eval_paths"] = arrayOf(*checkpoint.evalPaths);
    if (checkpoint.metrics) units["metrics"] = arrayOf(*checkpoint.metrics);
    if (checkpoint.timeModels) {
        units["time_models"] = {{"rows", arrayOf(checkpoint.timeModels->rows)},
                                {"warnings", checkpoint.timeModels->warnings}};
    }
    return units;
}

}  // namespace lodopt::cli
