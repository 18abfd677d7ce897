// lodopt: finds the best combination of discrete LODs for a scene under a render-time budget.
#include <iostream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "cli_common.hpp"
#include "interrupt.hpp"
#include "optimizer/problem.hpp"
#if defined(LODOPT_WITH_PAGMO)
#include "optimizer/pagmo_algorithms.hpp"
#endif
#include "scenes/scene.hpp"

namespace {

// Keeps freed image-sized blocks in the process instead of returning them to the system. By
// default glibc serves blocks over its (adaptive) mmap threshold with fresh pages and gives
// them back on free, so every per-frame buffer (a 512² fused metric allocates ~5 MB) is
// page-faulted in again; on this machine that made one-shot metrics::evaluate cost 15.9 ms
// instead of 3.0 ms (metrics_bench BM_FusedFitnessOneShot/512, docs/optimizer.md).
void keepFreedMemory() {
#if defined(__GLIBC__)
    mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest allowed value on 64-bit
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
#endif
}

}  // namespace

int main(int argc, char** argv) {
    using namespace lodopt::cli;
    keepFreedMemory();
#if defined(LODOPT_WITH_PAGMO)
    lodopt::optimizer::registerPagmoAlgorithms();  // before the commands list the algorithms
#endif
    CLI::App app{"lodopt: perceptual LOD combination optimizer", "lodopt"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("lodopt ") + LODOPT_VERSION);
    addSceneCommand(app);
    addRenderCommand(app);
    addMetricsCommand(app);
    addCalibrateCommand(app);
    addEstimateCommand(app);
    addOptimizeCommand(app);
    addCompareCommand(app);
    addSweepCommand(app);
    addThresholdsCommand(app);
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
