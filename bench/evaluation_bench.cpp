// Fast (layers + incremental metrics) vs full (render + metrics) evaluation, per scene and view
// at 512² ("fast_path/forest/dense").
// Run: build/bench/evaluation_bench --benchmark_filter='/forest/' --benchmark_min_time=1 --benchmark_repetitions=3
// Reported: evaluations per second (items_per_second, from wall time) of each path on the same
// candidates, and CPU time of the whole process (the full path rasterizes in llvmpipe's
// threads); the ratio fast/full is the figure docs/optimizer.md records. Both paths score what a
// search scores (evaluation::searchParameters: no precision/recall).
// Variants of the fast path in the same run: fast_path_all_metrics also computes precision/recall;
// fast_path_bounds re-scores whole object rectangles (DirtyRegions::ObjectBounds), the earlier
// fast path; fast_path_no_parts is the fast path without the owned-window cache
// (PartCaching::Off), as it was before that cache.
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
    std::unique_ptr<evaluation::LayerEvaluator> fastNoParts;  // PartCaching::Off
    std::unique_ptr<evaluation::LayerEvaluator> fastAllMetrics;  // precision/recall too
    std::unique_ptr<evaluation::FullRenderEvaluator> full;
    std::vector<optimizer::Combination> candidates;  // a random walk: 1–3 objects change per step
};

// Cleared before main returns: left to static destruction, the renderers' teardown ended the
// program with a segmentation fault after the results were printed.
std::map<std::string, std::unique_ptr<Prepared>>& preparedCache() {
    static std::map<std::string, std::unique_ptr<Prepared>> cache;
    return cache;
}

// `key` is "scene/view".
Prepared& prepared(const std::string& key) {
    auto& slot = preparedCache()[key];
    if (slot) return *slot;
    slot = std::make_unique<Prepared>();
    Prepared& p = *slot;
    const std::size_t slash = key.find('/');
    p.scene = scenes::loadScene(key.substr(0, slash));
    p.renderer = std::make_unique<renderer::Renderer>(p.scene, renderer::RenderSettings{});
    const std::string viewName = key.substr(slash + 1);
    const scenes::Camera* view = &p.scene.views[0];
    for (const scenes::Camera& candidate : p.scene.views) {
        if (candidate.name == viewName) view = &candidate;
    }
    p.setup = std::make_unique<evaluation::ViewSetup>(p.scene, *view, *p.renderer);
    // What a search evaluates: fitness without precision/recall (evaluation::searchParameters).
    const metrics::MetricParameters parameters = evaluation::searchParameters({});
    p.fast = std::make_unique<evaluation::LayerEvaluator>(*p.setup, parameters, 1);
    p.fastBounds = std::make_unique<evaluation::LayerEvaluator>(*p.setup, parameters, 1,
                                                                evaluation::DirtyRegions::ObjectBounds);
    p.fastNoParts = std::make_unique<evaluation::LayerEvaluator>(
        *p.setup, parameters, 1, evaluation::DirtyRegions::ChangedPixels, evaluation::LayerEvaluator::kDefaultStates,
        evaluation::PartCaching::Off);
    p.fastAllMetrics = std::make_unique<evaluation::LayerEvaluator>(*p.setup, metrics::MetricParameters{}, 1);
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
    const metrics::PartCacheStats parts = evaluator.partCacheStats();
    if (parts.parts > 0) {
        // Share of the SSIM windows some searched object reaches that are owned by one object.
        const double reached = double(parts.ownedSsimWindows + parts.liveSsimWindows);
        state.counters["owned_share"] = reached > 0 ? double(parts.ownedSsimWindows) / reached : 0.0;
        state.counters["cache_MB"] = double(parts.bytes) / 1e6;
    }
}

void fastPath(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fast);
}

void fastPathBounds(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastBounds);
}

void fastPathNoParts(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastNoParts);
}

void fastPathAllMetrics(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastAllMetrics);
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
    // Every view of every built-in scene: "fast_path/forest/dense". Preparing a view renders
    // its layers, so filter (--benchmark_filter) to what you need.
    std::vector<std::string> names;
    for (const std::string& sceneName : scenes::builtinSceneNames()) {
        for (const scenes::Camera& view : scenes::loadScene(sceneName).views) names.push_back(sceneName + "/" + view.name);
    }
    for (const std::string& name : names) {
        // Wall time per evaluation, and the whole process's CPU (llvmpipe's threads included).
        using Path = void (*)(benchmark::State&, const std::string&);
        const std::pair<const char*, Path> paths[] = {{"fast_path/", fastPath},
                                                      {"fast_path_bounds/", fastPathBounds},
                                                      {"fast_path_no_parts/", fastPathNoParts},
                                                      {"fast_path_all_metrics/", fastPathAllMetrics},
                                                      {"full_path/", fullPath}};
        for (const auto& [prefix, path] : paths) {
            benchmark::RegisterBenchmark((prefix + name).c_str(), path, name)
                ->Unit(benchmark::kMicrosecond)
                ->MeasureProcessCPUTime()
                ->UseRealTime();
        }
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
