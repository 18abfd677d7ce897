// Device profiles: JSON round trip, clear errors, mismatch warnings, the shipped profiles, and
// the per-view estimator built from a profile's model.
#include "timemodel/profile.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scenes/builtin.hpp"
#include "timemodel/timing.hpp"

using namespace lodopt;

namespace {

timemodel::DeviceProfile sampleProfile() {
    std::vector<timemodel::Sample> fit, heldOut;
    timemodel::SplitMix64 rng(9);
    for (int i = 0; i < 24; ++i) {
        timemodel::Sample s;
        s.features[timemodel::Feature::kTriangles] = rng.between(1e3, 1e5);
        s.features[timemodel::Feature::kTextureBytes] = rng.between(0.0, 1e6);
        s.features[timemodel::Feature::kPixels] = rng.between(1e3, 1e5);
        s.features[timemodel::Feature::kDrawCalls] = 1.0 + double(i % 5);
        // Nonzero, so that reading a file without them shows as zeros.
        for (timemodel::Feature later : {timemodel::Feature::kTexturedPixels, timemodel::Feature::kShadedEdgePixels,
                                         timemodel::Feature::kPartialBlocks, timemodel::Feature::kShadedPartialBlocks})
            s.features[later] = rng.between(1.0, 1e3);
        s.measuredMs =
            0.3 + 2e-5 * s.features[timemodel::Feature::kTriangles] + 1e-5 * s.features[timemodel::Feature::kPixels];
        s.viewpoint = i % 4;
        (i % 4 == 3 ? heldOut : fit).push_back(s);
    }
    timemodel::DeviceProfile profile;
    profile.created = "2024-01-02T03:04:05Z";
    profile.machine = {"Test CPU", 2, ""};
    profile.glRenderer = "Mesa / llvmpipe (LLVM 15.0.6, 256 bits)";
    profile.glVersion = "4.5 (Core Profile) Mesa 22.3.6";
    profile.width = 512;
    profile.height = 384;
    profile.scene = "harbor";
    profile.seed = 17;
    profile.viewpoints = 4;
    profile.heldOutViewpoints = 1;
    profile.timing.learnedFrom = "cpu";
    profile.timing.learnedScale = 0.5;
    profile.timing.learnRequest = "cpu";
    profile.timing.rounds = 3;
    profile.timing.repeatsPerRound = 2;
    profile.timing.warmup = 1;
    profile.timing.medianSpread = 0.05;
    profile.timing.p90Spread = 0.1;
    profile.timing.seconds = 12.5;
    profile.models = timemodel::fitAllModels(fit, heldOut);
    // The first model with a rotated measurement, the others without (profiles from before it).
    profile.models[0].rotatedErrors = {12, 0.05, 0.04, 0.11, 0.2};
    // Fold (0 = held out), least, least-median, median, cpu (not recorded), wall median, GPU median.
    for (const auto& s : fit)
        profile.samples.push_back({s, false, 1 + s.viewpoint, 0.9 * s.measuredMs, 0.95 * s.measuredMs, s.measuredMs,
                                   0.0, s.measuredMs, 0.5 * s.measuredMs});
    for (const auto& s : heldOut)
        profile.samples.push_back({s, true, 0, 0.9 * s.measuredMs, 0.95 * s.measuredMs, s.measuredMs, 0.0,
                                   s.measuredMs, 0.5 * s.measuredMs});
    return profile;
}

std::string expectProfileError(const std::string& text) {
    try {
        timemodel::profileFromJson(text, "bad.json");
    } catch (const timemodel::ProfileError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no ProfileError";
    return "";
}

}  // namespace

TEST(Profile, RoundTripsThroughJsonAndAFile) {
    const timemodel::DeviceProfile profile = sampleProfile();
    const auto path = std::filesystem::temp_directory_path() / "lodopt-timemodel-profile-test.json";
    timemodel::saveProfile(path.string(), profile);
    const timemodel::DeviceProfile loaded = timemodel::loadProfile(path.string());
    std::filesystem::remove(path);
    EXPECT_EQ(loaded.created, profile.created);
    EXPECT_EQ(loaded.machine.cpuModel, "Test CPU");
    EXPECT_EQ(loaded.glRenderer, profile.glRenderer);
    EXPECT_EQ(loaded.width, 512);
    EXPECT_EQ(loaded.height, 384);
    EXPECT_EQ(loaded.seed, 17u);
    EXPECT_EQ(loaded.timing.rounds, 3);
    EXPECT_EQ(loaded.timing.learnedFrom, "cpu");
    EXPECT_EQ(loaded.timing.learnedScale, 0.5);
    EXPECT_EQ(loaded.timing.learnRequest, "cpu");
    EXPECT_EQ(loaded.timing.predicts, "median");
    EXPECT_EQ(loaded.timing.frameClock, "wall");
    ASSERT_EQ(loaded.models.size(), profile.models.size());
    for (std::size_t m = 0; m < loaded.models.size(); ++m) {
        EXPECT_EQ(loaded.models[m].name, profile.models[m].name);
        EXPECT_EQ(loaded.models[m].fitted, profile.models[m].fitted);
        ASSERT_EQ(loaded.models[m].coefficients.size(), profile.models[m].coefficients.size());
        for (std::size_t c = 0; c < loaded.models[m].coefficients.size(); ++c) {
            EXPECT_DOUBLE_EQ(loaded.models[m].coefficients[c], profile.models[m].coefficients[c]);
        }
        EXPECT_DOUBLE_EQ(loaded.models[m].heldOutErrors.p90, profile.models[m].heldOutErrors.p90);
        EXPECT_EQ(loaded.models[m].rotatedErrors.count, profile.models[m].rotatedErrors.count);
        EXPECT_DOUBLE_EQ(loaded.models[m].rotatedErrors.p90, profile.models[m].rotatedErrors.p90);
    }
    EXPECT_EQ(loaded.models[0].rotatedErrors.count, 12u);
    EXPECT_EQ(loaded.models[1].rotatedErrors.count, 0u);
    ASSERT_EQ(loaded.samples.size(), profile.samples.size());
    EXPECT_DOUBLE_EQ(loaded.samples[5].sample.measuredMs, profile.samples[5].sample.measuredMs);
    EXPECT_DOUBLE_EQ(loaded.samples[5].wallMedianMs, profile.samples[5].wallMedianMs);
    EXPECT_DOUBLE_EQ(loaded.samples[5].gpuMedianMs, profile.samples[5].gpuMedianMs);
    EXPECT_EQ(loaded.samples[5].fold, profile.samples[5].fold);
    EXPECT_EQ(timemodel::profileFolds(loaded)[5], profile.samples[5].fold);
    EXPECT_EQ(loaded.samples[5].cpuMs, 0.0);  // not recorded
    for (const std::string& statistic : timemodel::timingStatisticNames()) {
        EXPECT_EQ(timemodel::timeOfStatistic(loaded.samples[5], statistic),
                  timemodel::timeOfStatistic(profile.samples[5], statistic))
            << statistic;
    }
    EXPECT_DOUBLE_EQ(timemodel::timeOfStatistic(loaded.samples[5], "least-median"), loaded.samples[5].leastMedianMs);
    EXPECT_DOUBLE_EQ(timemodel::timeOfStatistic(loaded.samples[5], "least"), 0.9 * loaded.samples[5].medianMs);
    EXPECT_EQ(timemodel::timeOfStatistic(loaded.samples[5], "wall-min"), 0.0);  // older names are the file's only
    // The model built from the file predicts what the fitted one did.
    const auto model = timemodel::modelFromProfile(loaded);
    EXPECT_EQ(model->name(), "linear");
    const timemodel::Sample& s = profile.samples[0].sample;
    EXPECT_NEAR(model->estimateMs(s.features), s.measuredMs, 1e-6);
    EXPECT_EQ(timemodel::modelFromProfile(loaded, "wimmer")->name(), "wimmer");
}

TEST(Profile, BadFilesGiveMessagesNamingTheFileAndField) {
    EXPECT_NE(expectProfileError("{not json").find("bad.json: not valid JSON"), std::string::npos);
    EXPECT_NE(expectProfileError("{\"format\": \"other\"}").find("format"), std::string::npos);
    std::string text = timemodel::profileToJson(sampleProfile());
    const std::string key = "\"triangles\":";
    std::string missing = text;
    missing.replace(missing.find(key), key.size(), "\"triangle\":");
    const std::string message = expectProfileError(missing);
    EXPECT_NE(message.find("models[0].coefficients.triangles: missing"), std::string::npos) << message;
    std::string wrongType = text;
    wrongType.replace(wrongType.find("\"width\": 512"), 12, "\"width\": \"x\"");
    EXPECT_NE(expectProfileError(wrongType).find("render_size.width"), std::string::npos);
    EXPECT_THROW(timemodel::loadProfile("/nonexistent/profile.json"), timemodel::ProfileError);
    EXPECT_THROW(timemodel::modelFromProfile(sampleProfile(), "nosuch"), timemodel::ProfileError);
}

TEST(Profile, WarnsWhenRendererSizeOrMachineDiffer) {
    const timemodel::DeviceProfile profile = sampleProfile();
    EXPECT_TRUE(timemodel::profileWarnings(profile, profile.glRenderer, 512, 384, profile.machine, profile.shading).empty());
    EXPECT_EQ(timemodel::profileWarnings(profile, "NVIDIA / RTX", 512, 384, profile.machine, profile.shading).size(), 1u);
    EXPECT_EQ(timemodel::profileWarnings(profile, profile.glRenderer, 1024, 384, profile.machine, profile.shading).size(), 1u);
    EXPECT_EQ(timemodel::profileWarnings(profile, "", 512, 384, {"Other CPU", 64, ""}, profile.shading).size(), 1u);
    const std::string otherShading = profile.shading == "pbr" ? "lambert" : "pbr";
    EXPECT_EQ(timemodel::profileWarnings(profile, profile.glRenderer, 512, 384, profile.machine, otherShading).size(), 1u);
    // llvmpipe's thread count: calibrated with LP_NUM_THREADS=1, used without it.
    timemodel::DeviceProfile oneThread = profile;
    oneThread.machine.llvmpipeThreads = "1";
    const std::vector<std::string> warnings =
        timemodel::profileWarnings(oneThread, profile.glRenderer, 512, 384, profile.machine, profile.shading);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("LP_NUM_THREADS 1, this process has unset"), std::string::npos) << warnings[0];
    EXPECT_TRUE(timemodel::profileWarnings(oneThread, profile.glRenderer, 512, 384, oneThread.machine, profile.shading).empty());
    // Timed on a GPU's timer, used where frames are timed on the wall clock.
    timemodel::DeviceProfile gpu = profile;
    gpu.timing.frameClock = "gpu";
    const std::vector<std::string> clock =
        timemodel::profileWarnings(gpu, profile.glRenderer, 512, 384, profile.machine, profile.shading, "wall");
    ASSERT_EQ(clock.size(), 1u);
    EXPECT_NE(clock[0].find("gpu clock, this renderer on the wall clock"), std::string::npos) << clock[0];
    EXPECT_TRUE(timemodel::profileWarnings(gpu, profile.glRenderer, 512, 384, profile.machine, profile.shading, "gpu").empty());
    // A profile calibrated while the machine's speed drifted: calibrate said so; its users do not.
    timemodel::DeviceProfile drifted = profile;
    drifted.timing.passDrift = 0.32;
    EXPECT_TRUE(timemodel::profileWarnings(drifted, profile.glRenderer, 512, 384, profile.machine, profile.shading).empty());
    EXPECT_NE(timemodel::calibrationDriftWarning(0.32).find("moved by 32% between the calibration's passes"),
              std::string::npos);
}

TEST(Profile, RecordsThePassDriftAndTheSpeedAnchorAndReadsOlderFilesWithout) {
    timemodel::DeviceProfile profile = sampleProfile();
    profile.timing.passDrift = 0.125;
    const std::string text = timemodel::profileToJson(profile);
    EXPECT_EQ(timemodel::profileFromJson(text, "p.json").timing.passDrift, 0.125);
    std::string older = text;
    const std::string field = "\"pass_drift\": 0.125,";
    const std::size_t at = older.find(field);
    ASSERT_NE(at, std::string::npos) << text.substr(0, 1200);
    older.erase(at, field.size());
    EXPECT_EQ(timemodel::profileFromJson(older, "p.json").timing.passDrift, 0.0);
    // The speed anchor likewise: recorded, and absent from older files.
    profile.timing.anchorView = "overview";
    profile.timing.anchorMs = 7.5;
    const std::string anchored = timemodel::profileToJson(profile);
    const timemodel::DeviceProfile read = timemodel::profileFromJson(anchored, "p.json");
    EXPECT_EQ(read.timing.anchorView, "overview");
    EXPECT_EQ(read.timing.anchorMs, 7.5);
    std::string unanchored = anchored;
    for (const std::string& field : {std::string("\"anchor_ms\": 7.5,"), std::string("\"anchor_view\": \"overview\",")}) {
        const std::size_t where = unanchored.find(field);
        ASSERT_NE(where, std::string::npos) << field;
        unanchored.erase(where, field.size());
    }
    EXPECT_EQ(timemodel::profileFromJson(unanchored, "p.json").timing.anchorMs, 0.0);
    EXPECT_TRUE(timemodel::profileFromJson(unanchored, "p.json").timing.anchorView.empty());
    std::string negative = text;
    negative.replace(negative.find("0.125"), 5, "-0.10");
    try {
        timemodel::profileFromJson(negative, "p.json");
        ADD_FAILURE() << "a negative drift was read";
    } catch (const timemodel::ProfileError& error) {
        EXPECT_NE(std::string(error.what()).find("pass_drift"), std::string::npos) << error.what();
    }
}

TEST(Profile, RecordsTheRasterizerThreadsAndReadsOlderFilesWithout) {
    timemodel::DeviceProfile profile = sampleProfile();
    profile.machine.llvmpipeThreads = "1";
    const std::string text = timemodel::profileToJson(profile);
    EXPECT_EQ(timemodel::profileFromJson(text, "p.json").machine.llvmpipeThreads, "1");
    // A profile written before the field existed: unset.
    std::string older = text;
    const std::string field = ",\n    \"lp_num_threads\": \"1\"";
    const std::size_t at = older.find(field);
    ASSERT_NE(at, std::string::npos) << text.substr(0, 400);
    older.erase(at, field.size());
    EXPECT_EQ(timemodel::profileFromJson(older, "p.json").machine.llvmpipeThreads, "");
    std::string wrongType = text;
    const std::string asText = "\"lp_num_threads\": \"1\"";
    wrongType.replace(wrongType.find(asText), asText.size(), "\"lp_num_threads\": 1");
    EXPECT_NE(expectProfileError(wrongType).find("machine.lp_num_threads"), std::string::npos);
}

TEST(Profile, ReadsFilesWrittenBeforeTheMedianWasThePredictedQuantity) {
    nlohmann::json document = nlohmann::json::parse(timemodel::profileToJson(sampleProfile()));
    EXPECT_EQ(document["calibration"]["timing"]["predicts"], "median");
    EXPECT_EQ(document["calibration"]["timing"]["learned_scale"], 0.5);
    // What such a file held: one "clock", fitted and predicted, samples on the wall clock's names.
    nlohmann::json& timing = document["calibration"]["timing"];
    for (const char* key : {"predicts", "frame_clock", "learned_from", "learned_scale", "learn_request"}) timing.erase(key);
    timing["clock"] = "wall-min";
    timing["clock_request"] = "auto";
    for (nlohmann::json& sample : document["samples"]) {
        sample["wall_min_ms"] = sample["least_ms"];
        sample["wall_min_median_ms"] = sample["least_median_ms"];
        for (const char* key : {"least_ms", "least_median_ms", "median_ms", "gpu_median_ms", "fold"}) sample.erase(key);
    }
    const timemodel::DeviceProfile older = timemodel::profileFromJson(document.dump(), "old.json");
    EXPECT_EQ(older.timing.learnedFrom, "least");
    EXPECT_EQ(older.timing.predicts, "least");
    EXPECT_EQ(older.timing.learnedScale, 1.0);
    EXPECT_EQ(older.timing.frameClock, "wall");
    EXPECT_EQ(older.timing.learnRequest, "auto");
    const timemodel::DeviceProfile current = sampleProfile();
    EXPECT_DOUBLE_EQ(older.samples[3].leastMs, current.samples[3].leastMs);
    EXPECT_DOUBLE_EQ(older.samples[3].medianMs, current.samples[3].wallMedianMs);
    EXPECT_EQ(older.samples[3].gpuMedianMs, 0.0);
    // It predicts the least, not the median every command measures: a warning says so.
    const std::vector<std::string> warnings =
        timemodel::profileWarnings(older, older.glRenderer, 512, 384, older.machine, older.shading);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("predicts the least"), std::string::npos) << warnings[0];
    // Held-out samples in fold 0, one fold per fitting viewpoint (viewpoints 0, 1, 2 here).
    const std::vector<int> folds = timemodel::profileFolds(older);
    for (std::size_t i = 0; i < folds.size(); ++i) {
        EXPECT_EQ(folds[i], older.samples[i].heldOut ? 0 : 1 + older.samples[i].sample.viewpoint) << i;
    }
    // --refit: the same samples, now predicting the median; learned from the least, scaled by
    // median / least = 1 / 0.9.
    timemodel::DeviceProfile refitted = older;
    const timemodel::ProfileFit fit = timemodel::refitProfile(refitted, "least");
    EXPECT_EQ(refitted.timing.predicts, "median");
    EXPECT_EQ(refitted.timing.learnedFrom, "least");
    EXPECT_NEAR(refitted.timing.learnedScale, 1.0 / 0.9, 1e-12);
    EXPECT_EQ(fit.choice.candidates.size(), 3u);
    EXPECT_TRUE(timemodel::profileWarnings(refitted, older.glRenderer, 512, 384, older.machine, older.shading).empty());
    const auto model = timemodel::modelFromProfile(refitted);
    const timemodel::ProfileSample& any = refitted.samples[2];
    EXPECT_NEAR(model->estimateMs(any.sample.features), any.medianMs, 1e-6 * any.medianMs);
    EXPECT_EQ(any.sample.measuredMs, any.medianMs);
    EXPECT_EQ(timemodel::profileFolds(timemodel::profileFromJson(timemodel::profileToJson(refitted), "r.json")), folds);
    timing["clock"] = "wall-fastest";
    EXPECT_NE(expectProfileError(document.dump()).find("calibration.timing.clock"), std::string::npos);
    timing["clock"] = "wall-min";
    timing["clock_request"] = 3;
    EXPECT_NE(expectProfileError(document.dump()).find("calibration.timing.clock_request"), std::string::npos);
}

TEST(Profile, ReadsFilesWrittenBeforeTheNewerFeatures) {
    const timemodel::DeviceProfile profile = sampleProfile();
    nlohmann::json document = nlohmann::json::parse(timemodel::profileToJson(profile));
    // What such a file looked like: the features added since the first profiles absent everywhere.
    const std::vector<std::string> newer = {"textured_pixels", "shaded_edge_pixels", "partial_blocks",
                                            "shaded_partial_blocks"};
    std::vector<std::size_t> positions;
    nlohmann::json names = nlohmann::json::array();
    for (std::size_t i = 0; i < document["feature_names"].size(); ++i) {
        const std::string name = document["feature_names"][i];
        if (std::find(newer.begin(), newer.end(), name) != newer.end())
            positions.push_back(i);
        else
            names.push_back(name);
    }
    ASSERT_EQ(positions.size(), newer.size());
    document["feature_names"] = names;
    for (auto& model : document["models"]) {
        for (const std::string& name : newer) model["coefficients"].erase(name);
    }
    for (auto& sample : document["samples"]) {
        nlohmann::json kept = nlohmann::json::array();
        for (std::size_t i = 0; i < sample["features"].size(); ++i) {
            if (std::find(positions.begin(), positions.end(), i) == positions.end())
                kept.push_back(sample["features"][i]);
        }
        sample["features"] = kept;
    }
    const timemodel::DeviceProfile older = timemodel::profileFromJson(document.dump(), "older.json");
    ASSERT_EQ(older.samples.size(), profile.samples.size());
    for (std::size_t i = 0; i < older.samples.size(); ++i) {
        for (timemodel::Feature feature : timemodel::allFeatures()) {
            const bool isNewer = std::find(newer.begin(), newer.end(), timemodel::featureName(feature)) != newer.end();
            EXPECT_EQ(older.samples[i].sample.features[feature],
                      isNewer ? 0.0 : profile.samples[i].sample.features[feature])
                << timemodel::featureName(feature);
        }
    }
    // The linear model reads the absent coefficients as 0 and keeps the others.
    const auto find = [](const timemodel::DeviceProfile& p) {
        for (const auto& model : p.models) {
            if (model.name == "linear") return model;
        }
        return timemodel::ModelResult{};
    };
    const timemodel::ModelResult before = find(profile), after = find(older);
    ASSERT_EQ(after.coefficients.size(), before.coefficients.size());
    for (std::size_t k = 0; k < after.coefficientNames.size(); ++k) {
        const std::string& name = after.coefficientNames[k];
        const bool isNewer = std::find(newer.begin(), newer.end(), name) != newer.end();
        EXPECT_EQ(after.coefficients[k], isNewer ? 0.0 : before.coefficients[k]) << name;
    }
    // A name it does not know, or one listed twice, is an error naming the entry.
    nlohmann::json unknown = document;
    unknown["feature_names"][0] = "polygons";
    EXPECT_NE(expectProfileError(unknown.dump()).find("feature_names[0]: unknown feature 'polygons'"),
              std::string::npos);
    nlohmann::json twice = document;
    twice["feature_names"][1] = twice["feature_names"][0];
    EXPECT_NE(expectProfileError(twice.dump()).find("listed twice"), std::string::npos);
    // A sample with a value per feature of another version is an error too.
    nlohmann::json shortSample = document;
    shortSample["samples"][0]["features"].erase(0);
    EXPECT_NE(expectProfileError(shortSample.dump()).find("samples[0].features"), std::string::npos);
}

TEST(Profile, DescribesThisMachine) {
    const timemodel::MachineDescription machine = timemodel::describeMachine();
    EXPECT_FALSE(machine.cpuModel.empty());
    EXPECT_GT(machine.cores, 0);
    EXPECT_EQ(timemodel::currentDateUtc().size(), 20u);
}

TEST(ShippedProfiles, ParseAndPredictPositiveTimesForTheirScenes) {
    const std::vector<std::string> scenesWithProfiles = timemodel::shippedProfileScenes();
    if (scenesWithProfiles.empty()) GTEST_SKIP() << "this build ships no profile (timemodel/profiles/ is empty)";
    for (const std::string& name : scenesWithProfiles) {
        bool exact = false;
        const timemodel::DeviceProfile profile = timemodel::shippedProfile(name, &exact);
        EXPECT_TRUE(exact);
        EXPECT_EQ(profile.scene, name);
        if (!scenes::isBuiltinScene(name)) continue;
        const scenes::Scene scene = scenes::makeBuiltinScene(name, profile.sceneSeed);
        for (const std::string& model : timemodel::timeModelNames()) {
            const std::unique_ptr<timemodel::TimeModel> fitted = timemodel::modelFromProfile(profile, model);
            const timemodel::FeatureTable table(scene, scene.views[0], profile.width, profile.height);
            const double ms = fitted->estimateMs(table.features(scenes::referenceCombination(scene)));
            EXPECT_TRUE(std::isfinite(ms)) << name << " " << model;
            // dong's Cramer average may have a negative texture coefficient (clamped to 0 ms);
            // the least-squares models must predict a real cost for the finest frame.
            if (model != "dong")
                EXPECT_GT(ms, 0.0) << name << " " << model;
            else
                EXPECT_GE(ms, 0.0) << name;
        }
    }
}

// A level change applied to a frame's features (FeatureTable::delta, what the scheduler and
// the search's cost keep up to date) predicts what the whole frame's features predict.
TEST(FeatureTable, LevelChangeOnTheFeaturesPredictsTheWholeFrameForEveryModel) {
    const scenes::Scene scene = scenes::makeHarborScene();
    const timemodel::DeviceProfile profile = sampleProfile();
    const timemodel::FeatureTable table(scene, scene.views[1], 256, 256);
    for (const std::string& name : timemodel::timeModelNames()) {
        const std::unique_ptr<timemodel::TimeModel> model = timemodel::modelFromProfile(profile, name);
        scenes::Combination combination = {2, 0, scenes::kNotDrawn};
        const timemodel::FrameFeatures current = table.features(combination);
        for (int object = 0; object < 3; ++object) {
            for (int level = scenes::kNotDrawn; level < 3; ++level) {
                scenes::Combination changed = combination;
                changed[object] = level;
                const double expected = model->estimateMs(table.features(changed));
                EXPECT_NEAR(model->estimateMs(current + table.delta(object, combination[object], level)), expected,
                            1e-9 * std::max(1.0, expected))
                    << name;
            }
        }
        // Finer levels cost more under a fitted model with non-negative coefficients.
        EXPECT_GE(model->estimateMs(table.features(scenes::referenceCombination(scene))),
                  model->estimateMs(table.features(scenes::coarsestCombination(scene))))
            << name;
    }
}

TEST(TimeModel, FeedbackScalesLaterEstimates) {
    const scenes::Scene scene = scenes::makeHarborScene();
    const std::unique_ptr<timemodel::TimeModel> model = timemodel::modelFromProfile(sampleProfile());
    const timemodel::FeatureTable table(scene, scene.views[0], 256, 256);
    const timemodel::FrameFeatures features = table.features(scenes::referenceCombination(scene));
    const double before = model->estimateMs(features);
    model->applyFeedback(features, 2.0 * before);  // the default gain, 0.7
    EXPECT_NEAR(model->estimateMs(features), 1.7 * before, 1e-9 * before);
}
