// The optimizer on real renders: GA-PSO against exhaustive ground truth and against the
// engine-style screen-size baseline, on every harbor view.
#include <gtest/gtest.h>

#include "evaluation/evaluation.hpp"
#include "evaluation/time_cost.hpp"
#include "optimizer/optimizer.hpp"
#include "scenes/builtin.hpp"

using namespace lodopt;

namespace {

// A fixed, plausible cost: 0.4 ms per frame, 0.15 ms per 1000 triangles, 0.02 ms per draw call.
double syntheticMs(const timemodel::FrameFeatures& f) {
    return 0.4 + 0.15e-3 * f[timemodel::Feature::kTriangles] + 0.02 * f[timemodel::Feature::kDrawCalls];
}

struct HarborView {
    scenes::Scene scene = scenes::makeHarborScene();
    std::unique_ptr<renderer::Renderer> renderer;
    std::unique_ptr<evaluation::ViewSetup> setup;
    std::unique_ptr<evaluation::LayerEvaluator> evaluator;
    std::unique_ptr<evaluation::TimeModelCost> cost;
    optimizer::Problem problem;

    HarborView(int view, double budgetFraction) {
        renderer::RenderSettings settings;
        settings.width = settings.height = 160;
        renderer = std::make_unique<renderer::Renderer>(scene, settings);
        setup = std::make_unique<evaluation::ViewSetup>(scene, scene.views[view], *renderer);
        evaluator = std::make_unique<evaluation::LayerEvaluator>(*setup, metrics::MetricParameters{}, 2);
        cost = std::make_unique<evaluation::TimeModelCost>(*setup, syntheticMs);
        problem.levelCounts = setup->levelCounts();
        problem.evaluator = evaluator.get();
        problem.cost = cost.get();
        const double finest = cost->predictMs(optimizer::finestCombination(problem));
        const double coarsest = cost->predictMs(optimizer::coarsestCombination(problem));
        problem.budgetMs = coarsest + budgetFraction * (finest - coarsest);
        problem.hints = evaluation::computeHints(*setup);
    }
};

}  // namespace

TEST(OptimizeIntegration, GapsoFindsTheExhaustiveOptimumOnHarbor) {
    HarborView harbor(0, 0.45);
    optimizer::Result truth = optimizer::makeAlgorithm("exhaustive")->run(harbor.problem, optimizer::Termination{});
    ASSERT_LE(truth.predictedMs, harbor.problem.budgetMs);
    int hits = 0;
    std::vector<int> iterationsToOptimum;
    for (std::uint64_t seed = 1; seed <= 10; ++seed) {
        optimizer::Termination termination;
        termination.maxIterations = 30;
        termination.stableIterations = 0;
        optimizer::Result result = optimizer::makeAlgorithm("gapso", seed)->run(harbor.problem, termination);
        EXPECT_LE(result.predictedMs, harbor.problem.budgetMs) << "seed " << seed;
        if (result.bestScore.fitness >= truth.bestScore.fitness - 1e-12) {
            ++hits;
            for (const optimizer::IterationLog& row : result.log) {
                if (row.bestFitness >= truth.bestScore.fitness - 1e-12) {
                    iterationsToOptimum.push_back(row.iteration);
                    break;
                }
            }
        }
    }
    std::cout << "gapso reached the exhaustive optimum " << optimizer::formatCombination(truth.best) << " in " << hits
              << "/10 seeds; iterations:";
    for (int it : iterationsToOptimum) std::cout << " " << it;
    std::cout << "\n";
    EXPECT_GE(hits, 9);
}

TEST(OptimizeIntegration, DefaultOptimizerBeatsScreenSizeOnEveryHarborView) {
    for (int view = 0; view < 4; ++view) {
        HarborView harbor(view, 0.4);
        optimizer::Result engine = optimizer::makeAlgorithm("screensize")->run(harbor.problem, optimizer::Termination{});
        optimizer::Termination termination;
        termination.maxIterations = 30;
        optimizer::Result ours = optimizer::makeAlgorithm("gapso", 1)->run(harbor.problem, termination);
        EXPECT_LE(ours.predictedMs, harbor.problem.budgetMs);
        EXPECT_GE(ours.bestScore.fitness, engine.bestScore.fitness) << harbor.scene.views[view].name;
        std::cout << harbor.scene.views[view].name << ": gapso " << ours.bestScore.fitness << " vs screensize "
                  << engine.bestScore.fitness << "\n";
    }
}

TEST(OptimizeIntegration, SameSeedGivesTheSameAnswerWithAnyThreadCount) {
    HarborView two(1, 0.5);
    optimizer::Termination termination;
    termination.maxIterations = 10;
    optimizer::Result a = optimizer::makeAlgorithm("gapso", 7)->run(two.problem, termination);
    evaluation::LayerEvaluator single(*two.setup, metrics::MetricParameters{}, 1);
    optimizer::Problem serial = two.problem;
    serial.evaluator = &single;
    optimizer::Result b = optimizer::makeAlgorithm("gapso", 7)->run(serial, termination);
    EXPECT_EQ(a.best, b.best);
    EXPECT_EQ(a.bestScore.fitness, b.bestScore.fitness);
    ASSERT_EQ(a.log.size(), b.log.size());
    for (std::size_t k = 0; k < a.log.size(); ++k) {
        EXPECT_EQ(a.log[k].bestFitness, b.log[k].bestFitness);
        EXPECT_EQ(a.log[k].meanFitness, b.log[k].meanFitness);
        EXPECT_EQ(a.log[k].evaluations, b.log[k].evaluations);
    }
}
