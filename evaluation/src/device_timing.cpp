#include "evaluation/device_timing.hpp"

#include <time.h>

#include <algorithm>
#include <cassert>
#include <stdexcept>

#include "timemodel/features.hpp"

namespace lodopt::evaluation {

namespace {

double processCpuMs() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return double(now.tv_sec) * 1e3 + double(now.tv_nsec) * 1e-6;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Every sample timed in passes; returns the pass count.
int timePasses(renderer::Renderer& renderer, const timemodel::CalibrationPlan& plan,
               const CalibrationSettings& settings, const CalibrationProgress& progress,
               std::vector<timemodel::PassTimes>& timings) {
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
        std::size_t done = 0;
        for (std::size_t index : order) {
            const timemodel::PlannedSample& planned = plan.samples[index];
            const DrawTimes times = timeDraws(renderer, planned.combination, plan.viewpoints[planned.viewpoint].camera,
                                              settings.repeats, settings.warmup);
            timings[index].leastWall.push_back(times.wallMin);
            timings[index].medianWall.push_back(times.wallMedian);
            timings[index].medianCpu.push_back(times.cpuMedian);
            if (progress) progress(passes, ++done, count);
        }
        slowestPass = std::max(slowestPass, secondsSince(settings.start) - passStart);
        ++passes;
    }
    return passes;
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
    return {*std::min_element(wall.begin(), wall.end()), timemodel::median(wall), timemodel::median(cpu)};
}

double batchTime(const DrawTimes& times, const std::string& clock) {
    if (clock == "cpu") return times.cpuMedian;
    if (clock == "wall-median") return times.wallMedian;
    return times.wallMin;
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
    const int passes = timePasses(renderer, plan, settings, progress, timings);
    const std::size_t count = plan.samples.size();

    CalibrationResult result;
    result.folds = plan.folds;
    std::vector<bool> heldOut(count);
    for (std::size_t i = 0; i < count; ++i) heldOut[i] = plan.viewpoints[plan.samples[i].viewpoint].heldOut;
    std::vector<bool> fitting = heldOut;
    fitting.flip();
    result.choice = timemodel::chooseMostRepeatableClock(timings, fitting);
    const std::string clock = settings.clock == timemodel::kAutoClock ? result.choice.clock : settings.clock;

    timemodel::DeviceProfile& profile = result.profile;
    std::vector<timemodel::Sample> fitSamples, heldOutSamples;
    std::vector<double> spreads;
    for (std::size_t i = 0; i < count; ++i) {
        const timemodel::PlannedSample& planned = plan.samples[i];
        const timemodel::PassTimes& t = timings[i];
        timemodel::ProfileSample recorded;
        recorded.wallMinMs = timemodel::timeFromPasses("wall-min", t);
        recorded.wallMinMedianMs = timemodel::timeFromPasses("wall-min-median", t);
        recorded.wallMedianMs = timemodel::timeFromPasses("wall-median", t);
        recorded.cpuMs = timemodel::timeFromPasses("cpu", t);
        timemodel::Sample& sample = recorded.sample;
        sample.features = tables[planned.viewpoint].features(planned.combination);
        sample.measuredMs = timemodel::timeOnClock(recorded, clock);
        sample.viewpoint = planned.viewpoint;
        if (sample.measuredMs > 0.0) spreads.push_back(timemodel::passSpread(timemodel::perPassValues(clock, t)));
        recorded.heldOut = heldOut[i];
        (recorded.heldOut ? heldOutSamples : fitSamples).push_back(sample);
        profile.samples.push_back(recorded);
    }
    result.fitSamples = fitSamples.size();
    result.heldOutSamples = heldOutSamples.size();
    profile.models = timemodel::fitAllModels(fitSamples, heldOutSamples);
    {  // every viewpoint held out once, from the same draws
        std::vector<timemodel::Sample> all;
        std::vector<int> folds;
        for (std::size_t i = 0; i < count; ++i) {
            all.push_back(profile.samples[i].sample);
            folds.push_back(plan.viewpoints[plan.samples[i].viewpoint].fold);
        }
        const std::vector<timemodel::ErrorStats> rotated = timemodel::rotatedHeldOutErrors(all, folds);
        for (std::size_t m = 0; m < profile.models.size() && m < rotated.size(); ++m) {
            profile.models[m].rotatedErrors = rotated[m];
        }
    }
    const bool anyFitted = std::any_of(profile.models.begin(), profile.models.end(),
                                       [](const timemodel::ModelResult& r) { return r.fitted; });
    if (!anyFitted) {
        std::string reasons;
        for (const auto& r : profile.models) reasons += "\n  " + r.name + ": " + r.failure;
        throw std::runtime_error("no time model could be fitted:" + reasons);
    }

    for (const std::string& other : timemodel::timingClockNames()) {
        if (other == clock) continue;
        std::vector<timemodel::Sample> fitOther, heldOutOther;
        for (const timemodel::ProfileSample& recorded : profile.samples) {
            timemodel::Sample sample = recorded.sample;
            sample.measuredMs = timemodel::timeOnClock(recorded, other);
            (recorded.heldOut ? heldOutOther : fitOther).push_back(sample);
        }
        result.otherClocks.push_back({other, timemodel::fitAllModels(fitOther, heldOutOther),
                                      timemodel::splitHalfRepeatability(other, timings, heldOut)});
    }

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
    result.repeatability = timemodel::splitHalfRepeatability(clock, timings, heldOut);
    profile.timing.clock = clock;
    profile.timing.clockRequest = settings.clock;
    profile.timing.rounds = passes;
    profile.timing.repeatsPerRound = settings.repeats;
    profile.timing.warmup = settings.warmup;
    profile.timing.medianSpread = result.spread.median;
    profile.timing.p90Spread = result.spread.p90;
    profile.timing.splitHalfMedian = result.repeatability.median;
    profile.timing.splitHalfP90 = result.repeatability.p90;
    profile.timing.seconds = secondsSince(settings.start);
    return result;
}

}  // namespace lodopt::evaluation
