// Numerical and structural edges of the evaluation + search (issue #9), on hand-made scenes
// small enough to work out by hand: an object without triangles, everything off screen, a
// scene without objects, one object with one level, identical levels, a budget below the
// minimum or above the maximum, and fitness ties. docs/robustness.md states the behaviour
// each test pins.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "optimizer/optimizer.hpp"
#include "scenes/geometric_error.hpp"
#include "scenes/mesh_builder.hpp"

using namespace lodopt;

namespace {

scenes::Mesh boxMesh(glm::vec3 center, glm::vec3 halfExtents, int material) {
    scenes::MeshBuilder builder(material);
    builder.addBox(center, halfExtents);
    return builder.finish();
}

scenes::Level levelOf(std::vector<scenes::Mesh> meshes) {
    scenes::Level level;
    level.meshes = std::move(meshes);
    return level;
}

scenes::Object objectAt(const std::string& name, glm::vec3 position, std::vector<scenes::Level> levels) {
    scenes::Object object;
    object.name = name;
    object.transform = glm::translate(glm::mat4(1.0f), position);
    object.levels = std::move(levels);
    return object;
}

// Camera at z = 10 looking at the origin, 60° field of view.
scenes::Scene emptyScene() {
    scenes::Scene scene;
    scene.name = "edges";
    scene.materials.push_back(scenes::diffuseMaterial("red", {0.8f, 0.2f, 0.2f}));
    scene.materials.push_back(scenes::diffuseMaterial("grey", {0.5f, 0.5f, 0.5f}));
    scenes::Camera camera;
    camera.name = "front";
    camera.position = {0, 0, 10};
    camera.target = {0, 0, 0};
    camera.fovYDegrees = 60.0f;
    camera.nearPlane = 0.1f;
    camera.farPlane = 100.0f;
    scene.views.push_back(camera);
    return scene;
}

renderer::RenderSettings settingsOf(int size) {
    renderer::RenderSettings settings;
    settings.width = settings.height = size;
    return settings;
}

// 1 ms per frame plus 1 µs per triangle drawn.
double trianglesMs(const timemodel::FrameFeatures& features) {
    return 1.0 + features[timemodel::Feature::kTriangles] * 1e-3;
}

// Everything prepareView() in the CLI builds for a view.
struct Prepared {
    scenes::Scene scene;
    renderer::Renderer renderer;
    evaluation::ViewSetup setup;
    evaluation::LayerEvaluator evaluator;
    evaluation::TimeModelCost cost;
    optimizer::Problem problem;

    Prepared(scenes::Scene s, int size, double budgetMs)
        : scene((scenes::updateStatistics(s), std::move(s))),
          renderer(scene, settingsOf(size)),
          setup(scene, scene.views[0], renderer),
          evaluator(setup, metrics::MetricParameters{}, 2),
          cost(setup, &trianglesMs) {
        problem.levelCounts = setup.levelCounts();
        problem.evaluator = &evaluator;
        problem.cost = &cost;
        problem.budgetMs = budgetMs;
        if (!problem.levelCounts.empty()) {
            problem.hints = evaluation::computeHints(setup);
            optimizer::CheckedEvaluator checked(problem);
            problem.surrogateLoss = optimizer::measureSurrogateLoss(problem, checked);
        }
    }
};

optimizer::Termination shortRun() {
    optimizer::Termination termination;
    termination.maxIterations = 10;
    termination.stableIterations = 5;
    return termination;
}

}  // namespace

// An object whose levels hold no triangle (an empty mesh, no mesh at all) is uploaded as
// nothing, covers no pixel and is skipped like an object smaller than a pixel; the other
// object is searched as usual.
TEST(EdgeCases, ObjectWithoutTrianglesIsSkippedNotDrawn) {
    scenes::Scene scene = emptyScene();
    scenes::Mesh empty;
    empty.material = 0;
    scene.objects.push_back(objectAt("nothing", {0, 0, 0}, {levelOf({empty}), levelOf({})}));
    scene.objects.push_back(
        objectAt("box", {0, 0, 0}, {levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 0)}), levelOf({boxMesh({0, 0, 0}, {0.5f, 0.5f, 0.5f}, 0)})}));
    Prepared prepared(scene, 64, 1000.0);
    const auto& objects = prepared.setup.objects();
    EXPECT_NE(objects[0].skip, evaluation::SkipReason::None);
    EXPECT_EQ(objects[0].referencePixels, 0u);
    EXPECT_EQ(objects[1].skip, evaluation::SkipReason::None);
    EXPECT_EQ(prepared.setup.levelCounts(), (std::vector<int>{2}));
    const optimizer::Result result = optimizer::makeAlgorithm("exhaustive")->run(prepared.problem, optimizer::Termination::none());
    EXPECT_EQ(result.best, (optimizer::Combination{0}));
    EXPECT_DOUBLE_EQ(result.bestScore.fitness, 1.0);
}

// Every object behind the camera: nothing to search. The reference is the clear color alone,
// the empty combination scores a perfect 1, and the cost is the fixed frame cost.
TEST(EdgeCases, AllObjectsOffScreenLeaveNothingToSearch) {
    scenes::Scene scene = emptyScene();
    scene.objects.push_back(objectAt("behind", {0, 0, 30}, {levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 0)})}));
    scene.objects.push_back(objectAt("left", {-400, 0, 0}, {levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 1)})}));
    Prepared prepared(scene, 48, 1000.0);
    EXPECT_TRUE(prepared.setup.levelCounts().empty());
    EXPECT_EQ(prepared.setup.skipSummary().outsideFrustum, 2);
    EXPECT_EQ(prepared.setup.skipSummary().searchedObjects, 0);
    const optimizer::Score score = prepared.evaluator.evaluate({});
    EXPECT_DOUBLE_EQ(score.fitness, 1.0);
    // Skipped objects stay in the frame at their coarsest level: the cost still counts them.
    EXPECT_DOUBLE_EQ(prepared.cost.predictMs({}), prepared.cost.predictSceneMs({0, 0}));
    EXPECT_GE(prepared.cost.predictMs({}), 1.0);
    // The reference holds only the clear color.
    std::uint8_t clear[4];
    renderer::clearColorBytes(prepared.setup.clearColor(), clear);
    const std::vector<std::uint8_t>& rgba = prepared.setup.reference().rgba;
    for (std::size_t i = 0; i < rgba.size(); i += 4) ASSERT_EQ(rgba[i], clear[0]) << i;
    // An optimizer::Problem needs one variable: the CLI answers the fixed combination itself
    // (cli/src/optimize_run.cpp); validateProblem refuses an empty one by name.
    EXPECT_THROW(optimizer::validateProblem(prepared.problem), optimizer::ProblemError);
}

// A scene with no objects at all renders the background and has nothing to search; the CLI
// refuses it before (exit 2, "has no objects", tests/cli/robustness_test.cpp).
TEST(EdgeCases, SceneWithoutObjectsIsTheBackground) {
    Prepared prepared(emptyScene(), 32, 1000.0);
    EXPECT_TRUE(prepared.setup.levelCounts().empty());
    EXPECT_DOUBLE_EQ(prepared.evaluator.evaluate({}).fitness, 1.0);
    EXPECT_EQ(prepared.setup.toScene({}), scenes::Combination{});
}

// One object with one level: one variable with one option. Every algorithm returns it.
TEST(EdgeCases, OneObjectWithOneLevelEveryAlgorithmReturnsIt) {
    scenes::Scene scene = emptyScene();
    scene.objects.push_back(objectAt("only", {0, 0, 0}, {levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 0)})}));
    scenes::computeGeometricErrors(scene);  // what the engines' rules read
    Prepared prepared(scene, 48, 1000.0);
    ASSERT_EQ(prepared.problem.levelCounts, (std::vector<int>{1}));
    for (const std::string& name : optimizer::algorithmNames()) {
        const optimizer::Result result = optimizer::makeAlgorithm(name, 3)->run(prepared.problem, shortRun());
        EXPECT_EQ(result.best, (optimizer::Combination{0})) << name;
        EXPECT_DOUBLE_EQ(result.bestScore.fitness, 1.0) << name;
        EXPECT_LE(result.predictedMs, prepared.problem.budgetMs) << name;
    }
}

// Three bit-identical levels are merged into the coarsest (cheapest) one: a single option that
// the search never has to tell apart from its copies.
TEST(EdgeCases, IdenticalLevelsMergeIntoTheCoarsest) {
    scenes::Scene scene = emptyScene();
    const scenes::Level same = levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 0)});
    scene.objects.push_back(objectAt("copies", {0, 0, 0}, {same, same, same}));
    Prepared prepared(scene, 48, 1000.0);
    const evaluation::ObjectSetup& object = prepared.setup.objects()[0];
    EXPECT_EQ(object.optionLevels, (std::vector<int>{2}));
    EXPECT_EQ(object.mergedLevels, 2);
    EXPECT_EQ(prepared.setup.toScene({0}), (scenes::Combination{2}));
}

// Budget below the cheapest combination: BudgetError stating both figures (the CLI exits 2
// with this message). Above the most expensive one: the reference combination, fitness 1.
TEST(EdgeCases, BudgetBelowTheMinimumOrAboveTheMaximum) {
    scenes::Scene scene = emptyScene();
    scene.objects.push_back(objectAt("a", {-2, 0, 0}, {levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 0)}),
                                                       levelOf({boxMesh({0, 0, 0}, {0.7f, 0.7f, 0.7f}, 0)})}));
    scene.objects.push_back(objectAt("b", {2, 0, 0}, {levelOf({boxMesh({0, 0, 0}, {1, 1, 1}, 1)}),
                                                      levelOf({boxMesh({0, 0, 0}, {0.6f, 0.6f, 0.6f}, 1)})}));
    Prepared below(scene, 48, 0.5);  // the frame alone costs 1 ms
    const double minimum = below.cost.predictMs(optimizer::coarsestCombination(below.problem));
    for (const std::string name : {"gapso", "greedy", "mckp", "exhaustive"}) {
        try {
            optimizer::makeAlgorithm(name)->run(below.problem, shortRun());
            ADD_FAILURE() << name << " ran with a budget below the minimum";
        } catch (const optimizer::BudgetError& error) {
            EXPECT_EQ(error.minimumMs(), minimum) << name;
            EXPECT_EQ(error.budgetMs(), 0.5) << name;
            EXPECT_NE(std::string(error.what()).find("below the cheapest combination"), std::string::npos);
        }
    }
    for (double budget : {1e9, std::numeric_limits<double>::infinity()}) {
        Prepared above(scene, 48, budget);
        for (const std::string name : {"gapso", "greedy", "mckp", "exhaustive", "random"}) {
            const optimizer::Result result = optimizer::makeAlgorithm(name, 2)->run(above.problem, shortRun());
            EXPECT_EQ(result.best, (optimizer::Combination{0, 0})) << name << " budget " << budget;
            EXPECT_DOUBLE_EQ(result.bestScore.fitness, 1.0) << name;
        }
    }
}

// A fitness tie: "hidden" has two levels that differ only behind the wall, so both composite
// to the same image and score the same; the finer one costs 20 triangles more. The documented
// tie-break (higher fitness, then lower predicted time, then the smaller combination) picks
// the cheaper level, whatever the thread count.
//
//   camera (z=10) ──►  wall (z=0, 3x3, in front)   hidden (z=-3): a box half out from
//                                                   behind the wall; level 0 adds a second
//                                                   box entirely behind the wall
TEST(EdgeCases, FitnessTiesGoToTheCheaperCombination) {
    scenes::Scene scene = emptyScene();
    scene.objects.push_back(objectAt("wall", {0, 0, 0}, {levelOf({boxMesh({0, 0, 0}, {1.5f, 1.5f, 0.1f}, 1)})}));
    const scenes::Mesh visiblePart = boxMesh({2.0f, 0, 0}, {1.0f, 0.5f, 0.5f}, 0);
    const scenes::Mesh hiddenPart = boxMesh({0, 0, 0}, {0.5f, 0.5f, 0.5f}, 0);
    scene.objects.push_back(objectAt("hidden", {0, 0, -3}, {levelOf({visiblePart, hiddenPart}), levelOf({visiblePart})}));
    for (int threads : {1, 2}) {
        scenes::updateStatistics(scene);
        Prepared prepared(scene, 64, 1000.0);
        ASSERT_EQ(prepared.setup.objects()[1].optionLevels, (std::vector<int>{0, 1}))
            << "the levels differ as layers, so they are not merged";
        const int variable = prepared.setup.levelCounts().size() == 2 ? 1 : 0;
        optimizer::Combination fine(prepared.setup.levelCounts().size(), 0), coarse = fine;
        coarse[variable] = 1;
        EXPECT_EQ(prepared.evaluator.evaluate(fine).fitness, prepared.evaluator.evaluate(coarse).fitness);
        EXPECT_LT(prepared.cost.predictMs(coarse), prepared.cost.predictMs(fine));
        evaluation::LayerEvaluator evaluator(prepared.setup, metrics::MetricParameters{}, threads);
        prepared.problem.evaluator = &evaluator;
        for (const std::string name : {"exhaustive", "greedy", "gapso"}) {
            const optimizer::Result result = optimizer::makeAlgorithm(name, 1)->run(prepared.problem, shortRun());
            EXPECT_EQ(result.best, coarse) << name << " threads " << threads;
        }
    }
}
