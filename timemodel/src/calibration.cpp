// Calibration plan and the side-by-side fit of every model (DONG15 eq. 10 errors).
#include "timemodel/calibration.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <glm/gtc/constants.hpp>
#include <memory>
#include <sstream>

#include "timemodel/timing.hpp"

namespace lodopt::timemodel {

std::uint64_t SplitMix64::next() {
    std::uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

double SplitMix64::uniform() {
    return double(next() >> 11) * 0x1.0p-53;
}

int SplitMix64::below(int n) {
    assert(n > 0);
    return static_cast<int>(uniform() * double(n));
}

scenes::Camera jitterCamera(const scenes::Camera& camera, SplitMix64& rng) {
    scenes::Camera out = camera;
    const glm::vec3 offset = camera.position - camera.target;
    const float distance = glm::length(offset);
    if (!(distance > 0.0f)) return out;
    glm::vec3 up = glm::length(camera.up) > 0.0f ? glm::normalize(camera.up) : glm::vec3(0.0f, 1.0f, 0.0f);
    // Spherical coordinates of the offset around `up`.
    const glm::vec3 direction = offset / distance;
    float pitch = std::asin(std::clamp(glm::dot(direction, up), -1.0f, 1.0f));
    glm::vec3 horizontal = direction - glm::dot(direction, up) * up;
    glm::vec3 east = glm::length(horizontal) > 1e-6f ? glm::normalize(horizontal)
                                                     : glm::normalize(glm::cross(up, glm::vec3(1.0f, 0.0f, 0.0f)));
    glm::vec3 north = glm::cross(up, east);
    const float yaw = float(rng.between(-25.0, 25.0)) * glm::pi<float>() / 180.0f;
    pitch = std::clamp(pitch + float(rng.between(-10.0, 10.0)) * glm::pi<float>() / 180.0f, -1.45f, 1.45f);
    const float scale = float(std::exp(rng.between(-0.25, 0.25)));
    const glm::vec3 rotated = std::cos(yaw) * east + std::sin(yaw) * north;
    const glm::vec3 newDirection = std::cos(pitch) * rotated + std::sin(pitch) * up;
    const glm::vec3 shift(float(rng.between(-1.0, 1.0)), float(rng.between(-1.0, 1.0)), float(rng.between(-1.0, 1.0)));
    out.target = camera.target + 0.04f * distance * shift;
    out.position = out.target + newDirection * distance * scale;
    return out;
}

namespace {

scenes::Combination sampleCombination(const scenes::Scene& scene, const CalibrationOptions& options, SplitMix64& rng) {
    scenes::Combination combination(scene.objects.size());
    if (rng.uniform() < 0.5) {
        for (std::size_t o = 0; o < combination.size(); ++o) {
            const int levels = static_cast<int>(scene.objects[o].levels.size());
            combination[o] = rng.uniform() < options.notDrawnProbability ? scenes::kNotDrawn : rng.below(levels);
        }
        return combination;
    }
    // Skewed: a preferred relative level and a drawn fraction for the whole frame; often
    // every object is drawn, so that full, fine frames (the reference) are inside the data.
    const double preferred = rng.uniform();
    const double drawn = rng.uniform() < 0.4 ? 1.0 : rng.between(0.3, 1.0);
    for (std::size_t o = 0; o < combination.size(); ++o) {
        const int levels = static_cast<int>(scene.objects[o].levels.size());
        if (rng.uniform() >= drawn) {
            combination[o] = scenes::kNotDrawn;
        } else if (rng.uniform() < 0.25) {
            combination[o] = rng.below(levels);
        } else {
            combination[o] = std::min(levels - 1, static_cast<int>(preferred * double(levels)));
        }
    }
    return combination;
}

}  // namespace

CalibrationPlan planCalibration(const scenes::Scene& scene, const CalibrationOptions& options) {
    if (options.samples < 4) {
        throw TimeModelError("calibration needs at least 4 samples, got " + std::to_string(options.samples));
    }
    if (options.jitteredPerView < 0) {
        throw TimeModelError("jittered viewpoints per view must be >= 0, got " +
                             std::to_string(options.jitteredPerView));
    }
    if (!(options.notDrawnProbability >= 0.0 && options.notDrawnProbability <= 1.0)) {
        throw TimeModelError("not-drawn probability must be in [0, 1]");
    }
    if (scene.objects.empty()) throw TimeModelError("scene '" + scene.name + "' has no objects to time");
    if (scene.views.empty()) throw TimeModelError("scene '" + scene.name + "' has no views to calibrate from");
    std::vector<int> views = options.views;
    if (views.empty()) {
        for (std::size_t v = 0; v < scene.views.size(); ++v) views.push_back(static_cast<int>(v));
    }
    for (int v : views) {
        if (v < 0 || v >= static_cast<int>(scene.views.size())) {
            throw TimeModelError("scene '" + scene.name + "' has no view " + std::to_string(v));
        }
    }
    const int group = options.jitteredPerView + 1;
    if (views.size() * std::size_t(group) < 2) {
        throw TimeModelError("calibration needs at least two viewpoints to hold one out: use more views or jitter");
    }

    SplitMix64 rng(options.seed);
    CalibrationPlan plan;
    for (std::size_t g = 0; g < views.size(); ++g) {
        const scenes::Camera& named = scene.views[views[g]];
        for (int member = 0; member < group; ++member) {
            Viewpoint viewpoint;
            viewpoint.namedView = views[g];
            viewpoint.jittered = member > 0;
            viewpoint.camera = member == 0 ? named : jitterCamera(named, rng);
            if (viewpoint.jittered) viewpoint.camera.name = named.name + "~" + std::to_string(member);
            // Held out by rotation k when member == (g + seed + k) mod group (with no jitter:
            // when (g + seed + k) mod 4 == 0); its fold is that k.
            const int folds = group > 1 ? group : 4;
            const int shifted = static_cast<int>((g + options.seed) % std::uint64_t(folds));
            viewpoint.fold = ((group > 1 ? member : 0) - shifted + folds) % folds;
            viewpoint.heldOut = viewpoint.fold == 0;
            plan.folds = folds;
            plan.viewpoints.push_back(std::move(viewpoint));
        }
    }
    // With one view per group and fewer than four views the rotation may hold out none.
    bool anyHeldOut = false, anyFitted = false;
    for (const Viewpoint& v : plan.viewpoints) (v.heldOut ? anyHeldOut : anyFitted) = true;
    if (!anyHeldOut) plan.viewpoints.back().heldOut = true;
    if (!anyFitted) plan.viewpoints.front().heldOut = false;
    for (Viewpoint& v : plan.viewpoints) {  // keep fold 0 = held out after those fixes
        if (v.heldOut) v.fold = 0;
        if (!v.heldOut && v.fold == 0) v.fold = 1;
    }
    plan.folds = std::max(plan.folds, 2);

    plan.samples.reserve(std::size_t(options.samples));
    for (int i = 0; i < options.samples; ++i) {
        PlannedSample sample;
        sample.viewpoint = i % static_cast<int>(plan.viewpoints.size());
        sample.combination = sampleCombination(scene, options, rng);
        plan.samples.push_back(std::move(sample));
    }
    return plan;
}

std::vector<ModelResult> fitAllModels(const std::vector<Sample>& fitSamples, const std::vector<Sample>& heldOut) {
    std::vector<ModelResult> results;
    for (const std::string& name : timeModelNames()) {
        std::unique_ptr<TimeModel> model = makeTimeModel(name);
        ModelResult result;
        result.name = name;
        result.coefficientNames = model->coefficientNames();
        try {
            result.fit = model->fit(fitSamples);
            result.fitted = true;
            result.coefficients = model->coefficients();
            result.fitErrors = relativeErrors(*model, fitSamples);
            result.heldOutErrors = relativeErrors(*model, heldOut);
        } catch (const TimeModelError& error) {
            result.failure = error.what();
        }
        results.push_back(std::move(result));
    }
    return results;
}

std::vector<ErrorStats> rotatedHeldOutErrors(const std::vector<Sample>& samples, const std::vector<int>& folds) {
    std::vector<double> times;
    for (const Sample& s : samples) times.push_back(s.measuredMs);
    return rotatedHeldOutErrors(samples, times, folds, timeModelNames());
}

std::vector<ErrorStats> rotatedHeldOutErrors(const std::vector<Sample>& learned, const std::vector<double>& predicted,
                                             const std::vector<int>& folds, const std::vector<std::string>& models) {
    if (folds.size() != learned.size() || predicted.size() != learned.size()) {
        throw TimeModelError("rotatedHeldOutErrors: one fold and one predicted time per sample are needed");
    }
    std::vector<std::vector<double>> errors(models.size());
    std::vector<bool> failed(models.size(), false);
    const int foldCount = folds.empty() ? 0 : *std::max_element(folds.begin(), folds.end()) + 1;
    for (int fold = 0; fold < foldCount; ++fold) {
        std::vector<Sample> fit;
        std::vector<double> fitLearned, fitPredicted;
        std::vector<std::size_t> held;
        for (std::size_t i = 0; i < learned.size(); ++i) {
            if (folds[i] == fold) {
                held.push_back(i);
                continue;
            }
            fit.push_back(learned[i]);
            fitLearned.push_back(learned[i].measuredMs);
            fitPredicted.push_back(predicted[i]);
        }
        if (held.empty()) continue;
        const double scale = learnedScale(fitLearned, fitPredicted);
        for (Sample& s : fit) s.measuredMs *= scale;
        for (std::size_t m = 0; m < models.size(); ++m) {
            if (failed[m]) continue;
            std::unique_ptr<TimeModel> model = makeTimeModel(models[m]);
            try {
                model->fit(fit);
            } catch (const TimeModelError&) {
                failed[m] = true;
                continue;
            }
            for (std::size_t i : held) {
                errors[m].push_back(std::abs(predicted[i] - model->estimateMs(learned[i].features)) / predicted[i]);
            }
        }
    }
    std::vector<ErrorStats> result(models.size());
    for (std::size_t m = 0; m < models.size(); ++m) {
        if (!failed[m]) result[m] = summarizeErrors(errors[m]);
    }
    return result;
}

std::string formatErrorTable(const std::vector<ModelResult>& results) {
    std::ostringstream out;
    char line[256];
    std::snprintf(line, sizeof line, "%-8s %9s %9s %9s %9s %9s %7s\n", "model", "mean", "median", "p90", "max",
                  "fit mean", "n");
    out << "|t_act - t_est| / t_act on held-out viewpoints\n" << line;
    for (const ModelResult& r : results) {
        if (!r.fitted) {
            out << r.name << "  not fitted: " << r.failure << "\n";
            continue;
        }
        const ErrorStats& e = r.heldOutErrors;
        std::snprintf(line, sizeof line, "%-8s %8.1f%% %8.1f%% %8.1f%% %8.1f%% %8.1f%% %7zu\n", r.name.c_str(),
                      100.0 * e.mean, 100.0 * e.median, 100.0 * e.p90, 100.0 * e.max, 100.0 * r.fitErrors.mean,
                      e.count);
        out << line;
    }
    return out.str();
}

}  // namespace lodopt::timemodel
