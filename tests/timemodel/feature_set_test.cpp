// What a model reads (TimeModel::readFeatures) and the FeatureTable built for it: every
// feature in the set exact, the skipped work's features 0, and the model's predictions the same.
#include <gtest/gtest.h>

#include <vector>

#include "scenes/builtin.hpp"
#include "timemodel/calibration.hpp"
#include "timemodel/features.hpp"
#include "timemodel/profile.hpp"
#include "timemodel/time_model.hpp"

using namespace lodopt;
using timemodel::Feature;
using timemodel::FeatureSet;

namespace {

FeatureSet setOf(std::initializer_list<Feature> features) {
    FeatureSet set;
    for (Feature f : features) set.set(std::size_t(f));
    return set;
}

std::unique_ptr<timemodel::TimeModel> linearWith(std::initializer_list<Feature> features) {
    auto model = timemodel::makeTimeModel("linear");
    std::vector<double> coefficients(model->coefficientNames().size(), 0.0);
    coefficients[0] = 0.5;
    for (Feature f : features) coefficients[std::size_t(f) + 1] = 1e-4;
    model->setCoefficients(coefficients);
    return model;
}

const FeatureSet kPartialBlockFeatures = setOf({Feature::kPartialBlocks, Feature::kShadedPartialBlocks});
const FeatureSet kDepthPassFeatures = setOf(
    {Feature::kShadedPixels, Feature::kTexturedPixels, Feature::kShadedEdgePixels, Feature::kShadedPartialBlocks});

}  // namespace

TEST(FeatureSet, EachModelReadsItsOwnFeatures) {
    EXPECT_EQ(linearWith({Feature::kTriangles, Feature::kPartialBlocks})->readFeatures(),
              setOf({Feature::kTriangles, Feature::kPartialBlocks}));
    EXPECT_EQ(linearWith({})->readFeatures().count(), 0u);  // the intercept alone
    auto dong = timemodel::makeTimeModel("dong");
    auto wimmer = timemodel::makeTimeModel("wimmer");
    // Unfitted: everything, so that a table built for an unfitted model is never short.
    EXPECT_TRUE(dong->readFeatures().all());
    EXPECT_TRUE(timemodel::makeTimeModel("linear")->readFeatures().all());
    dong->setCoefficients({1e-4, 1e-7});
    EXPECT_EQ(dong->readFeatures(), setOf({Feature::kTriangles, Feature::kTextureBytes}));
    wimmer->setCoefficients(std::vector<double>(wimmer->coefficientNames().size(), 1e-3));
    EXPECT_EQ(wimmer->readFeatures(), setOf({Feature::kVertices, Feature::kPixels, Feature::kMatrices,
                                             Feature::kBoundingBoxes, Feature::kDrawCalls}));
    // Feedback scales every coefficient alike: the set stays.
    auto linear = linearWith({Feature::kEdgePixels});
    linear->applyFeedback(timemodel::FrameFeatures{}, 2.0);
    EXPECT_EQ(linear->readFeatures(), setOf({Feature::kEdgePixels}));
}

TEST(FeatureSet, ATableBuiltForASetIsExactOnItAndSkipsOnlyWorkOutsideIt) {
    const scenes::Scene scene = scenes::makeBuiltinScene("harbor", 1);
    const std::vector<FeatureSet> sets = {
        FeatureSet(),                                           // nothing: no depth pass, no blocks
        setOf({Feature::kTriangles, Feature::kTextureBytes}),   // dong
        setOf({Feature::kPartialBlocks}),                       // blocks without the depth pass
        setOf({Feature::kShadedPixels, Feature::kEdgePixels}),  // the depth pass without blocks
        timemodel::everyFeature() & ~kPartialBlockFeatures,     // all but the blocks
    };
    for (const scenes::Camera& camera : scene.views) {
        const timemodel::FeatureTable full(scene, camera, 160, 120);
        for (const FeatureSet& set : sets) {
            const timemodel::FeatureTable table(scene, camera, 160, 120, timemodel::FeatureTable::kDepthPassCells, set);
            const bool blocks = (set & kPartialBlockFeatures).any();
            const bool depthPass = (set & kDepthPassFeatures).any();
            double skippedSeen = 0.0;  // what the skipped work gives in the full table
            for (int o = 0; o < full.objectCount(); ++o) {
                for (int l = 0; l < full.levelCount(o); ++l) {
                    for (Feature f : timemodel::allFeatures()) {
                        const double exact = full.contribution(o, l)[f], got = table.contribution(o, l)[f];
                        const bool skipped = (kPartialBlockFeatures.test(std::size_t(f)) && !blocks) ||
                                             (kDepthPassFeatures.test(std::size_t(f)) && !depthPass);
                        if (skipped) {
                            EXPECT_EQ(got, 0.0) << timemodel::featureName(f);
                            skippedSeen += exact;
                        } else {
                            EXPECT_EQ(got, exact) << timemodel::featureName(f) << " object " << o << " level " << l;
                        }
                    }
                }
            }
            if (!blocks || !depthPass) {
                EXPECT_GT(skippedSeen, 0.0);  // the skip left something out
            }
            EXPECT_EQ(table.frameConstant()[Feature::kBoundingBoxes], full.frameConstant()[Feature::kBoundingBoxes]);
        }
    }
}

TEST(FeatureSet, EveryModelOfEveryShippedProfilePredictsTheSameFromItsTable) {
    const std::vector<std::string> names = timemodel::shippedProfileScenes();
    if (names.empty()) GTEST_SKIP() << "this build ships no profile (timemodel/profiles/ is empty)";
    for (const std::string& name : names) {
        if (!scenes::isBuiltinScene(name)) continue;
        const timemodel::DeviceProfile profile = timemodel::shippedProfile(name);
        const scenes::Scene scene = scenes::makeBuiltinScene(name, profile.sceneSeed);
        const scenes::Camera& camera = scene.views.front();
        const timemodel::FeatureTable full(scene, camera, profile.width / 4, profile.height / 4);
        timemodel::SplitMix64 rng(7);
        for (const std::string& modelName : timemodel::timeModelNames()) {
            const auto model = timemodel::modelFromProfile(profile, modelName);
            const timemodel::FeatureTable table(scene, camera, profile.width / 4, profile.height / 4,
                                                timemodel::FeatureTable::kDepthPassCells, model->readFeatures());
            for (int trial = 0; trial < 20; ++trial) {
                scenes::Combination combination(scene.objects.size());
                for (std::size_t o = 0; o < combination.size(); ++o)
                    combination[o] = rng.below(int(scene.objects[o].levels.size()) + 1) - 1;  // kNotDrawn = -1
                EXPECT_EQ(model->estimateMs(table.features(combination)), model->estimateMs(full.features(combination)))
                    << name << " " << modelName;
            }
        }
    }
}
