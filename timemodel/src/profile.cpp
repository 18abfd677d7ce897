// Device profiles as JSON (nlohmann::ordered_json keeps the fields in a readable order).
#include "timemodel/profile.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "scenes/atomic_file.hpp"
#include "scenes/builtin.hpp"
#include "shipped_profiles.hpp"
#include "timemodel/timing.hpp"

namespace lodopt::timemodel {

using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kFormat = "lodopt-device-profile";
constexpr int kVersion = 1;

Json errorsToJson(const ErrorStats& e) {
    return Json{{"count", e.count}, {"mean", e.mean}, {"median", e.median}, {"p90", e.p90}, {"max", e.max}};
}

// Reads fields with messages that name the source and the path of the field.
class Reader {
public:
    explicit Reader(std::string source) : mSource(std::move(source)) {}

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw ProfileError(mSource + ": " + where + ": " + what);
    }
    const Json& field(const Json& object, const std::string& key, const std::string& where) const {
        if (!object.is_object()) fail(where, "expected an object");
        auto it = object.find(key);
        if (it == object.end()) fail(where + "." + key, "missing");
        return *it;
    }
    double number(const Json& object, const std::string& key, const std::string& where) const {
        const Json& value = field(object, key, where);
        if (!value.is_number()) fail(where + "." + key, "expected a number");
        return value.get<double>();
    }
    long long integer(const Json& object, const std::string& key, const std::string& where) const {
        const Json& value = field(object, key, where);
        if (!value.is_number_integer()) fail(where + "." + key, "expected an integer");
        return value.get<long long>();
    }
    std::string text(const Json& object, const std::string& key, const std::string& where) const {
        const Json& value = field(object, key, where);
        if (!value.is_string()) fail(where + "." + key, "expected a string");
        return value.get<std::string>();
    }
    bool boolean(const Json& object, const std::string& key, const std::string& where) const {
        const Json& value = field(object, key, where);
        if (!value.is_boolean()) fail(where + "." + key, "expected true or false");
        return value.get<bool>();
    }
    ErrorStats errors(const Json& object, const std::string& key, const std::string& where) const {
        const Json& e = field(object, key, where);
        const std::string at = where + "." + key;
        ErrorStats stats;
        stats.count = static_cast<std::size_t>(integer(e, "count", at));
        stats.mean = number(e, "mean", at);
        stats.median = number(e, "median", at);
        stats.p90 = number(e, "p90", at);
        stats.max = number(e, "max", at);
        return stats;
    }

private:
    std::string mSource;
};

}  // namespace

double timeOfStatistic(const ProfileSample& sample, const std::string& statistic) {
    if (statistic == "least") return sample.leastMs;
    if (statistic == "least-median") return sample.leastMedianMs;
    if (statistic == "median") return sample.medianMs;
    if (statistic == "cpu") return sample.cpuMs;
    return 0.0;
}

MachineDescription describeMachine() {
    MachineDescription machine;
    machine.cpuModel = "unknown";
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("model name", 0) == 0) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos) {
                std::string value = line.substr(colon + 1);
                const std::size_t first = value.find_first_not_of(" \t");
                machine.cpuModel = first == std::string::npos ? value : value.substr(first);
            }
            break;
        }
    }
    machine.cores = static_cast<int>(std::thread::hardware_concurrency());
    if (const char* threads = std::getenv("LP_NUM_THREADS")) machine.llvmpipeThreads = threads;
    return machine;
}

std::string currentDateUtc() {
    const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm utc{};
    gmtime_r(&now, &utc);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
    return text;
}

std::string profileToJson(const DeviceProfile& profile) {
    Json models = Json::array();
    for (const ModelResult& model : profile.models) {
        Json coefficients = Json::object();
        for (std::size_t i = 0; i < model.coefficientNames.size() && i < model.coefficients.size(); ++i) {
            coefficients[model.coefficientNames[i]] = model.coefficients[i];
        }
        Json entry = {{"name", model.name}, {"fitted", model.fitted}};
        if (!model.fitted) entry["failure"] = model.failure;
        entry["coefficients"] = coefficients;
        entry["fit"] = {{"samples", model.fit.samples},
                        {"rms_residual_ms", model.fit.rmsResidualMs},
                        {"condition_number", model.fit.conditionNumber},
                        {"pairs", model.fit.pairs},
                        {"skipped_pairs", model.fit.skippedPairs},
                        {"iterations", model.fit.iterations},
                        {"notes", model.fit.notes},
                        {"errors", errorsToJson(model.fitErrors)}};
        entry["held_out_errors"] = errorsToJson(model.heldOutErrors);
        if (model.rotatedErrors.count > 0) entry["rotated_held_out_errors"] = errorsToJson(model.rotatedErrors);
        models.push_back(entry);
    }
    Json featureNames = Json::array();
    for (Feature feature : allFeatures()) featureNames.push_back(featureName(feature));
    Json samples = Json::array();
    std::size_t fitCount = 0, heldOutCount = 0;
    for (const ProfileSample& s : profile.samples) {
        (s.heldOut ? heldOutCount : fitCount) += 1;
        Json entry = {{"viewpoint", s.sample.viewpoint}, {"held_out", s.heldOut}, {"measured_ms", s.sample.measuredMs}};
        if (s.fold >= 0) entry["fold"] = s.fold;
        if (s.leastMs > 0.0) entry["least_ms"] = s.leastMs;
        if (s.leastMedianMs > 0.0) entry["least_median_ms"] = s.leastMedianMs;
        if (s.medianMs > 0.0) entry["median_ms"] = s.medianMs;
        if (s.cpuMs > 0.0) entry["cpu_ms"] = s.cpuMs;
        if (s.wallMedianMs > 0.0) entry["wall_median_ms"] = s.wallMedianMs;
        if (s.gpuMedianMs > 0.0) entry["gpu_median_ms"] = s.gpuMedianMs;
        entry["features"] = s.sample.features.values;
        samples.push_back(entry);
    }
    const TimingSettings& t = profile.timing;
    Json document = {
        {"format", kFormat},
        {"version", kVersion},
        {"created", profile.created},
        {"machine",
         {{"cpu_model", profile.machine.cpuModel},
          {"cores", profile.machine.cores},
          {"lp_num_threads", profile.machine.llvmpipeThreads}}},
        {"renderer", {{"gl_renderer", profile.glRenderer}, {"gl_version", profile.glVersion}}},
        {"render_size", {{"width", profile.width}, {"height", profile.height}, {"shading", profile.shading}}},
        {"scene", {{"name", profile.scene}, {"seed", profile.sceneSeed}}},
        {"calibration",
         {{"seed", profile.seed},
          {"viewpoints", profile.viewpoints},
          {"held_out_viewpoints", profile.heldOutViewpoints},
          {"fit_samples", fitCount},
          {"held_out_samples", heldOutCount},
          {"timing",
           {{"predicts", t.predicts},
            {"frame_clock", t.frameClock},
            {"learned_from", t.learnedFrom},
            {"learned_scale", t.learnedScale},
            {"learn_request", t.learnRequest},
            {"rounds", t.rounds},
            {"repeats_per_round", t.repeatsPerRound},
            {"warmup", t.warmup},
            {"median_spread", t.medianSpread},
            {"p90_spread", t.p90Spread},
            {"split_half_median", t.splitHalfMedian},
            {"split_half_p90", t.splitHalfP90},
            {"pass_drift", t.passDrift},
            {"anchor_view", t.anchorView},
            {"anchor_ms", t.anchorMs},
            {"seconds", t.seconds}}}}},
        {"default_model", profile.defaultModel},
        {"models", models},
        {"feature_names", featureNames},
        {"samples", "@samples@"},
    };
    // One line per sample keeps a profile of hundreds of samples readable and diffable.
    std::string samplesText = "[";
    for (std::size_t i = 0; i < samples.size(); ++i) {
        samplesText += (i ? ",\n    " : "\n    ") + samples[i].dump();
    }
    samplesText += samples.empty() ? "]" : "\n  ]";
    std::string text = document.dump(2);
    const std::string placeholder = "\"@samples@\"";
    text.replace(text.rfind(placeholder), placeholder.size(), samplesText);
    return text + "\n";
}

DeviceProfile profileFromJson(const std::string& text, const std::string& source) {
    Json document;
    try {
        document = Json::parse(text);
    } catch (const Json::exception& error) {
        throw ProfileError(source + ": not valid JSON (" + error.what() + ")");
    }
    Reader read(source);
    if (!document.is_object()) read.fail("document", "expected a JSON object");
    if (read.text(document, "format", "document") != kFormat) {
        read.fail("format", std::string("expected '") + kFormat + "'");
    }
    const long long version = read.integer(document, "version", "document");
    if (version != kVersion) read.fail("version", "unsupported version " + std::to_string(version));
    DeviceProfile profile;
    profile.created = read.text(document, "created", "document");
    const Json& machine = read.field(document, "machine", "document");
    profile.machine.cpuModel = read.text(machine, "cpu_model", "machine");
    profile.machine.cores = static_cast<int>(read.integer(machine, "cores", "machine"));
    // Optional: profiles written before it was recorded ran with it unset.
    if (machine.contains("lp_num_threads")) {
        profile.machine.llvmpipeThreads = read.text(machine, "lp_num_threads", "machine");
    }
    const Json& renderer = read.field(document, "renderer", "document");
    profile.glRenderer = read.text(renderer, "gl_renderer", "renderer");
    profile.glVersion = read.text(renderer, "gl_version", "renderer");
    const Json& size = read.field(document, "render_size", "document");
    profile.width = static_cast<int>(read.integer(size, "width", "render_size"));
    profile.height = static_cast<int>(read.integer(size, "height", "render_size"));
    if (profile.width < 1 || profile.height < 1) read.fail("render_size", "width and height must be >= 1");
    if (size.contains("shading")) profile.shading = read.text(size, "shading", "render_size");
    const Json& scene = read.field(document, "scene", "document");
    profile.scene = read.text(scene, "name", "scene");
    profile.sceneSeed = static_cast<std::uint32_t>(read.integer(scene, "seed", "scene"));
    const Json& calibration = read.field(document, "calibration", "document");
    profile.seed = static_cast<std::uint64_t>(read.integer(calibration, "seed", "calibration"));
    profile.viewpoints = static_cast<int>(read.integer(calibration, "viewpoints", "calibration"));
    profile.heldOutViewpoints = static_cast<int>(read.integer(calibration, "held_out_viewpoints", "calibration"));
    const Json& timing = read.field(calibration, "timing", "calibration");
    // Profiles written before the predicted statistic was fixed: "clock" named the one statistic
    // they were fitted on and predict, on the wall clock, unscaled.
    const bool fixedPrediction = timing.contains("predicts");
    auto statistic = [&](const char* key) {
        const std::string name = read.text(timing, key, "calibration.timing");
        const std::string canonical = canonicalStatistic(name);
        if (canonical.empty()) read.fail(std::string("calibration.timing.") + key, "unknown statistic '" + name + "'");
        return canonical;
    };
    if (fixedPrediction) {
        profile.timing.predicts = statistic("predicts");
        profile.timing.learnedFrom = statistic("learned_from");
        profile.timing.learnedScale = read.number(timing, "learned_scale", "calibration.timing");
        if (!(profile.timing.learnedScale > 0.0)) read.fail("calibration.timing.learned_scale", "must be > 0");
        profile.timing.frameClock = read.text(timing, "frame_clock", "calibration.timing");
        profile.timing.learnRequest = read.text(timing, "learn_request", "calibration.timing");
    } else {
        profile.timing.learnedFrom = statistic("clock");
        profile.timing.predicts = profile.timing.learnedFrom;
        if (timing.contains("clock_request")) {
            profile.timing.learnRequest = read.text(timing, "clock_request", "calibration.timing");
        }
    }
    profile.timing.rounds = static_cast<int>(read.integer(timing, "rounds", "calibration.timing"));
    profile.timing.repeatsPerRound = static_cast<int>(read.integer(timing, "repeats_per_round", "calibration.timing"));
    profile.timing.warmup = static_cast<int>(read.integer(timing, "warmup", "calibration.timing"));
    profile.timing.medianSpread = read.number(timing, "median_spread", "calibration.timing");
    profile.timing.p90Spread = read.number(timing, "p90_spread", "calibration.timing");
    profile.timing.seconds = read.number(timing, "seconds", "calibration.timing");
    // Optional: profiles written before they were recorded.
    if (timing.contains("split_half_median")) {
        profile.timing.splitHalfMedian = read.number(timing, "split_half_median", "calibration.timing");
        profile.timing.splitHalfP90 = read.number(timing, "split_half_p90", "calibration.timing");
    }
    if (timing.contains("anchor_ms")) {
        profile.timing.anchorView = read.text(timing, "anchor_view", "calibration.timing");
        profile.timing.anchorMs = read.number(timing, "anchor_ms", "calibration.timing");
        if (!(profile.timing.anchorMs >= 0.0)) read.fail("calibration.timing.anchor_ms", "must be >= 0");
    }
    if (timing.contains("pass_drift")) {
        profile.timing.passDrift = read.number(timing, "pass_drift", "calibration.timing");
        if (!(profile.timing.passDrift >= 0.0)) read.fail("calibration.timing.pass_drift", "must be >= 0");
    }
    profile.defaultModel = read.text(document, "default_model", "document");

    // Features by name: a profile written before a feature existed lacks it, and its
    // coefficients and samples read it as 0 (the model was fitted without it).
    std::vector<int> fileFeatures;  // file position -> Feature index
    std::vector<bool> inFile(kFeatureCount, false);
    if (document.contains("feature_names")) {
        const Json& names = document["feature_names"];
        if (!names.is_array()) read.fail("feature_names", "expected an array of names");
        for (std::size_t i = 0; i < names.size(); ++i) {
            if (!names[i].is_string()) read.fail("feature_names", "expected an array of names");
            const std::string name = names[i].get<std::string>();
            int found = -1;
            for (Feature feature : allFeatures()) {
                if (name == featureName(feature)) found = static_cast<int>(feature);
            }
            if (found < 0) read.fail("feature_names[" + std::to_string(i) + "]", "unknown feature '" + name + "'");
            if (inFile[found]) read.fail("feature_names[" + std::to_string(i) + "]", "'" + name + "' listed twice");
            inFile[found] = true;
            fileFeatures.push_back(found);
        }
    } else {
        for (Feature feature : allFeatures()) fileFeatures.push_back(static_cast<int>(feature));
        inFile.assign(kFeatureCount, true);
    }
    auto absentFeature = [&](const std::string& coefficient) {
        for (Feature feature : allFeatures()) {
            if (coefficient == featureName(feature)) return !inFile[static_cast<std::size_t>(feature)];
        }
        return false;
    };

    const Json& models = read.field(document, "models", "document");
    if (!models.is_array()) read.fail("models", "expected an array");
    for (std::size_t m = 0; m < models.size(); ++m) {
        const std::string at = "models[" + std::to_string(m) + "]";
        const Json& entry = models[m];
        ModelResult result;
        result.name = read.text(entry, "name", at);
        std::unique_ptr<TimeModel> model;
        try {
            model = makeTimeModel(result.name);
        } catch (const TimeModelError& error) {
            read.fail(at + ".name", error.what());
        }
        result.fitted = read.boolean(entry, "fitted", at);
        if (!result.fitted && entry.contains("failure") && entry["failure"].is_string()) {
            result.failure = entry["failure"].get<std::string>();
        }
        result.coefficientNames = model->coefficientNames();
        const Json& coefficients = read.field(entry, "coefficients", at);
        if (result.fitted) {
            for (const std::string& name : result.coefficientNames) {
                const bool absent = absentFeature(name) && coefficients.is_object() && !coefficients.contains(name);
                result.coefficients.push_back(absent ? 0.0 : read.number(coefficients, name, at + ".coefficients"));
            }
            try {
                model->setCoefficients(result.coefficients);  // checks finiteness
            } catch (const TimeModelError& error) {
                read.fail(at + ".coefficients", error.what());
            }
        }
        const Json& fit = read.field(entry, "fit", at);
        result.fit.samples = static_cast<std::size_t>(read.integer(fit, "samples", at + ".fit"));
        result.fit.rmsResidualMs = read.number(fit, "rms_residual_ms", at + ".fit");
        result.fit.conditionNumber = read.number(fit, "condition_number", at + ".fit");
        result.fit.pairs = static_cast<std::size_t>(read.integer(fit, "pairs", at + ".fit"));
        result.fit.skippedPairs = static_cast<std::size_t>(read.integer(fit, "skipped_pairs", at + ".fit"));
        result.fit.iterations = static_cast<int>(read.integer(fit, "iterations", at + ".fit"));
        const Json& notes = read.field(fit, "notes", at + ".fit");
        if (!notes.is_array()) read.fail(at + ".fit.notes", "expected an array");
        for (const Json& note : notes) {
            if (note.is_string()) result.fit.notes.push_back(note.get<std::string>());
        }
        result.fitErrors = read.errors(fit, "errors", at + ".fit");
        result.heldOutErrors = read.errors(entry, "held_out_errors", at);
        if (entry.contains("rotated_held_out_errors")) {  // older profiles lack it
            result.rotatedErrors = read.errors(entry, "rotated_held_out_errors", at);
        }
        profile.models.push_back(std::move(result));
    }

    if (document.contains("samples")) {
        const Json& samples = document["samples"];
        if (!samples.is_array()) read.fail("samples", "expected an array");
        for (std::size_t i = 0; i < samples.size(); ++i) {
            const std::string at = "samples[" + std::to_string(i) + "]";
            ProfileSample s;
            s.sample.viewpoint = static_cast<int>(read.integer(samples[i], "viewpoint", at));
            s.heldOut = read.boolean(samples[i], "held_out", at);
            if (samples[i].contains("fold")) {
                s.fold = static_cast<int>(read.integer(samples[i], "fold", at));
                if (s.fold < 0 || (s.fold == 0) != s.heldOut) read.fail(at + ".fold", "must be 0 exactly when held out");
            }
            s.sample.measuredMs = read.number(samples[i], "measured_ms", at);
            auto optional = [&](const char* key, double& value) {
                if (samples[i].contains(key)) value = read.number(samples[i], key, at);
            };
            optional("least_ms", s.leastMs);
            optional("least_median_ms", s.leastMedianMs);
            optional("median_ms", s.medianMs);
            optional("cpu_ms", s.cpuMs);
            optional("wall_median_ms", s.wallMedianMs);
            optional("gpu_median_ms", s.gpuMedianMs);
            if (!fixedPrediction) {  // older names, all on the wall clock
                optional("wall_min_ms", s.leastMs);
                optional("wall_min_median_ms", s.leastMedianMs);
                s.medianMs = s.wallMedianMs;
            }
            const Json& features = read.field(samples[i], "features", at);
            if (!features.is_array() || features.size() != fileFeatures.size()) {
                read.fail(at + ".features",
                          "expected " + std::to_string(fileFeatures.size()) + " numbers, one per feature_names entry");
            }
            for (std::size_t k = 0; k < fileFeatures.size(); ++k) {
                if (!features[k].is_number()) read.fail(at + ".features", "expected numbers");
                s.sample.features.values[std::size_t(fileFeatures[k])] = features[k].get<double>();
            }
            profile.samples.push_back(s);
        }
    }
    return profile;
}

void saveProfile(const std::string& path, const DeviceProfile& profile) {
    scenes::writeTextAtomically(path, profileToJson(profile));
}

DeviceProfile loadProfile(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw ProfileError(path + ": cannot open the profile file");
    std::ostringstream text;
    text << file.rdbuf();
    if (file.bad()) throw ProfileError(path + ": cannot read the profile file");
    return profileFromJson(text.str(), path);
}

std::unique_ptr<TimeModel> modelFromProfile(const DeviceProfile& profile, const std::string& name) {
    const std::string wanted = name.empty() ? profile.defaultModel : name;
    std::string known;
    for (const ModelResult& model : profile.models) {
        known += (known.empty() ? "" : ", ") + model.name;
        if (model.name != wanted) continue;
        if (!model.fitted) {
            throw ProfileError("profile model '" + wanted + "' was not fitted: " + model.failure);
        }
        std::unique_ptr<TimeModel> result = makeTimeModel(wanted);
        result->setCoefficients(model.coefficients);
        return result;
    }
    throw ProfileError("profile has no model '" + wanted + "' (models: " + (known.empty() ? "none" : known) + ")");
}

std::string calibrationDriftWarning(double passDrift) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "the machine's speed moved by %.0f%% between the calibration's passes: its predictions carry that "
                  "much uncertainty; calibrate again on a quiet machine",
                  100.0 * passDrift);
    return text;
}

std::vector<std::string> profileWarnings(const DeviceProfile& profile, const std::string& glRenderer, int width,
                                         int height, const MachineDescription& machine, const std::string& shading,
                                         const std::string& frameClock) {
    std::vector<std::string> warnings;
    if (profile.timing.predicts != kPredictedStatistic) {
        warnings.push_back("the profile predicts the " + profile.timing.predicts +
                           " of a frame's draws (written before every profile predicted their median, what "
                           "render --time measures): recalibrate");
    }
    if (!frameClock.empty() && frameClock != profile.timing.frameClock) {
        warnings.push_back("the profile timed frames on the " + profile.timing.frameClock + " clock, this renderer on the " +
                           frameClock + " clock: predictions and measurements are different quantities");
    }
    if (shading != profile.shading) {
        warnings.push_back("the profile was measured with --shading " + profile.shading + ", this is " + shading +
                           ": per-pixel costs differ");
    }
    if (!glRenderer.empty() && glRenderer != profile.glRenderer) {
        warnings.push_back("the profile was measured with renderer '" + profile.glRenderer + "', this is '" +
                           glRenderer + "': predictions may be off");
    }
    if (width != profile.width || height != profile.height) {
        warnings.push_back("the profile was measured at " + std::to_string(profile.width) + "x" +
                           std::to_string(profile.height) + ", this frame is " + std::to_string(width) + "x" +
                           std::to_string(height) + ": per-pixel costs may not transfer");
    }
    if (machine.cpuModel != profile.machine.cpuModel || machine.cores != profile.machine.cores) {
        warnings.push_back("the profile was measured on '" + profile.machine.cpuModel + "' with " +
                           std::to_string(profile.machine.cores) + " threads, this is '" + machine.cpuModel +
                           "' with " + std::to_string(machine.cores));
    }
    if (machine.llvmpipeThreads != profile.machine.llvmpipeThreads) {
        const auto shown = [](const std::string& value) { return value.empty() ? std::string("unset") : value; };
        warnings.push_back("the profile was measured with LP_NUM_THREADS " + shown(profile.machine.llvmpipeThreads) +
                           ", this process has " + shown(machine.llvmpipeThreads) +
                           ": llvmpipe's thread count changes frame times");
    }
    return warnings;
}

std::vector<std::string> shippedProfileScenes() {
    std::vector<std::string> names;
    for (const ShippedProfile& entry : shippedProfiles()) names.push_back(entry.scene);
    return names;
}

DeviceProfile shippedProfile(const std::string& scene, bool* exact) {
    const std::vector<ShippedProfile>& profiles = shippedProfiles();
    if (profiles.empty()) throw ProfileError("this build ships no device profile: run 'lodopt calibrate' first");
    const ShippedProfile* chosen = nullptr;
    for (const ShippedProfile& entry : profiles) {
        if (entry.scene == scene) chosen = &entry;
    }
    if (exact) *exact = chosen != nullptr;
    if (!chosen) {
        for (const ShippedProfile& entry : profiles) {
            if (entry.scene == scenes::kDefaultSceneName) chosen = &entry;
        }
    }
    if (!chosen) chosen = &profiles.front();
    return profileFromJson(chosen->json, "shipped profile '" + chosen->scene + "'");
}

}  // namespace lodopt::timemodel
