#include "cli_common.hpp"

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

void parseSize(const std::string& text, int& width, int& height) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    std::istringstream stream(text);
    if (!(stream >> w >> x >> h) || (x != 'x' && x != 'X') || (stream >> extra) || w <= 0 || h <= 0 ||
        w > 16384 || h > 16384) {
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

std::vector<bool> heldOutViews(int count, int holdout) {
    std::vector<bool> heldOut(std::size_t(std::max(count, 0)), false);
    if (holdout < 1 || holdout >= count) return heldOut;
    const int stride = count / holdout;
    for (int j = 0; j < holdout; ++j) heldOut[std::size_t(j * stride + (stride - 1 - j % stride))] = true;
    return heldOut;
}

std::vector<int> tuningFolds(const std::vector<bool>& heldOut, int folds) {
    std::vector<int> fold(heldOut.size(), -1);
    int next = 0;
    for (std::size_t k = 0; k < heldOut.size(); ++k) {
        if (!heldOut[k]) fold[k] = next++ % std::max(folds, 1);
    }
    return fold;
}

int firstBestAbove(double floor, const std::vector<double>& scores, double margin) {
    int chosen = -1;
    double best = floor;
    for (std::size_t i = 0; i < scores.size(); ++i) {
        if (scores[i] > best + margin) {
            chosen = int(i);
            best = scores[i];
        }
    }
    return chosen;
}

}  // namespace lodopt::cli
