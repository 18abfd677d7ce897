// Speed of the metrics (issue #4): each component and the fused fitness at 512^2, 1024^2 and
// 2048^2, full and incremental (one 64x64 dirty rectangle), next to a straightforward
// OpenCV float64 SSIM (cv::GaussianBlur + Mat expressions) run in the same process.
//
// Run: build-metrics/bench/metrics_bench --benchmark_min_time=0.5 --benchmark_repetitions=5
//        --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
// OpenCV is limited to one thread (cv::setNumThreads(1)) because lodopt's metrics are
// single-threaded; the platform notes found OpenCV's 2 threads no faster at these sizes.
// The accuracy counter `abs_diff_vs_lodopt` is |reference SSIM - lodopt SSIM|.
#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "../tests/metrics/test_images.hpp"
#include "metrics/incremental_evaluator.hpp"
#include "metrics/metrics.hpp"
#include "metrics/reference.hpp"

namespace {

using lodopt::metrics::testing::generateScene;
using lodopt::metrics::testing::TestImage;
namespace m = lodopt::metrics;

struct Pair {
    TestImage reference, candidate;
    TestImage everywhere;  // the reference with +-2 noise on every pixel: nothing is shared
};

// A reference "render" (sky, a box, a disk) and a candidate with the objects moved and
// re-noised: like a render at other levels, most of the sky is unchanged. Cached by size.
const Pair& images(int size) {
    static std::map<int, Pair> cache;
    auto it = cache.find(size);
    if (it == cache.end()) {
        Pair pair{generateScene(size, size, 4, 1, 0), generateScene(size, size, 4, 2, 2), {}};
        std::mt19937 rng(5);
        pair.everywhere = lodopt::metrics::testing::addNoise(pair.reference, 2, rng);
        it = cache.emplace(size, std::move(pair)).first;
    }
    return it->second;
}

// metrics::reference::ssim's computation without temporaries: every Mat allocated once and
// reused, so OpenCV pays no allocation or page faults (a harder target than the reference).
struct PreallocatedReferenceSsim {
    cv::Mat wide, x, y, xx, yy, xy, mx, my, bxx, byy, bxy, mxy, mx2, my2, t1, t2, t3, t4;
    double operator()(const TestImage& candidate, const TestImage& reference) {
        auto gray = [&](const TestImage& image, cv::Mat& out) {
            cv::Mat rgba(image.height, image.width, CV_8UC4, const_cast<std::uint8_t*>(image.pixels.data()));
            rgba.convertTo(wide, CV_64FC4);
            cv::transform(wide, out, cv::Matx14d(0.30, 0.59, 0.11, 0.0));
        };
        gray(candidate, x);
        gray(reference, y);
        const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
        const cv::Size window(11, 11);
        cv::multiply(x, x, xx);
        cv::multiply(y, y, yy);
        cv::multiply(x, y, xy);
        cv::GaussianBlur(x, mx, window, 1.5, 1.5, cv::BORDER_REFLECT);
        cv::GaussianBlur(y, my, window, 1.5, 1.5, cv::BORDER_REFLECT);
        cv::GaussianBlur(xx, bxx, window, 1.5, 1.5, cv::BORDER_REFLECT);
        cv::GaussianBlur(yy, byy, window, 1.5, 1.5, cv::BORDER_REFLECT);
        cv::GaussianBlur(xy, bxy, window, 1.5, 1.5, cv::BORDER_REFLECT);
        cv::multiply(mx, my, mxy);
        cv::multiply(mx, mx, mx2);
        cv::multiply(my, my, my2);
        mxy.convertTo(t1, -1, 2.0, c1);  // 2 mx my + C1
        cv::subtract(bxy, mxy, t2);
        t2.convertTo(t2, -1, 2.0, c2);  // 2 sxy + C2
        cv::add(mx2, my2, t3);
        t3.convertTo(t3, -1, 1.0, c1);  // mx^2 + my^2 + C1
        cv::subtract(bxx, mx2, t4);
        cv::add(t4, byy, t4);
        cv::subtract(t4, my2, t4);
        t4.convertTo(t4, -1, 1.0, c2);  // sx^2 + sy^2 + C2
        cv::multiply(t1, t2, t1);
        cv::multiply(t3, t4, t3);
        cv::divide(t1, t3, t1);
        return cv::mean(t1(cv::Rect(5, 5, x.cols - 10, x.rows - 10)))[0];
    }
};

void BM_SsimReferenceOpenCvFloat64Preallocated(benchmark::State& state) {
    cv::setNumThreads(1);
    const Pair& p = images(int(state.range(0)));
    PreallocatedReferenceSsim reference;
    double value = 0;
    for (auto _ : state) benchmark::DoNotOptimize(value = reference(p.candidate, p.reference));
    state.counters["abs_diff_vs_lodopt"] = std::abs(value - m::ssim(p.candidate.view(), p.reference.view(), {}));
}

void BM_SsimReferenceOpenCvFloat64(benchmark::State& state) {
    cv::setNumThreads(1);
    const Pair& p = images(int(state.range(0)));
    double value = 0;
    for (auto _ : state) benchmark::DoNotOptimize(value = m::reference::ssim(p.candidate.view(), p.reference.view()));
    state.counters["abs_diff_vs_lodopt"] = std::abs(value - m::ssim(p.candidate.view(), p.reference.view(), {}));
}

void BM_Ssim(benchmark::State& state) {
    const Pair& p = images(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(m::ssim(p.candidate.view(), p.reference.view(), {}));
}

void BM_BoundaryEntropy(benchmark::State& state) {
    const Pair& p = images(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(m::boundaryEntropy(p.candidate.view(), {}));
}

void BM_InformationEntropy(benchmark::State& state) {
    const Pair& p = images(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(m::informationEntropy(p.candidate.view(), {}));
}

void BM_PrecisionRecall(benchmark::State& state) {
    const Pair& p = images(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(m::precisionRecall(p.candidate.view(), p.reference.view(), {}));
}

// evaluate(): every component from scratch, both images converted on every call.
void BM_FusedFitnessOneShot(benchmark::State& state) {
    const Pair& p = images(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(m::evaluate(p.candidate.view(), p.reference.view(), {}).fitness);
}

// Evaluator configurations: 0 fused (all components, precision/recall on), 1 SSIM only,
// 2 boundary entropy only, 3 information entropy only.
m::MetricParameters configuration(int which) {
    m::MetricParameters p;
    if (which == 0) return p;
    p.computePrecisionRecall = false;
    p.ssimWeight = which == 1 ? 1 : 0;
    p.boundaryEntropyWeight = which == 2 ? 1 : 0;
    p.informationEntropyWeight = which == 3 ? 1 : 0;
    return p;
}
const char* kConfigurationNames[] = {"fused", "ssim", "boundary_entropy", "information_entropy"};

// Full: setCandidate (the whole image) + result() on a warmed-up evaluator.
void BM_EvaluatorFull(benchmark::State& state) {
    const int which = int(state.range(0));
    const Pair& p = images(int(state.range(1)));
    m::IncrementalEvaluator evaluator(p.reference.view(), configuration(which));
    for (auto _ : state) {
        evaluator.setCandidate(p.candidate.view());
        benchmark::DoNotOptimize(evaluator.result().fitness);
    }
    state.SetLabel(kConfigurationNames[which]);
}

// Worst case for the full path: every pixel differs from the reference (a global lighting
// change), so no SSIM window can be skipped as identical.
void BM_EvaluatorFullEveryPixelDiffers(benchmark::State& state) {
    const int which = int(state.range(0));
    const Pair& p = images(int(state.range(1)));
    m::IncrementalEvaluator evaluator(p.reference.view(), configuration(which));
    for (auto _ : state) {
        evaluator.setCandidate(p.everywhere.view());
        benchmark::DoNotOptimize(evaluator.result().fitness);
    }
    state.SetLabel(kConfigurationNames[which]);
}

void BM_SsimEveryPixelDiffers(benchmark::State& state) {
    const Pair& p = images(int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(m::ssim(p.everywhere.view(), p.reference.view(), {}));
}

// Incremental: the candidate alternates between two images that differ only inside one
// 64x64 rectangle; each iteration is updateRect(that rectangle) + result().
void BM_EvaluatorIncremental64(benchmark::State& state) {
    const int which = int(state.range(0));
    const int size = int(state.range(1));
    const Pair& p = images(size);
    TestImage changed = p.candidate;
    const int x0 = size / 3, y0 = size / 2;
    std::mt19937 rng(1);
    lodopt::metrics::testing::scribble(changed, x0, y0, x0 + 64, y0 + 64, rng);
    m::IncrementalEvaluator evaluator(p.reference.view(), configuration(which));
    evaluator.setCandidate(p.candidate.view());
    bool flip = false;
    for (auto _ : state) {
        flip = !flip;
        evaluator.updateRect(flip ? changed.view() : p.candidate.view(), x0, y0, x0 + 64, y0 + 64);
        benchmark::DoNotOptimize(evaluator.result().fitness);
    }
    state.SetLabel(kConfigurationNames[which]);
}

void sizes(benchmark::internal::Benchmark* b) {
    for (int size : {512, 1024, 2048}) b->Arg(size);
    b->Unit(benchmark::kMillisecond);
}
void configurationsAndSizes(benchmark::internal::Benchmark* b) {
    for (int which = 0; which < 4; ++which) {
        for (int size : {512, 1024, 2048}) b->Args({which, size});
    }
    b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_SsimReferenceOpenCvFloat64)->Apply(sizes);
BENCHMARK(BM_SsimReferenceOpenCvFloat64Preallocated)->Apply(sizes);
BENCHMARK(BM_Ssim)->Apply(sizes);
BENCHMARK(BM_BoundaryEntropy)->Apply(sizes);
BENCHMARK(BM_InformationEntropy)->Apply(sizes);
BENCHMARK(BM_PrecisionRecall)->Apply(sizes);
BENCHMARK(BM_FusedFitnessOneShot)->Apply(sizes);
BENCHMARK(BM_EvaluatorFull)->Apply(configurationsAndSizes);
BENCHMARK(BM_EvaluatorIncremental64)->Apply(configurationsAndSizes);
BENCHMARK(BM_SsimEveryPixelDiffers)->Apply(sizes);
BENCHMARK(BM_EvaluatorFullEveryPixelDiffers)
    ->Args({0, 512})->Args({0, 1024})->Args({0, 2048})
    ->Args({1, 512})->Args({1, 1024})->Args({1, 2048})
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
