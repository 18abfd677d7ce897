// Links every library of the installed package and calls into each, so that a project using
// all of them is shown to configure (each library's private dependencies found again by
// lodoptConfig.cmake), link and run: the harbor drawn at its finest and coarsest levels, judged,
// scored, priced by a feature table, searched by a baseline, and one scheduler decision.
#include <cstdio>

#include "evaluation/evaluation.hpp"
#include "metrics/judge.hpp"
#include "metrics/metrics.hpp"
#include "optimizer/optimizer.hpp"
#include "renderer/renderer.hpp"
#include "scenes/builtin.hpp"
#include "scheduler/importance.hpp"
#include "timemodel/features.hpp"
#ifdef LODOPT_CONSUMER_PAGMO
#include "optimizer/pagmo_algorithms.hpp"
#endif

int main() {
    using namespace lodopt;
    const scenes::Scene scene = scenes::loadScene("harbor");
    renderer::RenderSettings settings;
    settings.width = 64;
    settings.height = 64;
    renderer::Renderer renderer(scene, settings);
    const scenes::Camera& camera = scene.views.at(0);
    const renderer::Frame finest = renderer.render(scenes::referenceCombination(scene), camera);
    const renderer::Frame coarsest = renderer.render(scenes::coarsestCombination(scene), camera);
    const metrics::JudgeResult judged = evaluation::judgeFrame(coarsest, finest, metrics::JudgeParameters{});
    const double ssim =
        metrics::ssim(metrics::makeImageView(coarsest.rgba.data(), 64, 64, 4),
                      metrics::makeImageView(finest.rgba.data(), 64, 64, 4), metrics::MetricParameters{});
    const std::size_t features = timemodel::allFeatures().size();
    const bool greedy = optimizer::makeAlgorithm("greedy", 1) != nullptr;
    scheduler::ObjectView view;
    view.distance = 10.0;
    view.projectedArea = 4.0;
    const double denominator = scheduler::importanceDenominator(view, scheduler::ImportanceCoefficients{});
#ifdef LODOPT_CONSUMER_PAGMO
    optimizer::registerPagmoAlgorithms();
#endif
    std::printf("objects %zu judge %.4f ssim %.4f features %zu greedy %d importance %.4f\n", scene.objects.size(),
                judged.distance, ssim, features, int(greedy), denominator);
    return judged.distance > 0.0 && ssim < 1.0 && greedy ? 0 : 1;
}
