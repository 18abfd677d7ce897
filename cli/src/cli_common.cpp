#include "cli_common.hpp"

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

#include "scenes/atomic_file.hpp"

namespace lodopt::cli {

void addOutputOptions(CLI::App& command, OutputOptions& options) {
    command.add_flag("--json", options.json, "Print machine-readable JSON on stdout");
    command.add_flag("--quiet,-q", options.quiet, "No progress output");
}

void printJson(const nlohmann::json& document) {
    std::cout << document.dump(2) << std::endl;
}

void writeJsonFile(const std::string& path, const nlohmann::json& document) {
    scenes::writeTextAtomically(path, document.dump(2) + "\n");
}

std::vector<int> parseIntList(const std::string& text, const std::string& what) {
    std::vector<int> values;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        try {
            std::size_t used = 0;
            int value = std::stoi(item, &used);
            if (used != item.size()) throw std::invalid_argument(item);
            values.push_back(value);
        } catch (const std::exception&) {
            throw UsageError(what + ": '" + item + "' is not an integer (expected a list like 0,2,1)");
        }
    }
    if (values.empty()) throw UsageError(what + ": empty list");
    return values;
}

std::vector<double> parseNumberList(const std::string& text, const std::string& what, const std::string& expected) {
    std::vector<double> values;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        try {
            std::size_t used = 0;
            values.push_back(std::stod(item, &used));
            if (used != item.size()) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw UsageError(what + ": '" + item + "' is not a number (expected " + expected + ")");
        }
    }
    return values;
}

CLI::Option* addSceneOption(CLI::App& command, std::string& scene, bool positional) {
    return command.add_option(positional ? "--scene,scene" : "--scene", scene, "Built-in scene name or glTF/GLB path")
        ->capture_default_str();
}

CLI::Option* addViewOption(CLI::App& command, std::string& view, const std::string& help) {
    return command.add_option("--view", view, help)->capture_default_str();
}

CLI::Option* addSizeOption(CLI::App& command, std::string& size, const std::string& help) {
    return command.add_option("--size", size, help)->capture_default_str();
}

void addProfileOptions(CLI::App& command, std::string& profile, std::string& model) {
    command.add_option("--profile", profile, "Device profile from 'lodopt calibrate' (default: shipped)");
    command.add_option("--model", model, "Time model in the profile: linear, dong or wimmer (default: the profile's)");
}

void addWeightsOption(CLI::App& command, std::string& weights) {
    command
        .add_option("--weights", weights, "Fusion weights ssim,boundary,information (each >= 0; 0 skips that metric)")
        ->capture_default_str();
}

void addJudgeOptions(CLI::App& command, JudgeOptions& options, bool withSwitch) {
    if (withSwitch) {
        command.add_flag("!--no-judge", options.enabled,
                         "Do not score the answers with the judge (butteraugli), which no search reads");
    }
    command
        .add_option("--judge-nits", options.parameters.intensityTargetNits,
                    "Judge: the display's white in nits (butteraugli's intensity target)")
        ->capture_default_str();
    command
        .add_option("--judge-display-scale", options.parameters.displayScale,
                    "Judge: display pixels per image pixel on each axis (1..16)")
        ->capture_default_str();
    command
        .add_option("--judge-pnorm", options.parameters.pnorm, "Judge: the p of the p-norm pooling the distance map")
        ->capture_default_str();
}

std::optional<metrics::JudgeParameters> judgeParameters(const JudgeOptions& options) {
    try {
        metrics::validateJudgeParameters(options.parameters);
    } catch (const metrics::MetricError& error) {
        throw UsageError(error.what());
    }
    if (!options.enabled) return std::nullopt;
    return options.parameters;
}

nlohmann::json judgeJson(const std::optional<metrics::JudgeResult>& result,
                         const metrics::JudgeParameters& parameters) {
    if (!result) return nullptr;
    return {{"butteraugli", result->distance},
            {"butteraugli_max", result->maxDistance},
            {"pnorm", parameters.pnorm},
            {"intensity_target_nits", parameters.intensityTargetNits},
            {"display_scale", parameters.displayScale}};
}

nlohmann::json judgeIdentity(const JudgeOptions& options) {
    if (!options.enabled) return false;
    return {{"nits", options.parameters.intensityTargetNits},
            {"display-scale", options.parameters.displayScale},
            {"pnorm", options.parameters.pnorm}};
}

void addResumeFlag(CLI::App& command, bool& resume, const std::string& what) {
    command.add_flag("--resume", resume, "Continue from " + what + " saved by an interrupted run");
}

void addSceneSeedOption(CLI::App& command, std::uint32_t& sceneSeed) {
    command.add_option("--scene-seed", sceneSeed, "Variant of a built-in scene (not the search's seed)")
        ->capture_default_str();
}

void addShadingOption(CLI::App& command, std::string& shading) {
    command
        .add_option("--shading", shading,
                    "lambert (the papers': base color, Lambert + ambient) or pbr (glTF metallic-roughness, "
                    "alpha modes, culling, tone mapped)")
        ->check(CLI::IsMember({"lambert", "pbr"}))
        ->capture_default_str();
}

void BackendOptions::applyTo(renderer::RenderSettings& settings) const {
    settings.backend = renderer::parseBackend(backend);
    settings.frameClock = renderer::parseFrameClock(frameClock);
}

void addBackendOptions(CLI::App& command, BackendOptions& options) {
    command
        .add_option("--backend", options.backend,
                    "osmesa (software, deterministic: the default) or egl (headless on the machine's GPU driver, "
                    "else Mesa's)")
        ->check(CLI::IsMember({"osmesa", "egl"}))
        ->capture_default_str();
    command
        .add_option("--frame-clock", options.frameClock,
                    "What a timed frame's time is: wall (draw + glFinish), gpu (GL_TIME_ELAPSED) or auto (gpu on a "
                    "GPU driver with timer queries, wall on software rasterizers)")
        ->check(CLI::IsMember({"auto", "wall", "gpu"}))
        ->capture_default_str();
}

void parseSize(const std::string& text, int& width, int& height) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    std::istringstream stream(text);
    if (!(stream >> w >> x >> h) || (x != 'x' && x != 'X') || (stream >> extra) || w <= 0 || h <= 0 || w > 16384 ||
        h > 16384) {
        throw UsageError("--size: '" + text + "' is not WIDTHxHEIGHT with 1..16384 pixels each");
    }
    width = w;
    height = h;
}

double numberOrNaN(const nlohmann::json& value) {
    return value.is_null() ? std::numeric_limits<double>::quiet_NaN() : value.get<double>();
}

void checkIdentity(const std::string& path, const nlohmann::json& was, const nlohmann::json& identity) {
    for (auto it = identity.begin(); it != identity.end(); ++it) {
        if (was.contains(it.key()) && was[it.key()] == it.value()) continue;
        throw UsageError(path + ": was written with --" + it.key() + " " +
                         (was.contains(it.key()) ? was[it.key()].dump() : std::string("(unset)")) + ", this run has " +
                         it.value().dump() + "; resume with the same options, or delete the file to start over");
    }
}

void parseWeights(const std::string& text, metrics::MetricParameters& parameters) {
    std::vector<double> weights;
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ',')) {
        double value = 0;
        std::size_t used = 0;
        try {
            value = std::stod(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size() || !std::isfinite(value) || value < 0) {
            throw UsageError("--weights: '" + item + "' is not a finite number >= 0 (expected three, like 1,1,1)");
        }
        weights.push_back(value);
    }
    if (weights.size() != 3) {
        throw UsageError("--weights: '" + text +
                         "' must list exactly three weights: SSIM, boundary entropy, information entropy");
    }
    if (weights[0] + weights[1] + weights[2] <= 0) throw UsageError("--weights: at least one weight must be > 0");
    parameters.ssimWeight = weights[0];
    parameters.boundaryEntropyWeight = weights[1];
    parameters.informationEntropyWeight = weights[2];
}

}  // namespace lodopt::cli
