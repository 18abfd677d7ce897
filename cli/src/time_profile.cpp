#include "time_profile.hpp"

#include <time.h>

#include <algorithm>
#include <cassert>
#include <chrono>
#include <vector>

#include "cli_common.hpp"
#include "statistics.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::cli {
namespace {

double processCpuMs() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

}  // namespace

DrawTimes timeDraws(renderer::Renderer& renderer, const scenes::Combination& combination, const scenes::Camera& camera,
                    int repeats, int warmup) {
    assert(repeats >= 1);
    for (int i = 0; i < warmup; ++i) renderer.drawAndFinish(combination, camera);
    std::vector<double> wall, cpu;
    for (int i = 0; i < repeats; ++i) {
        const double cpuStart = processCpuMs();
        const auto wallStart = std::chrono::steady_clock::now();
        renderer.drawAndFinish(combination, camera);
        const auto wallStop = std::chrono::steady_clock::now();
        cpu.push_back(processCpuMs() - cpuStart);
        wall.push_back(std::chrono::duration<double, std::milli>(wallStop - wallStart).count());
    }
    return {*std::min_element(wall.begin(), wall.end()), median(wall), median(cpu)};
}

double batchTime(const DrawTimes& times, const std::string& clock) {
    if (clock == "cpu") return times.cpuMedian;
    if (clock == "wall-median") return times.wallMedian;
    return times.wallMin;
}

TimeEstimator loadTimeEstimator(const std::string& profilePath, const std::string& modelName,
                                const std::string& sceneName, const renderer::RenderSettings& settings,
                                const std::string& glRenderer, std::ostream& warnings) {
    timemodel::DeviceProfile profile;
    std::string source;
    try {
        if (profilePath.empty()) {
            bool exact = false;
            profile = timemodel::shippedProfile(sceneName, &exact);
            source = "shipped profile '" + profile.scene + "'";
        } else {
            profile = timemodel::loadProfile(profilePath);
            source = profilePath;
        }
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }
    std::unique_ptr<timemodel::TimeModel> model;
    try {
        model = timemodel::modelFromProfile(profile, modelName);
    } catch (const timemodel::TimeModelError& error) {
        throw UsageError(error.what());
    }
    for (const std::string& warning :
         timemodel::profileWarnings(profile, glRenderer, settings.width, settings.height, timemodel::describeMachine(),
                                    renderer::shadingName(settings.shading))) {
        warnings << "lodopt: warning: " << source << ": " << warning << "\n";
    }
    TimeEstimator estimator;
    estimator.name = model->name() + " (" + source + ")";
    estimator.model = std::shared_ptr<timemodel::TimeModel>(std::move(model));
    std::shared_ptr<timemodel::TimeModel> shared = estimator.model;
    estimator.estimate = [shared](const timemodel::FrameFeatures& features) { return shared->estimateMs(features); };
    return estimator;
}

}  // namespace lodopt::cli
