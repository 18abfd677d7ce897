// The scheduler's view of a frame without rendering (scheduler::SceneIndex, Bounds features)
// against the time model's exact features, along each built-in scene's path at 512²: what a
// decision pays per frame and how far its predictions stray ("observe/harbor").
// Run: build/bench/scheduler_bench --benchmark_min_time=0.5 --benchmark_repetitions=3
// Timed: SceneIndex::beginFrame and observe of every object for one frame, frames in turn.
// Counters, computed once before timing with the scene's shipped profile (linear model):
//   frame_error  mean |bounds − exact| / exact of the all-finest frame's predicted time;
//   step_error   mean |Δbounds − Δexact| / Δexact over one-level steps of an object (Δ the
//                predicted time the step saves; steps saving ≤ 0.05 ms left out): what the
//                scheduler's lowering and raising compare;
//   near_step_error  the same over objects within 1.5 radii of the eye (measured through
//                stand-ins, scene_index.hpp).
// Paths: the forest's walk and the city's flight (every 10th and 15th frame), the harbor's
// approach of scripts/harbor_approach.py (a 300-frame spiral around the ship, every 5th).
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <numbers>

#include "scenes/builtin.hpp"
#include "scheduler/scene_index.hpp"
#include "timemodel/profile.hpp"

using namespace lodopt;

namespace {

constexpr int kSize = 512;

std::vector<scenes::Camera> harborApproach() {
    std::vector<scenes::Camera> frames;
    for (int f = 0; f < 300; ++f) {
        const double t = f / 299.0;
        const double r = 250.0 - 215.0 * t, h = 45.0 - 36.0 * t, a = (135.0 + 270.0 * t) * std::numbers::pi / 180.0;
        scenes::Camera camera;
        camera.position = glm::vec3(float(r * std::cos(a)), float(h), float(r * std::sin(a)));
        camera.target = glm::vec3(0.0f, 4.0f, 0.0f);
        camera.nearPlane = 0.5f;
        camera.farPlane = 1500.0f;
        frames.push_back(camera);
    }
    return frames;
}

struct Prepared {
    scenes::Scene scene;
    std::vector<scenes::Camera> frames;
    std::unique_ptr<timemodel::TimeModel> model;
    std::unique_ptr<scheduler::SceneIndex> bounds;
    double frameError = 0.0, stepError = 0.0, nearStepError = 0.0;
};

// Mean |a − b| / b over pairs.
struct MeanError {
    double sum = 0.0;
    int count = 0;
    void add(double estimate, double truth) {
        sum += std::fabs(estimate - truth) / truth;
        ++count;
    }
    double mean() const { return count > 0 ? sum / count : 0.0; }
};

Prepared& prepared(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Prepared>> cache;
    std::unique_ptr<Prepared>& slot = cache[name];
    if (slot) return *slot;
    slot = std::make_unique<Prepared>();
    Prepared& p = *slot;
    p.scene = scenes::makeBuiltinScene(name);
    const int stride = name == "harbor" ? 5 : (name == "forest" ? 10 : 15);
    const std::vector<scenes::Camera> path = name == "harbor" ? harborApproach() : p.scene.paths.at(0).frames;
    for (std::size_t f = 0; f < path.size(); f += std::size_t(stride)) p.frames.push_back(path[f]);
    p.model = timemodel::modelFromProfile(timemodel::shippedProfile(name));
    const timemodel::FeatureSet needed = p.model->readFeatures();
    p.bounds =
        std::make_unique<scheduler::SceneIndex>(p.scene, kSize, kSize, scheduler::FeatureMode::Bounds, 0, needed);
    const scheduler::SceneIndex exact(p.scene, kSize, kSize, scheduler::FeatureMode::Exact, 0, needed);
    scheduler::FrameObjects a, b;
    MeanError frame, step, nearStep;
    const timemodel::FrameFeatures& base = p.bounds->frameConstant();
    const auto ms = [&](const timemodel::FrameFeatures& contribution) {
        return p.model->estimateMs(base + contribution) - p.model->estimateMs(base);
    };
    for (const scenes::Camera& camera : p.frames) {
        p.bounds->beginFrame(camera, a);
        exact.beginFrame(camera, b);
        timemodel::FrameFeatures finestA = base, finestB = exact.frameConstant();
        for (int o = 0; o < p.bounds->objectCount(); ++o) {
            if (!p.bounds->observe(o, a) || !exact.observe(o, b)) continue;
            const scheduler::ObjectShape& shape = p.bounds->shape(o);
            const bool near = glm::length(camera.position - shape.center) < 1.5f * shape.radius;
            const int first = p.bounds->firstLevel(o);
            finestA += a.contributions[std::size_t(first)];
            finestB += b.contributions[std::size_t(first)];
            for (int l = 1; l < p.bounds->levelCount(o); ++l) {
                const std::size_t finer = std::size_t(first + l - 1), coarser = std::size_t(first + l);
                const double saved = ms(b.contributions[finer]) - ms(b.contributions[coarser]);
                if (saved <= 0.05) continue;
                const double estimate = ms(a.contributions[finer]) - ms(a.contributions[coarser]);
                (near ? nearStep : step).add(estimate, saved);
            }
        }
        frame.add(p.model->estimateMs(finestA), p.model->estimateMs(finestB));
    }
    p.frameError = frame.mean();
    p.stepError = step.mean();
    p.nearStepError = nearStep.mean();
    return p;
}

void observe(benchmark::State& state, const std::string& name) {
    Prepared& p = prepared(name);
    scheduler::FrameObjects out;
    std::size_t frame = 0;
    for (auto _ : state) {
        p.bounds->beginFrame(p.frames[frame], out);
        for (int o = 0; o < p.bounds->objectCount(); ++o) benchmark::DoNotOptimize(p.bounds->observe(o, out));
        frame = (frame + 1) % p.frames.size();
    }
    state.counters["frame_error"] = p.frameError;
    state.counters["step_error"] = p.stepError;
    state.counters["near_step_error"] = p.nearStepError;
    state.counters["frames"] = double(p.frames.size());
}

}  // namespace

BENCHMARK_CAPTURE(observe, harbor, std::string("harbor"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(observe, forest, std::string("forest"))->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(observe, city, std::string("city"))->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
