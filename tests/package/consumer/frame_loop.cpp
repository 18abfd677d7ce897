// An engine's frame loop with the lodopt scheduler: load tuned coefficients, index the scene
// once, then per frame decide the levels from the camera, draw, and report the measured time.
//
//   frame_loop COEFFICIENTS.json BUDGET_MS FRAMES
//
// The scene is the built-in forest and its walk-through, the time model the profile the
// library ships for it; "drawing" takes 10% longer than predicted, so the feedback has work to
// do. Prints one line per frame: frame, predicted ms, budget met (0/1), feedback scale, levels.
// Exit codes: 0 ok, 1 runtime failure, 2 bad arguments.
#include <cstdio>
#include <exception>
#include <string>

#include "scenes/builtin.hpp"
#include "scheduler/coefficients.hpp"
#include "scheduler/scheduler.hpp"
#include "timemodel/profile.hpp"

int main(int argc, char** argv) {
    using namespace lodopt;
    if (argc != 4) {
        std::fprintf(stderr, "usage: frame_loop COEFFICIENTS.json BUDGET_MS FRAMES\n");
        return 2;
    }
    double budgetMs = 0.0;
    int frames = 0;
    try {
        budgetMs = std::stod(argv[2]);
        frames = std::stoi(argv[3]);
    } catch (const std::exception&) {
        std::fprintf(stderr, "frame_loop: BUDGET_MS and FRAMES must be numbers\n");
        return 2;
    }
    try {
        const scenes::Scene scene = scenes::makeBuiltinScene("forest");
        const timemodel::DeviceProfile profile = timemodel::shippedProfile(scene.name);
        std::unique_ptr<timemodel::TimeModel> model = timemodel::modelFromProfile(profile);
        const scheduler::SceneIndex index(scene, profile.width, profile.height, scheduler::FeatureMode::Bounds, 0,
                                          model->readFeatures());
        scheduler::SchedulerParameters parameters;
        parameters.coefficients = scheduler::loadCoefficients(argv[1]);
        parameters.budgetMs = budgetMs;
        scheduler::FrameScheduler frameScheduler(index, std::move(model), parameters);

        const scenes::CameraPath& path = scene.paths.at(0);
        for (int f = 0; f < frames && f < int(path.frames.size()); ++f) {
            const scheduler::FrameDecision& decision =
                frameScheduler.decide(path.frames[std::size_t(f)], double(f) / double(path.framesPerSecond));
            std::printf("%d %.9g %d", f, decision.predictedMs, decision.budgetMet ? 1 : 0);
            const double measuredMs = 1.1 * decision.predictedMs;  // stands in for the engine's timer
            frameScheduler.reportMeasuredMs(measuredMs);
            std::printf(" %.9g", frameScheduler.model().feedbackScale());
            for (int level : decision.levels) std::printf(" %d", level);
            std::printf("\n");
        }
        return 0;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "frame_loop: %s\n", error.what());
        return 1;
    }
}
