// Coefficients files of the scheduler (see scheduler/coefficients.hpp).
#include "scheduler/coefficients.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace lodopt::scheduler {

namespace {

constexpr const char* kFormat = "lodopt-scheduler-coefficients";
constexpr double kDegrees = 57.29577951308232;

[[noreturn]] void fail(const std::string& source, const std::string& field, const std::string& what) {
    throw CoefficientsError(source + ": " + field + ": " + what);
}

const nlohmann::json& member(const nlohmann::json& object, const char* key, const std::string& source,
                             const std::string& where) {
    if (!object.is_object() || !object.contains(key)) fail(source, where + "." + key, "missing");
    return object.at(key);
}

double number(const nlohmann::json& object, const char* key, const std::string& source, const std::string& where,
              std::optional<double> fallback = std::nullopt) {
    if (fallback && (!object.is_object() || !object.contains(key))) return *fallback;
    const nlohmann::json& value = member(object, key, source, where);
    if (!value.is_number()) fail(source, where + "." + key, "expected a number");
    const double result = value.get<double>();
    if (!std::isfinite(result)) fail(source, where + "." + key, "not finite");
    return result;
}

}  // namespace

std::string coefficientsToJson(const SchedulerCoefficients& c) {
    nlohmann::json document;
    document["format"] = kFormat;
    document["version"] = 1;
    document["importance"] = {{"alpha1", c.importance.alpha1},
                              {"alpha2", c.importance.alpha2},
                              {"alpha3", c.importance.alpha3},
                              {"alpha4", c.importance.alpha4}};
    if (c.benchmark.view) {
        const ObjectView& v = *c.benchmark.view;
        document["benchmark"] = {{"distance", v.distance},
                                 {"view_angle_degrees", v.viewAngleRadians * kDegrees},
                                 {"projected_area", v.projectedArea},
                                 {"projected_pixels", v.projectedPixels},
                                 {"center_offset", v.centerOffset}};
    } else {
        document["benchmark"] = {{"scale", c.benchmark.scale}};
    }
    document["distance_thresholds"] = {{"relative_to_radius", c.thresholds.relativeToRadius},
                                       {"values", c.thresholds.values}};
    return document.dump(2);
}

SchedulerCoefficients coefficientsFromJson(const std::string& text, const std::string& source) {
    nlohmann::json document = nlohmann::json::parse(text, nullptr, false);
    if (document.is_discarded()) fail(source, "(document)", "not valid JSON");
    if (!document.is_object()) fail(source, "(document)", "expected a JSON object");
    const nlohmann::json& format = member(document, "format", source, "");
    if (!format.is_string() || format.get<std::string>() != kFormat) {
        fail(source, ".format", std::string("expected \"") + kFormat + "\"");
    }
    const nlohmann::json& version = member(document, "version", source, "");
    if (!version.is_number_integer() || version.get<int>() != 1) fail(source, ".version", "expected 1");

    SchedulerCoefficients c;
    const nlohmann::json& importance = member(document, "importance", source, "");
    c.importance.alpha1 = number(importance, "alpha1", source, ".importance");
    c.importance.alpha2 = number(importance, "alpha2", source, ".importance");
    c.importance.alpha3 = number(importance, "alpha3", source, ".importance", 0.0);
    c.importance.alpha4 = number(importance, "alpha4", source, ".importance", 0.0);
    try {
        validateCoefficients(c.importance);
    } catch (const std::invalid_argument& error) {
        fail(source, ".importance", error.what());
    }

    const nlohmann::json& benchmark = member(document, "benchmark", source, "");
    if (!benchmark.is_object()) fail(source, ".benchmark", "expected an object");
    if (benchmark.contains("scale")) {
        c.benchmark.scale = number(benchmark, "scale", source, ".benchmark");
        if (c.benchmark.scale <= 0.0) fail(source, ".benchmark.scale", "must be > 0");
    } else {
        ObjectView v;
        v.distance = number(benchmark, "distance", source, ".benchmark");
        v.viewAngleRadians = number(benchmark, "view_angle_degrees", source, ".benchmark") / kDegrees;
        v.projectedArea = number(benchmark, "projected_area", source, ".benchmark");
        v.projectedPixels = number(benchmark, "projected_pixels", source, ".benchmark", 1.0);
        v.centerOffset = number(benchmark, "center_offset", source, ".benchmark", 0.0);
        if (v.distance < 0.0) fail(source, ".benchmark.distance", "must be >= 0");
        if (v.viewAngleRadians < 0.0 || v.viewAngleRadians >= 1.5707963267948966) {
            fail(source, ".benchmark.view_angle_degrees", "must be in [0, 90)");
        }
        if (v.projectedArea <= 0.0) fail(source, ".benchmark.projected_area", "must be > 0");
        if (v.projectedPixels < 0.0) fail(source, ".benchmark.projected_pixels", "must be >= 0");
        if (v.centerOffset < 0.0) fail(source, ".benchmark.center_offset", "must be >= 0");
        if (!(importanceDenominator(v, c.importance) > 0.0)) fail(source, ".benchmark", "its denominator is 0");
        c.benchmark.view = v;
    }

    const nlohmann::json& thresholds = member(document, "distance_thresholds", source, "");
    const nlohmann::json& relative = member(thresholds, "relative_to_radius", source, ".distance_thresholds");
    if (!relative.is_boolean()) fail(source, ".distance_thresholds.relative_to_radius", "expected true or false");
    c.thresholds.relativeToRadius = relative.get<bool>();
    const nlohmann::json& values = member(thresholds, "values", source, ".distance_thresholds");
    if (!values.is_array()) fail(source, ".distance_thresholds.values", "expected an array of numbers");
    c.thresholds.values.clear();
    for (std::size_t k = 0; k < values.size(); ++k) {
        if (!values[k].is_number()) {
            fail(source, ".distance_thresholds.values[" + std::to_string(k) + "]", "expected a number");
        }
        c.thresholds.values.push_back(values[k].get<double>());
    }
    try {
        validateThresholds(c.thresholds);
    } catch (const std::invalid_argument& error) {
        fail(source, ".distance_thresholds", error.what());
    }
    return c;
}

SchedulerCoefficients loadCoefficients(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw CoefficientsError(path + ": cannot open the coefficients file");
    std::ostringstream text;
    text << file.rdbuf();
    return coefficientsFromJson(text.str(), path);
}

}  // namespace lodopt::scheduler
