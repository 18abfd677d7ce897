// Shared plumbing of the lodopt commands: exit codes, error classes, JSON and table output.
#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "metrics/judge.hpp"
#include "metrics/metrics.hpp"
#include "renderer/renderer.hpp"

namespace lodopt::cli {

// Documented in the README: 0 ok, 1 runtime failure, 2 bad input or usage.
enum ExitCode : int { kExitOk = 0, kExitRuntime = 1, kExitBadInput = 2 };

// Bad command-line values or input files that the user must fix: exit code 2.
class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Options every result-printing command has.
struct OutputOptions {
    bool json = false;   // print one JSON document on stdout instead of text
    bool quiet = false;  // no progress lines
};
void addOutputOptions(CLI::App& command, OutputOptions& options);

// Prints `document` (pretty, 2 spaces) and a newline on stdout.
void printJson(const nlohmann::json& document);

// Writes `document` atomically to `path`.
void writeJsonFile(const std::string& path, const nlohmann::json& document);

// A number saved in a checkpoint; null (how nlohmann-json writes NaN) reads back as NaN.
double numberOrNaN(const nlohmann::json& value);

// For --resume: throws UsageError naming the first option of `identity` (the options that
// change a long command's results) that the checkpoint at `path` saved (`was`) with another
// value or not at all.
void checkIdentity(const std::string& path, const nlohmann::json& was, const nlohmann::json& identity);

// Parses "0,2,1" into integers; throws UsageError naming `what`.
std::vector<int> parseIntList(const std::string& text, const std::string& what);
// Parses "1.5,-2,3e-2" into numbers; throws UsageError naming `what` and `expected` (the form,
// e.g. "D1,K1,D2,K2,NEAR") for an item that is not one.
std::vector<double> parseNumberList(const std::string& text, const std::string& what, const std::string& expected);

// ---- Option groups: declared once, the same name and meaning on every command ----
// --scene NAME|FILE (built-in scene or glTF/GLB); `positional` also takes it without the flag.
CLI::Option* addSceneOption(CLI::App& command, std::string& scene, bool positional = false);
// --view NAME|INDEX (and 'all' where `help` says so).
CLI::Option* addViewOption(CLI::App& command, std::string& view, const std::string& help = "View name or index");
// --size WIDTHxHEIGHT (parseSize).
CLI::Option* addSizeOption(CLI::App& command, std::string& size, const std::string& help = "Render size WIDTHxHEIGHT");
// --profile FILE and --model NAME: the device profile (default: shipped) and its time model.
void addProfileOptions(CLI::App& command, std::string& profile, std::string& model);
// --weights ssim,boundary,information (parseWeights).
void addWeightsOption(CLI::App& command, std::string& weights);
// --resume: continue from what an interrupted run of the command saved (`what`).
void addResumeFlag(CLI::App& command, bool& resume, const std::string& what);

// --weights "ssim,boundary,information" (docs/metrics.md): three finite numbers >= 0, not all 0,
// into `parameters`' fusion weights; throws UsageError naming the bad item.
void parseWeights(const std::string& text, metrics::MetricParameters& parameters);
// Parses "512x512".
void parseSize(const std::string& text, int& width, int& height);
// The judge (docs/metrics.md "The judge"): --judge-nits, --judge-display-scale, --judge-pnorm, and
// --no-judge where a command judges its answers by default. Never read by a search.
struct JudgeOptions {
    bool enabled = true;
    metrics::JudgeParameters parameters;
};
// `withSwitch`: the command also takes --no-judge.
void addJudgeOptions(CLI::App& command, JudgeOptions& options, bool withSwitch = true);
// The judge's parameters, or nothing with --no-judge; throws UsageError for a bad value.
std::optional<metrics::JudgeParameters> judgeParameters(const JudgeOptions& options);
// {"butteraugli": 3-norm distance, "butteraugli_max", "pnorm", "intensity_target_nits",
//  "display_scale"}: one judge verdict as every command writes it; null without one.
nlohmann::json judgeJson(const std::optional<metrics::JudgeResult>& result, const metrics::JudgeParameters& parameters);
// The judge's options as a checkpoint identity holds them (checkIdentity): false with --no-judge.
nlohmann::json judgeIdentity(const JudgeOptions& options);

// --backend osmesa|egl (renderer::Backend) and --frame-clock auto|wall|gpu (renderer::FrameClock;
// docs/renderer.md "Backends" and "Timing"): the platform a command draws on, and what a frame's
// time is read from where it times frames.
struct BackendOptions {
    std::string backend = "osmesa";
    std::string frameClock = "auto";
    void applyTo(renderer::RenderSettings& settings) const;
};
void addBackendOptions(CLI::App& command, BackendOptions& options);
// --shading lambert|pbr (docs/renderer.md "Shading"); CLI11 refuses any other value.
void addShadingOption(CLI::App& command, std::string& shading);
// --scene-seed: which variant of a built-in scene a command uses, apart from any search seed, so
// that every seed of a search searches the same scene.
void addSceneSeedOption(CLI::App& command, std::uint32_t& sceneSeed);

// Each command adds itself as a subcommand; its callback throws on failure and main maps
// the exception to an exit code (UsageError, scenes::SceneError → 2; anything else → 1).
void addSceneCommand(CLI::App& app);
void addRenderCommand(CLI::App& app);
void addMetricsCommand(CLI::App& app);
void addCalibrateCommand(CLI::App& app);
void addEstimateCommand(CLI::App& app);
void addOptimizeCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);
void addTuneCommand(CLI::App& app);
void addScheduleCommand(CLI::App& app);
void addReportCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addSweepCommand(CLI::App& app);
void addThresholdsCommand(CLI::App& app);

}  // namespace lodopt::cli
