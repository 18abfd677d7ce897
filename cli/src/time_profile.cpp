#include "time_profile.hpp"

#include "cli_common.hpp"
#include "timemodel/profile.hpp"

namespace lodopt::cli {

TimeEstimator loadTimeEstimator(const std::string& profilePath, const std::string& modelName,
                                const std::string& sceneName, const renderer::RenderSettings& settings,
                                const renderer::Renderer* timedOn, std::ostream& warnings) {
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
         timemodel::profileWarnings(profile, timedOn ? timedOn->glRendererString() : "", settings.width,
                                    settings.height, timemodel::describeMachine(), renderer::shadingName(settings.shading),
                                    timedOn ? renderer::frameClockName(timedOn->frameClock()) : "")) {
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
