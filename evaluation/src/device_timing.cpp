#include "evaluation/device_timing.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>

#include "scenes/scene.hpp"
#include "timemodel/features.hpp"

namespace lodopt::evaluation {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double medianOr0(const std::vector<double>& values) {
    return values.empty() ? 0.0 : timemodel::median(values);
}

struct SpeedAnchor {
    scenes::Combination combination;
    scenes::Camera camera;
};

// The frame a profile's speed is anchored to: the scene's first view, every object at its
// finest level (what `render --view 0` draws by default).
constexpr int kAnchorView = 0;
SpeedAnchor speedAnchor(const scenes::Scene& scene) {
    if (scene.views.empty()) throw std::runtime_error("scene '" + scene.name + "' has no view to anchor the timing to");
    return {scenes::referenceCombination(scene), scene.views[kAnchorView]};
}

// Every sample timed in passes, each pass opened by the speed anchor (`anchorMs` gets its median
// per pass); returns the pass count.
int timePasses(renderer::Renderer& renderer, const timemodel::CalibrationPlan& plan, const SpeedAnchor& anchor,
               const CalibrationSettings& settings, const CalibrationProgress& progress,
               std::vector<timemodel::PassTimes>& timings, std::vector<double>& anchorMs) {
    const std::size_t count = plan.samples.size();
    timings.assign(count, {});
    timemodel::SplitMix64 shuffle(settings.seed ^ 0xC0FFEEull);
    std::vector<std::size_t> order(count);
    for (std::size_t i = 0; i < count; ++i) order[i] = i;
    int passes = 0;
    double slowestPass = 0.0;
    while (passes < settings.rounds || (passes < std::max(settings.rounds, settings.maxRounds) &&
                                        secondsSince(settings.start) + slowestPass <= settings.timeBudgetSeconds)) {
        const double passStart = secondsSince(settings.start);
        for (std::size_t i = count; i > 1; --i) std::swap(order[i - 1], order[std::size_t(shuffle.below(int(i)))]);
        anchorMs.push_back(
            renderer.timeFrames(anchor.combination, anchor.camera, settings.repeats, settings.warmup).median());
        std::size_t done = 0;
        for (std::size_t index : order) {
            const timemodel::PlannedSample& planned = plan.samples[index];
            const renderer::FrameTimes times = renderer.timeFrames(
                planned.combination, plan.viewpoints[planned.viewpoint].camera, settings.repeats, settings.warmup);
            timemodel::PassTimes& t = timings[index];
            t.least.push_back(times.least());
            t.median.push_back(times.median());
            t.cpu.push_back(medianOr0(times.cpuMs));
            t.wallMedian.push_back(medianOr0(times.wallMs));
            if (!times.gpuMs.empty()) t.gpuMedian.push_back(medianOr0(times.gpuMs));
            if (progress) progress(passes, ++done, count);
        }
        slowestPass = std::max(slowestPass, secondsSince(settings.start) - passStart);
        ++passes;
    }
    return passes;
}

}  // namespace

SpeedProbe probeSpeed(const scenes::Scene& scene, const timemodel::DeviceProfile& profile,
                      const renderer::RenderSettings& settings, int repeats, int warmup) {
    const timemodel::TimingSettings& timing = profile.timing;
    if (!(timing.anchorMs > 0.0) || timing.anchorView.empty()) {
        throw std::invalid_argument("the profile has no speed anchor (written before calibrations recorded one): "
                                    "calibrate again to probe the machine's speed");
    }
    if (profile.scene != scene.name) {
        throw std::invalid_argument("the profile's speed anchor is a frame of scene '" + profile.scene + "', not '" +
                                    scene.name + "'");
    }
    if (settings.width != profile.width || settings.height != profile.height ||
        renderer::shadingName(settings.shading) != profile.shading) {
        throw std::invalid_argument("the speed anchor was timed at " + std::to_string(profile.width) + "x" +
                                    std::to_string(profile.height) + " " + profile.shading +
                                    "; probe it at the same size and shading");
    }
    const auto view = std::find_if(scene.views.begin(), scene.views.end(),
                                   [&](const scenes::Camera& camera) { return camera.name == timing.anchorView; });
    if (view == scene.views.end()) {
        throw std::invalid_argument("the profile's speed anchor is view '" + timing.anchorView + "', which scene '" +
                                    scene.name + "' does not have");
    }
    renderer::Renderer renderer(scene, settings);
    SpeedProbe probe;
    probe.view = timing.anchorView;
    probe.anchorMs = timing.anchorMs;
    probe.probeMs = renderer.timeFrames(scenes::referenceCombination(scene), *view, repeats, warmup).median();
    probe.ratio = probe.probeMs / probe.anchorMs;
    return probe;
}

CalibrationResult calibrateDevice(const scenes::Scene& scene, renderer::Renderer& renderer,
                                  const timemodel::CalibrationPlan& plan, std::uint64_t planSeed,
                                  const CalibrationSettings& settings, const CalibrationProgress& progress) {
    const renderer::RenderSettings& renderSettings = renderer.settings();
    std::vector<timemodel::FeatureTable> tables;
    tables.reserve(plan.viewpoints.size());
    for (const timemodel::Viewpoint& viewpoint : plan.viewpoints) {
        tables.emplace_back(scene, viewpoint.camera, renderSettings.width, renderSettings.height);
    }
    std::vector<timemodel::PassTimes> timings;
    std::vector<double> anchorMs;
    const int passes = timePasses(renderer, plan, speedAnchor(scene), settings, progress, timings, anchorMs);
    const std::size_t count = plan.samples.size();

    CalibrationResult result;
    result.folds = plan.folds;
    timemodel::DeviceProfile& profile = result.profile;
    std::vector<bool> heldOut(count);
    std::vector<int> folds(count);
    std::vector<double> spreads;
    for (std::size_t i = 0; i < count; ++i) {
        const timemodel::PlannedSample& planned = plan.samples[i];
        const timemodel::PassTimes& t = timings[i];
        heldOut[i] = plan.viewpoints[planned.viewpoint].heldOut;
        folds[i] = plan.viewpoints[planned.viewpoint].fold;
        timemodel::ProfileSample recorded;
        recorded.leastMs = timemodel::timeFromPasses("least", t);
        recorded.leastMedianMs = timemodel::timeFromPasses("least-median", t);
        recorded.medianMs = timemodel::timeFromPasses("median", t);
        recorded.cpuMs = timemodel::timeFromPasses("cpu", t);
        recorded.wallMedianMs = medianOr0(t.wallMedian);
        recorded.gpuMedianMs = medianOr0(t.gpuMedian);
        recorded.sample.features = tables[planned.viewpoint].features(planned.combination);
        recorded.sample.measuredMs = recorded.medianMs;
        recorded.sample.viewpoint = planned.viewpoint;
        recorded.heldOut = heldOut[i];
        recorded.fold = folds[i];
        if (recorded.medianMs > 0.0) spreads.push_back(timemodel::passSpread(t.median));
        profile.samples.push_back(recorded);
    }
    timemodel::ProfileFit fit;
    try {
        fit = timemodel::fitProfile(profile, folds, settings.learnFrom);
    } catch (const timemodel::TimeModelError& error) {
        throw std::runtime_error(error.what());
    }
    result.choice = fit.choice;
    for (timemodel::StatisticFit& other : fit.others) {
        OtherStatisticFit entry{other.statistic, other.scale, std::move(other.models), {}};
        entry.repeatability = timemodel::splitHalfRepeatability(other.statistic, timings, heldOut);
        result.otherStatistics.push_back(std::move(entry));
    }
    for (const timemodel::ProfileSample& s : profile.samples) (s.heldOut ? result.heldOutSamples : result.fitSamples)++;

    profile.created = timemodel::currentDateUtc();
    profile.machine = timemodel::describeMachine();
    profile.glRenderer = renderer.glRendererString();
    profile.glVersion = renderer.glVersionString();
    profile.width = renderSettings.width;
    profile.height = renderSettings.height;
    profile.shading = renderer::shadingName(renderSettings.shading);
    profile.scene = scene.name;
    profile.seed = planSeed;
    profile.viewpoints = static_cast<int>(plan.viewpoints.size());
    profile.heldOutViewpoints = static_cast<int>(std::count_if(
        plan.viewpoints.begin(), plan.viewpoints.end(), [](const timemodel::Viewpoint& v) { return v.heldOut; }));
    result.spread = timemodel::summarizeErrors(spreads);
    result.repeatability = timemodel::splitHalfRepeatability(timemodel::kPredictedStatistic, timings, heldOut);
    result.passTimeFactors = timemodel::passTimeFactors(timings);
    timemodel::TimingSettings& timing = profile.timing;
    timing.frameClock = renderer::frameClockName(renderer.frameClock());
    timing.rounds = passes;
    timing.repeatsPerRound = settings.repeats;
    timing.warmup = settings.warmup;
    timing.medianSpread = result.spread.median;
    timing.p90Spread = result.spread.p90;
    timing.splitHalfMedian = result.repeatability.median;
    timing.splitHalfP90 = result.repeatability.p90;
    timing.passDrift = timemodel::passDrift(result.passTimeFactors);
    timing.anchorView = scene.views[kAnchorView].name;
    timing.anchorMs = medianOr0(anchorMs);
    timing.seconds = secondsSince(settings.start);
    return result;
}

}  // namespace lodopt::evaluation
