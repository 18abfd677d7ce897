// Device profiles: one calibration run written down, so a model can be used without re-timing.
//
// A profile is a JSON file holding, for every model, its coefficients (by name), fit notes and
// residuals and its held-out error statistics, plus what it was measured on: CPU model and core
// count, the OpenGL renderer and version strings, the render size, the scene, the date, the
// timing settings, and the samples themselves. Profiles measured on the build machine for the
// built-in scenes ship inside the library (timemodel/profiles/<scene>.json), so an estimate
// works without one from any working directory.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "timemodel/calibration.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

// A profile file that cannot be used: the message names the file (or "shipped profile
// 'harbor'") and the field.
class ProfileError : public TimeModelError {
public:
    using TimeModelError::TimeModelError;
};

struct MachineDescription {
    std::string cpuModel;  // /proc/cpuinfo "model name", "unknown" when unreadable
    int cores = 0;         // hardware threads
    // LP_NUM_THREADS as this process has it ("" when unset: llvmpipe rasterizes on one thread
    // per core). It changes frame times, most on small frames (docs/timemodel.md "Limits").
    std::string llvmpipeThreads;
};
// The machine this process runs on.
MachineDescription describeMachine();

struct TimingSettings {
    // What the profile's models predict (timing.hpp): "median" in every profile written since it
    // was fixed; older profiles predict the statistic they were fitted on (profileWarnings says so).
    std::string predicts = "median";
    std::string frameClock = "wall";     // renderer::frameClockName: what a frame's time was read from
    std::string learnedFrom = "median";  // the statistic the models were fitted on (timing.hpp)
    double learnedScale = 1.0;           // learned times were multiplied by it to predict `predicts`
    // What the calibration was asked for: a statistic's name, or "auto" (timing.hpp) when
    // `learnedFrom` was chosen in that run; empty in profiles written before it was recorded.
    std::string learnRequest;
    int rounds = 0;             // interleaved passes over all samples
    int repeatsPerRound = 0;    // timed draws per sample per pass
    int warmup = 0;             // untimed draws before each timed batch
    double medianSpread = 0.0;  // median over samples of (max − min) / median across passes
    double p90Spread = 0.0;
    double seconds = 0.0;  // wall time of the whole calibration
    // Held-out samples' median from the even passes against the odd ones, as a share of their
    // median: median and p90. How far the clock itself moves a sample, a floor under the held-out
    // errors; 0 in profiles written before it was recorded, or with one pass.
    double splitHalfMedian = 0.0;
    double splitHalfP90 = 0.0;
    // How far the machine's speed moved between passes (timing.hpp passDrift); 0 in profiles
    // written before it was recorded, or with one pass.
    double passDrift = 0.0;
    // The speed anchor: the scene's view `anchorView` with every object at its finest level,
    // timed at the start of every pass like a sample; anchorMs is the median over the passes of
    // its medians. A later run times the same frame to learn how much faster or slower the
    // machine draws now (evaluation::probeSpeed, `estimate --speed-probe`). Empty / 0 in
    // profiles written before it was recorded.
    std::string anchorView;
    double anchorMs = 0.0;
};

struct ProfileSample {
    Sample sample;  // measuredMs: the predicted statistic (TimingSettings::predicts)
    bool heldOut = false;
    int fold = -1;  // the sample's viewpoint's fold (0 = held out); -1 in profiles written before it was recorded
    // Every statistic of the same draws (timing.hpp; 0 when not recorded), so one run can be
    // refitted to learn from another.
    double leastMs = 0.0;
    double leastMedianMs = 0.0;
    double medianMs = 0.0;
    double cpuMs = 0.0;
    // Medians of the other clocks' times of the same draws (0 when not recorded): wall time, and
    // GL_TIME_ELAPSED where the driver has timer queries.
    double wallMedianMs = 0.0;
    double gpuMedianMs = 0.0;
};
// `sample`'s time by `statistic` (one of timingStatisticNames(), timing.hpp); 0 when not recorded.
double timeOfStatistic(const ProfileSample& sample, const std::string& statistic);

struct DeviceProfile {
    std::string created;  // ISO 8601 UTC, e.g. 2024-05-01T12:00:00Z
    MachineDescription machine;
    std::string glRenderer;  // "vendor / renderer" as renderer::Renderer::glRendererString()
    std::string glVersion;
    int width = 0;
    int height = 0;
    std::string shading = "lambert";  // renderer::Shading by name; files without it: lambert
    std::string scene;
    std::uint32_t sceneSeed = 1;
    std::uint64_t seed = 1;  // calibration plan seed
    int viewpoints = 0;
    int heldOutViewpoints = 0;
    TimingSettings timing;
    std::string defaultModel = kDefaultTimeModel;
    std::vector<ModelResult> models;
    std::vector<ProfileSample> samples;  // may be empty
};

std::string profileToJson(const DeviceProfile& profile);
// `source` names the text in error messages (a path, "shipped profile 'harbor'").
DeviceProfile profileFromJson(const std::string& text, const std::string& source);
// Written atomically; throws on I/O failure.
void saveProfile(const std::string& path, const DeviceProfile& profile);
// Throws ProfileError when the file is missing, not JSON, or lacks a field.
DeviceProfile loadProfile(const std::string& path);

// A fitted model from the profile: `name` empty means the profile's default model. Throws
// ProfileError when the profile has no such model or it was not fitted.
std::unique_ptr<TimeModel> modelFromProfile(const DeviceProfile& profile, const std::string& name = "");

// Why a profile may not fit the current setup: a different renderer string, frame clock, render
// size, shading, CPU model or core count, or a profile that predicts another statistic than the
// median every command measures (one sentence each; empty when it matches). Empty `glRenderer`
// or `frameClock` skips that check.
std::vector<std::string> profileWarnings(const DeviceProfile& profile, const std::string& glRenderer, int width,
                                         int height, const MachineDescription& machine, const std::string& shading,
                                         const std::string& frameClock = "");

// Above this drift between passes (TimingSettings::passDrift) a calibration says the machine's
// speed moved while it timed: a prediction carries that much uncertainty whatever the model.
// Only `calibrate` says so, when the user can act on it; the profile keeps the figure.
inline constexpr double kPassDriftWarning = 0.15;
// The sentence `calibrate` gives for such a drift.
std::string calibrationDriftWarning(double passDrift);

// Scenes with a profile built into the library.
std::vector<std::string> shippedProfileScenes();
// The shipped profile for `scene`, or for the default scene when there is none for it
// (`exact` tells which). Throws ProfileError when the library ships none at all.
DeviceProfile shippedProfile(const std::string& scene, bool* exact = nullptr);

// Now, as ISO 8601 UTC.
std::string currentDateUtc();

}  // namespace lodopt::timemodel
