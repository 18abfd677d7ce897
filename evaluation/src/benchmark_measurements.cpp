#include <algorithm>
#include <chrono>
#include <random>
#include <span>

#include "evaluation/benchmark.hpp"
#include "evaluation/device_timing.hpp"
#include "metrics/incremental_evaluator.hpp"
#include "metrics/metrics.hpp"
#include "metrics/reference.hpp"
#include "timemodel/timing.hpp"

namespace lodopt::evaluation {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Median over 5 batches of the time per call of `call`, each batch about minSeconds / 5.
template <typename Call>
double microsecondsPerCall(Call call, double minSeconds, std::int64_t& calls) {
    auto start = Clock::now();
    call();
    const double once = std::max(secondsSince(start), 1e-7);
    const std::int64_t perBatch = std::max<std::int64_t>(1, std::int64_t(minSeconds / 5.0 / once));
    std::vector<double> perCall;
    calls = 1;
    for (int batch = 0; batch < 5; ++batch) {
        start = Clock::now();
        for (std::int64_t i = 0; i < perBatch; ++i) call();
        perCall.push_back(secondsSince(start) * 1e6 / double(perBatch));
        calls += perBatch;
    }
    return timemodel::median(perCall);
}

optimizer::Combination randomCombination(const std::vector<int>& levelCounts, std::mt19937_64& rng) {
    optimizer::Combination combination(levelCounts.size());
    for (std::size_t i = 0; i < levelCounts.size(); ++i) {
        combination[i] = int(std::uniform_int_distribution<int>(0, levelCounts[i] - 1)(rng));
    }
    return combination;
}

}  // namespace

std::vector<EvalPathRow> measureEvaluationPaths(const SearchView& view, renderer::Renderer& renderer,
                                                const metrics::MetricParameters& metrics, int threads, int candidates,
                                                std::uint64_t seed) {
    const std::vector<int>& levelCounts = view.problem.levelCounts;
    std::mt19937_64 rng(seed);
    std::vector<optimizer::Combination> random, walk;
    for (int i = 0; i < candidates; ++i) random.push_back(randomCombination(levelCounts, rng));
    // A walk changes one variable per step: what a swarm's small moves look like to the fast path.
    walk.push_back(randomCombination(levelCounts, rng));
    while (int(walk.size()) < candidates) {
        optimizer::Combination next = walk.back();
        if (!levelCounts.empty()) {
            const std::size_t i = std::uniform_int_distribution<std::size_t>(0, levelCounts.size() - 1)(rng);
            if (levelCounts[i] > 1) {
                const int shift = std::uniform_int_distribution<int>(1, levelCounts[i] - 1)(rng);
                next[i] = (next[i] + shift) % levelCounts[i];
            }
        }
        walk.push_back(next);
    }
    const ViewSetup& setup = *view.setup;
    // What a search evaluates (fitness only), on both paths.
    const metrics::MetricParameters search = searchParameters(metrics);
    std::vector<EvalPathRow> rows;
    for (const auto& [workload, set] :
         {std::pair<std::string, const std::vector<optimizer::Combination>*>{"random", &random}, {"walk", &walk}}) {
        // Full path first: its fitness is what the fast path is compared with.
        FullRenderEvaluator full(setup, renderer, search);
        full.evaluate(set->front());  // warm-up: buffers sized, GL state touched
        std::vector<double> fullFitness;
        auto start = Clock::now();
        for (const optimizer::Combination& c : *set) fullFitness.push_back(full.evaluate(c).fitness);
        const double fullSeconds = secondsSince(start);
        rows.push_back({"full", workload, "single", 1, candidates, fullSeconds, candidates / fullSeconds, NAN, NAN});

        auto addFast = [&](const std::string& mode, int threads, const std::vector<optimizer::Score>& scores,
                           double seconds) {
            EvalPathRow row{"fast", workload, mode, threads, candidates, seconds, candidates / seconds, 0.0, 0.0};
            for (std::size_t i = 0; i < scores.size(); ++i) {
                const double diff = std::abs(scores[i].fitness - fullFitness[i]);
                row.meanAbsFitnessDiff += diff / double(scores.size());
                row.maxAbsFitnessDiff = std::max(row.maxAbsFitnessDiff, diff);
            }
            rows.push_back(row);
        };
        {
            // Batches of 12, a swarm iteration's worth, spread over the threads.
            LayerEvaluator fast(setup, search, threads);
            std::vector<optimizer::Score> scores(set->size());
            fast.evaluate(set->front());
            start = Clock::now();
            for (std::size_t begin = 0; begin < set->size(); begin += 12) {
                const std::size_t count = std::min<std::size_t>(12, set->size() - begin);
                fast.evaluateBatch(std::span<const optimizer::Combination>(set->data() + begin, count),
                                   std::span<optimizer::Score>(scores.data() + begin, count));
            }
            addFast("batch", threads, scores, secondsSince(start));
        }
        {
            LayerEvaluator fast(setup, search, 1);
            std::vector<optimizer::Score> scores;
            fast.evaluate(set->front());
            start = Clock::now();
            for (const optimizer::Combination& c : *set) scores.push_back(fast.evaluate(c));
            addFast("single", 1, scores, secondsSince(start));
        }
    }
    return rows;
}

std::vector<MetricsRow> measureMetrics(const SearchView& view, renderer::Renderer& renderer,
                                       const metrics::MetricParameters& metrics, double minSeconds) {
    const ViewSetup& setup = *view.setup;
    const renderer::Frame& reference = setup.reference();
    // The candidate: every searched object at its coarsest option, a realistic worst case.
    optimizer::Combination coarsest(view.problem.levelCounts.size());
    for (std::size_t i = 0; i < coarsest.size(); ++i) coarsest[i] = view.problem.levelCounts[i] - 1;
    const renderer::Frame candidate = renderer.render(setup.toScene(coarsest), setup.camera());
    const int width = reference.width, height = reference.height;
    const metrics::ImageView c = metrics::makeImageView(candidate.rgba.data(), width, height, 4);
    const metrics::ImageView r = metrics::makeImageView(reference.rgba.data(), width, height, 4);
    metrics::MetricParameters parameters = metrics;
    // Fused deviations compare like with like: the reference fuses the three fidelities equally.
    parameters.ssimWeight = parameters.boundaryEntropyWeight = parameters.informationEntropyWeight = 1.0;

    std::vector<MetricsRow> rows;
    auto add = [&](const std::string& function, auto call, const std::string& referenceName, auto referenceCall,
                   double value, double referenceValue) {
        MetricsRow row;
        row.function = function;
        row.width = width;
        row.height = height;
        row.microsecondsPerCall = microsecondsPerCall(call, minSeconds, row.calls);
        row.reference = referenceName;
        if (!referenceName.empty()) {
            std::int64_t referenceCalls = 0;
            row.referenceMicrosecondsPerCall = microsecondsPerCall(referenceCall, minSeconds, referenceCalls);
            row.absDeviation = std::abs(value - referenceValue);
        }
        rows.push_back(row);
    };
    metrics::reference::useOneThread();  // lodopt's metrics are single-threaded; so is the reference
    auto none = [] {};
    volatile double sink = 0.0;
    const double ssimReference = metrics::reference::ssim(c, r);
    add(
        "ssim", [&] { sink = metrics::ssim(c, r, parameters); }, "OpenCV float64 GaussianBlur SSIM",
        [&] { sink = metrics::reference::ssim(c, r); }, metrics::ssim(c, r, parameters), ssimReference);
    const double boundaryReference = metrics::reference::boundaryEntropy(c);
    add(
        "boundary_entropy", [&] { sink = metrics::boundaryEntropy(c, parameters); }, "OpenCV float64 Sobel histogram",
        [&] { sink = metrics::reference::boundaryEntropy(c); }, metrics::boundaryEntropy(c, parameters),
        boundaryReference);
    const double informationReference = metrics::reference::informationEntropy(c);
    add(
        "information_entropy", [&] { sink = metrics::informationEntropy(c, parameters); }, "float64 gray histogram",
        [&] { sink = metrics::reference::informationEntropy(c); }, metrics::informationEntropy(c, parameters),
        informationReference);
    add(
        "precision_recall", [&] { sink = metrics::precisionRecall(c, r, parameters).precision; }, "", none, 0.0, 0.0);
    const double fusedReference = metrics::reference::fitness(c, r);
    const double fused = metrics::evaluate(c, r, parameters).fitness;
    add(
        "evaluate (fused, from scratch)", [&] { sink = metrics::evaluate(c, r, parameters).fitness; },
        "fused float64 references", [&] { sink = metrics::reference::fitness(c, r); }, fused, fusedReference);
    metrics::IncrementalEvaluator incremental(r, parameters);
    incremental.setCandidate(c);
    add(
        "incremental: whole candidate",
        [&] {
            incremental.setCandidate(c);
            sink = incremental.result().fitness;
        },
        "evaluate (fused, from scratch)", [&] { sink = metrics::evaluate(c, r, parameters).fitness; },
        incremental.result().fitness, fused);
    // One 64x64 rectangle toggled between the reference and the candidate.
    const int x0 = std::max(0, width / 2 - 32), y0 = std::max(0, height / 2 - 32);
    const int x1 = std::min(width, x0 + 64), y1 = std::min(height, y0 + 64);
    renderer::Frame patched = reference;
    for (int y = y0; y < y1; ++y) {
        std::copy_n(&candidate.rgba[(std::size_t(y) * width + x0) * 4], (x1 - x0) * 4,
                    &patched.rgba[(std::size_t(y) * width + x0) * 4]);
    }
    const metrics::ImageView p = metrics::makeImageView(patched.rgba.data(), width, height, 4);
    incremental.setCandidate(r);
    bool toggle = false;
    add(
        "incremental: 64x64 rectangle",
        [&] {
            toggle = !toggle;
            incremental.updateRect(toggle ? p : r, x0, y0, x1, y1);
            sink = incremental.result().fitness;
        },
        "", none, 0.0, 0.0);
    incremental.setCandidate(r);
    incremental.updateRect(p, x0, y0, x1, y1);
    rows.back().reference = "evaluate (fused, from scratch)";
    rows.back().absDeviation = std::abs(incremental.result().fitness - metrics::evaluate(p, r, parameters).fitness);
    (void)sink;
    return rows;
}

std::vector<TimeModelRow> measureTimeModels(const SearchView& view, renderer::Renderer& renderer,
                                            const timemodel::DeviceProfile& profile, int frames, int repeats,
                                            std::uint64_t seed) {
    std::vector<TimeModelRow> rows;
    for (const timemodel::ModelResult& model : profile.models) {
        if (!model.fitted) continue;
        const timemodel::ErrorStats& e = model.heldOutErrors;
        rows.push_back({model.name, "calibration held-out", e.count, e.mean, e.median, e.p90, e.max});
        const timemodel::ErrorStats& r = model.rotatedErrors;
        if (r.count > 0) {
            rows.push_back(
                {model.name, "calibration, every viewpoint held out", r.count, r.mean, r.median, r.p90, r.max});
        }
    }
    // Frames of this view: every object at a uniformly drawn level, timed now.
    std::mt19937_64 rng(seed);
    const scenes::Scene& scene = view.setup->scene();
    const scenes::Camera& camera = view.setup->camera();
    std::vector<scenes::Combination> combinations;
    std::vector<double> measured;
    for (int f = 0; f < frames; ++f) {
        scenes::Combination combination(scene.objects.size());
        for (std::size_t o = 0; o < combination.size(); ++o) {
            combination[o] = std::uniform_int_distribution<int>(0, int(scene.objects[o].levels.size()) - 1)(rng);
        }
        // What every profile predicts: the median of the frame's draws (one untimed draw first).
        measured.push_back(renderer.timeFrames(combination, camera, repeats, 1).median());
        combinations.push_back(std::move(combination));
    }
    // Every feature: the cost's table holds only what the chosen model reads.
    const timemodel::FeatureTable table(scene, camera, view.setup->width(), view.setup->height());
    for (const timemodel::ModelResult& result : profile.models) {
        if (!result.fitted) continue;
        const std::unique_ptr<timemodel::TimeModel> model = timemodel::modelFromProfile(profile, result.name);
        std::vector<double> errors;
        for (std::size_t f = 0; f < combinations.size(); ++f) {
            const double estimate = model->estimateMs(table.features(combinations[f]));
            if (measured[f] > 0.0) errors.push_back(std::abs(measured[f] - estimate) / measured[f]);
        }
        const timemodel::ErrorStats e = timemodel::summarizeErrors(errors);
        rows.push_back({result.name, "this view, timed now", e.count, e.mean, e.median, e.p90, e.max});
    }
    return rows;
}

}  // namespace lodopt::evaluation
