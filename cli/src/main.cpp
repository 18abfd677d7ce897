// lodopt: finds the best combination of discrete LODs for a scene under a render-time budget.
#include <iostream>

#include "cli_common.hpp"
#include "interrupt.hpp"
#include "optimizer/problem.hpp"
#include "scenes/scene.hpp"

int main(int argc, char** argv) {
    using namespace lodopt::cli;
    CLI::App app{"lodopt: perceptual LOD combination optimizer", "lodopt"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "lodopt 0.1.0");
    addSceneCommand(app);
    addRenderCommand(app);
    addMetricsCommand(app);
    addCalibrateCommand(app);
    addEstimateCommand(app);
    addOptimizeCommand(app);
    addCompareCommand(app);
    addTuneCommand(app);
    addScheduleCommand(app);
    addReportCommand(app);
    addBenchCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        int code = app.exit(error);
        return code == 0 ? kExitOk : kExitBadInput;
    } catch (const Interrupted& interrupted) {
        // A long command stopped at a unit boundary; its message says how to resume.
        std::cerr << "lodopt: " << interrupted.what() << "\n";
        return kExitInterrupted;
    } catch (const UsageError& error) {
        std::cerr << "lodopt: error: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const lodopt::optimizer::ProblemError& error) {
        // Includes BudgetError: a budget below the cheapest combination, with the minimum.
        std::cerr << "lodopt: error: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const lodopt::scenes::SceneError& error) {
        std::cerr << "lodopt: error: " << error.what() << "\n";
        return kExitBadInput;
    } catch (const std::exception& error) {
        std::cerr << "lodopt: runtime error: " << error.what() << "\n";
        return kExitRuntime;
    }
    return kExitOk;
}
