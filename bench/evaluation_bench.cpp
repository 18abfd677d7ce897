// Fast (layers + incremental metrics) vs full (render + metrics) evaluation, per scene and view
// at 512² ("fast_path/forest/dense").
// Run: build/bench/evaluation_bench --benchmark_filter='/forest/' --benchmark_min_time=1 --benchmark_repetitions=3
// Reported: evaluations per second (items_per_second, from wall time) of each path on the same
// kind of candidates, and CPU time of the whole process (the full path rasterizes in llvmpipe's
// threads); the ratio fast/full is the figure docs/optimizer.md records. Both paths score what a
// search scores (evaluation::searchParameters: no precision/recall).
// Candidates: an endless random walk from the all-finest combination, 1–3 objects changing per
// step; each path continues its own walk, so no candidate sequence is replayed to an evaluator
// that kept scores from it (the window groups would answer a replayed walk from memory).
// fast_path is one evaluator over the whole run (the default PartCaching::Auto): a long
// search's steady state.
// fast_path_first1000 starts a new evaluator (not timed) and a new walk every 1000 candidates:
// the start of a search, before many group scores are kept.
// Variants of the fast path in the same run: fast_path_groups always uses the window groups
// (PartCaching::Groups), fast_path_owned the owned windows instead of
// the groups (PartCaching::On, the default before the groups); fast_path_all_metrics also
// computes precision/recall (which the groups do not cover: owned windows); fast_path_bounds
// re-scores whole object rectangles (DirtyRegions::ObjectBounds); fast_path_no_parts is the fast
// path without any cache (PartCaching::Off).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>

#include "evaluation/evaluation.hpp"
#include "scenes/builtin.hpp"

using namespace lodopt;

namespace {

// An endless random walk: each step sets 1–3 random variables to random options.
class Walk {
public:
    Walk(std::vector<int> counts, unsigned seed) : mCounts(std::move(counts)), mRandom(seed) { restart(); }
    void restart() { mCurrent.assign(mCounts.size(), 0); }
    const optimizer::Combination& next() {
        const int changes = 1 + int(mRandom() % 3);
        for (int c = 0; c < changes && !mCounts.empty(); ++c) {
            const std::size_t v = mRandom() % mCounts.size();
            mCurrent[v] = int(mRandom() % mCounts[v]);
        }
        return mCurrent;
    }

private:
    std::vector<int> mCounts;
    std::mt19937 mRandom;
    optimizer::Combination mCurrent;
};

struct Prepared {
    scenes::Scene scene;
    std::unique_ptr<renderer::Renderer> renderer;
    std::unique_ptr<evaluation::ViewSetup> setup;
    metrics::MetricParameters parameters;  // what a search scores
    std::unique_ptr<evaluation::LayerEvaluator> fast;
    std::unique_ptr<evaluation::LayerEvaluator> fastGroups;      // PartCaching::Groups
    std::unique_ptr<evaluation::LayerEvaluator> fastOwned;       // PartCaching::On
    std::unique_ptr<evaluation::LayerEvaluator> fastBounds;
    std::unique_ptr<evaluation::LayerEvaluator> fastNoParts;     // PartCaching::Off
    std::unique_ptr<evaluation::LayerEvaluator> fastAllMetrics;  // precision/recall too
    std::unique_ptr<evaluation::FullRenderEvaluator> full;
    std::map<std::string, Walk> walks;  // per path
    Walk& walk(const std::string& path) {
        auto found = walks.find(path);
        if (found == walks.end()) found = walks.emplace(path, Walk(setup->levelCounts(), 3)).first;
        return found->second;
    }
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
    p.parameters = evaluation::searchParameters({});
    const metrics::MetricParameters& parameters = p.parameters;
    using evaluation::DirtyRegions, evaluation::PartCaching, evaluation::LayerEvaluator;
    p.fast = std::make_unique<LayerEvaluator>(*p.setup, parameters, 1);
    p.fastGroups = std::make_unique<LayerEvaluator>(*p.setup, parameters, 1, DirtyRegions::ChangedPixels,
                                                    LayerEvaluator::kDefaultStates, PartCaching::Groups);
    p.fastOwned = std::make_unique<LayerEvaluator>(*p.setup, parameters, 1, DirtyRegions::ChangedPixels,
                                                   LayerEvaluator::kDefaultStates, PartCaching::On);
    p.fastBounds = std::make_unique<LayerEvaluator>(*p.setup, parameters, 1, DirtyRegions::ObjectBounds);
    p.fastNoParts = std::make_unique<LayerEvaluator>(*p.setup, parameters, 1, DirtyRegions::ChangedPixels,
                                                     LayerEvaluator::kDefaultStates, PartCaching::Off);
    p.fastAllMetrics = std::make_unique<LayerEvaluator>(*p.setup, metrics::MetricParameters{}, 1);
    p.full = std::make_unique<evaluation::FullRenderEvaluator>(*p.setup, *p.renderer, parameters);
    return p;
}

void addCounters(benchmark::State& state, const Prepared& p, const evaluation::LayerEvaluator& evaluator) {
    state.counters["searched_objects"] = double(p.setup->skipSummary().searchedObjects);
    const metrics::PartCacheStats parts = evaluator.partCacheStats();
    if (parts.parts > 0) {
        // Share of the SSIM windows some searched object reaches that are owned by one object.
        const double reached = double(parts.ownedSsimWindows + parts.liveSsimWindows);
        state.counters["owned_share"] = reached > 0 ? double(parts.ownedSsimWindows) / reached : 0.0;
        state.counters["cache_MB"] = double(parts.bytes) / 1e6;
    }
    const evaluation::GroupCacheStats groups = evaluator.groupCacheStats();
    if (groups.groups > 0) {
        state.counters["groups"] = double(groups.groups);
        state.counters["kept_share"] = double(groups.hits) / double(std::max<std::uint64_t>(groups.hits + groups.misses, 1));
        state.counters["cache_MB"] = double(groups.bytes) / 1e6;
    }
}

void evaluatePath(benchmark::State& state, Prepared& p, evaluation::LayerEvaluator& evaluator, const char* path) {
    Walk& walk = p.walk(path);
    double sink = 0.0;
    for (auto _ : state) sink += evaluator.evaluate(walk.next()).fitness;
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations());
    addCounters(state, p, evaluator);
}

void fastPath(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fast, "fast");
}

void fastPathFirst1000(benchmark::State& state, const std::string& sceneName) {
    constexpr int kEvaluations = 1000;
    Prepared& p = prepared(sceneName);
    Walk& walk = p.walk("first1000");
    std::unique_ptr<evaluation::LayerEvaluator> evaluator;
    int used = kEvaluations;
    double sink = 0.0;
    for (auto _ : state) {
        if (used == kEvaluations) {
            state.PauseTiming();
            evaluator.reset();
            evaluator = std::make_unique<evaluation::LayerEvaluator>(*p.setup, p.parameters, 1);
            walk.restart();
            used = 0;
            state.ResumeTiming();
        }
        sink += evaluator->evaluate(walk.next()).fitness;
        ++used;
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(state.iterations());
    addCounters(state, p, *evaluator);
}

void fastPathGroups(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastGroups, "groups");
}

void fastPathOwned(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastOwned, "owned");
}

void fastPathBounds(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastBounds, "bounds");
}

void fastPathNoParts(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastNoParts, "no_parts");
}

void fastPathAllMetrics(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    evaluatePath(state, p, *p.fastAllMetrics, "all_metrics");
}

void fullPath(benchmark::State& state, const std::string& sceneName) {
    Prepared& p = prepared(sceneName);
    Walk& walk = p.walk("full");
    double sink = 0.0;
    for (auto _ : state) sink += p.full->evaluate(walk.next()).fitness;
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
                                                      {"fast_path_first1000/", fastPathFirst1000},
                                                      {"fast_path_groups/", fastPathGroups},
                                                      {"fast_path_owned/", fastPathOwned},
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
