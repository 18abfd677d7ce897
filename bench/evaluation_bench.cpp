// Fast (layers + incremental metrics) vs full (render + metrics) evaluation, per scene at 512².
// Run: build/bench/evaluation_bench --benchmark_min_time=1 --benchmark_repetitions=5
// Reported: evaluations per second (items_per_second, from wall time) of each path on the same
// candidates, and CPU time of the whole process (the full path rasterizes in llvmpipe's
// threads); the ratio fast/full is the figure docs/optimizer.md records.
// fast_path_bounds re-scores whole object rectangles (DirtyRegions::ObjectBounds), the earlier
// fast path, so both can be compared in one run.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "evaluation/evaluation.hpp"
#include "scenes/builtin.hpp"

using namespace lodopt;

namespace {

struct Prepared {
    scenes::Scene scene;
    std::unique_ptr<renderer::Renderer> renderer;
    std::unique_ptr<evaluation::ViewSetup> setup;
    std::unique_ptr<evaluation::LayerEvaluator> fast;
    std::unique_ptr<evaluation::LayerEvaluator> fastBounds;
    std::unique_ptr<evaluation::FullRenderEvaluator> full;
    std::vector<optimizer::Combination> candidates;  // a random walk: 1–3 objects change per step
};

// Cleared before main returns: left to static destruction, the renderers' teardown ended the
// program with a segmentation fault after the results were printed.
std::map<std::string, std::unique_ptr<Prepared>>& preparedCache() {
    static std::map<std::string, std::unique_ptr<Prepared>> cache;
    return cache;
}

Prepared& prepared(const std::string& sceneName) {
    auto& slot = preparedCache()[sceneName];
    if (slot) return *slot;
    slot = std::make_unique<Prepared>();
    Prepared& p = *slot;
    p.scene = scenes::loadScene(sceneName);
    p.renderer = std::make_unique<renderer::Renderer>(p.scene, renderer::RenderSettings{});
    p.setup = std::make_unique<evaluation::ViewSetup>(p.scene, p.scene.views[0], *p.renderer);
    metrics::MetricParameters parameters;
    p.fast = std::make_unique<evaluation::LayerEvaluator>(*p.setup, parameters, 1);
    p.fastBounds = std::make_unique<evaluation::LayerEvaluator>(*p.setup, parameters, 1,
                                                                evaluation::DirtyRegions::ObjectBounds);
    p.full = std::make_unique<evaluation::FullRenderEvaluator>(*p.setup, *p.renderer, parameters);
    const std::vector<int> counts = p.setup->levelCounts();
    std::mt19937 random(3);
    optimizer::Combination current(counts.size(), 0);
    for (int k = 0; k < 512 && !counts.empty(); ++k) {
        const int changes = 1 + int(random() % 3);
        for (int c = 0; c < changes; ++c) {
            const std::size_t v = random() % counts.size();
            current[v] = int(random() % counts[v]);
        }
        p.candidates.push_back(current);
    }
    return p;
}

void evaluatePath(benchmark::State& state, const Prepared& p, evaluation::LayerEvaluator& evaluator) {
    std::size_t k = 0;
    double sink = 0.0;
    for (auto _ : state) {
        sink += evaluator.evaluate(p.candidates[k++ % p.candidates.size()]).fitness;
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations());
    state.counters["searched_objects"] = double(p.setup->skipSummary().searchedObjects);
}

void fastPath(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fast);
}

void fastPathBounds(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastBounds);
}

void fullPath(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    std::size_t k = 0;
    double sink = 0.0;
    for (auto _ : state) {
        sink += p.full->evaluate(p.candidates[k++ % p.candidates.size()]).fitness;
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations());
}

void viewSetup(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    for (auto _ : state) {
        evaluation::ViewSetup setup(p.scene, p.scene.views[0], *p.renderer);
        benchmark::DoNotOptimize(setup.levelCounts());
    }
}

}  // namespace

int main(int argc, char** argv) {
    for (const std::string& name : scenes::builtinSceneNames()) {
        benchmark::RegisterBenchmark(("fast_path/" + name).c_str(), fastPath, name)
            ->Unit(benchmark::kMicrosecond)
            ->MeasureProcessCPUTime()
            ->UseRealTime();
        benchmark::RegisterBenchmark(("fast_path_bounds/" + name).c_str(), fastPathBounds, name)
            ->Unit(benchmark::kMicrosecond)
            ->MeasureProcessCPUTime()
            ->UseRealTime();
        benchmark::RegisterBenchmark(("full_path/" + name).c_str(), fullPath, name)
            ->Unit(benchmark::kMicrosecond)
            ->MeasureProcessCPUTime()
            ->UseRealTime();
        benchmark::RegisterBenchmark(("view_setup/" + name).c_str(), viewSetup, name)
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1);
    }
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    preparedCache().clear();
    return 0;
}
