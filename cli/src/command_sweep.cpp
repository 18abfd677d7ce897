// lodopt sweep: the optimizer's answer at every viewpoint of a grid, a camera path, sampled views
// or a user's camera list, one file per finished view, then one merged table (sweep_files.hpp).
//
// Spread over processes three ways, all giving the same merged bytes: one process in view order;
// `mpirun -np N lodopt sweep ...`, whose ranks share a work queue (sweep_queue.hpp) and rank 0
// merges; or `--shard i/N` per job of an array, merged afterwards by `lodopt sweep --merge`. A
// view's answer depends only on the plan (settings and camera), so a view finished anywhere is
// as good as one finished here: --resume keeps every view file of the same plan and runs only
// the missing views, with any number of ranks.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "cli_common.hpp"
#include "evaluation/sweep.hpp"
#include "interrupt.hpp"
#include "optimize_run.hpp"
#include "progress.hpp"
#include "report_data.hpp"
#include "scenes/atomic_file.hpp"
#include "scenes/viewpoints.hpp"
#include "schedule_common.hpp"
#include "sweep_files.hpp"
#include "sweep_queue.hpp"
#include "sweep_run.hpp"
#include "timemodel/calibration.hpp"

namespace lodopt::cli {
namespace {

// The options that change a view's answer (checkIdentity); the cameras are in the plan itself.
nlohmann::json settingsSignature(const SweepOptions& o) {
    const OptimizeOptions& p = o.optimize;
    return {{"scene", p.scene},
            {"scene-seed", p.sceneSeed},
            {"seed", p.seed},
            {"size", p.size},
            {"shading", p.shading},
            {"budget-ms", p.budgetMs},
            {"algo", p.algorithm},
            {"max-evals", p.maxEvaluations},
            {"max-iterations", p.maxIterations},
            {"stable", p.stableIterations},
            {"max-seconds", p.maxSeconds},
            {"weights", p.weights},
            {"profile", p.profile},
            {"model", p.model},
            {"eval", p.evalPath},
            {"seed-from", p.seedFrom},
            {"particles", p.particles},
            {"paper", p.paper},
            {"fill", effectiveFillProbability(p)},
            {"judge", judgeIdentity(p.judge)}};
}

std::vector<scenes::Camera> camerasFromFile(const std::string& file) {
    std::ifstream stream(file, std::ios::binary);
    if (!stream) throw UsageError("--cameras " + file + ": cannot read the file");
    std::ostringstream text;
    text << stream.rdbuf();
    nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, false);
    if (json.is_object() && json.contains("cameras")) json = json["cameras"];
    if (json.is_discarded() || !json.is_array() || json.empty()) {
        throw UsageError(file + ": expected a non-empty JSON array of cameras (or {\"cameras\": [...]})");
    }
    std::vector<scenes::Camera> cameras;
    for (std::size_t k = 0; k < json.size(); ++k) {
        scenes::Camera camera = cameraFromJson(json[k], file + ": cameras[" + std::to_string(k) + "]");
        if (camera.name.empty()) camera.name = "camera_" + std::to_string(k);
        cameras.push_back(camera);
    }
    return cameras;
}

scenes::GroundBox parseGroundBox(const std::string& text) {
    const std::vector<double> values = parseNumberList(text, "--grid-box", "MIN_X,MIN_Z,MAX_X,MAX_Z");
    if (values.size() != 4 || !(values[0] <= values[2] && values[1] <= values[3])) {
        throw UsageError("--grid-box '" + text + "': expected MIN_X,MIN_Z,MAX_X,MAX_Z with min <= max");
    }
    return {float(values[0]), float(values[1]), float(values[2]), float(values[3])};
}

// Exactly one source: --grid, --path, --view-count or --cameras.
std::vector<scenes::Camera> sweepCameras(const scenes::Scene& scene, const SweepOptions& o) {
    const int sources = int(!o.grid.empty()) + int(!o.path.empty()) + int(o.viewCount > 0) + int(!o.cameras.empty());
    if (sources != 1) {
        throw UsageError("sweep: give exactly one of --grid SPEC, --path P, --view-count N or --cameras FILE");
    }
    if (!o.gridBox.empty() && o.grid.empty()) throw UsageError("--grid-box needs --grid");
    if (!o.cameras.empty()) return camerasFromFile(o.cameras);
    if (!o.path.empty()) return loadCameraPath(scene, o.path).frames;
    if (!o.grid.empty()) {
        scenes::CameraGrid grid;
        try {
            grid = scenes::parseCameraGrid(o.grid);
        } catch (const std::invalid_argument& error) {
            throw UsageError(std::string("--grid: ") + error.what());
        }
        if (!o.gridBox.empty()) grid.box = parseGroundBox(o.gridBox);
        if (!scene.views.empty()) grid.fovYDegrees = scene.views.front().fovYDegrees;
        return scenes::gridCameras(scene, grid);
    }
    if (scene.views.empty()) throw UsageError("scene '" + scene.name + "' has no views to sample around");
    timemodel::SplitMix64 rng(o.sampleSeed);
    std::vector<scenes::Camera> cameras;
    for (int k = 0; k < o.viewCount; ++k) {
        const scenes::Camera& around = scene.views[std::size_t(k) % scene.views.size()];
        scenes::Camera camera = timemodel::jitterCamera(around, rng);
        camera.name = "sweep_" + std::to_string(k) + "_" + around.name;
        cameras.push_back(camera);
    }
    return cameras;
}

// Views this process may run: all of them, or its shard's.
std::vector<std::size_t> ownViews(std::size_t count, const std::string& shard) {
    std::unique_ptr<ViewQueue> queue = shard.empty() ? makeLocalQueue(count) : makeShardQueue(count, shard);
    std::vector<std::size_t> views;
    while (auto view = queue->next()) views.push_back(*view);
    return views;
}

// Read-only checks of --out before any process writes: another sweep's plan is refused; view
// files of an unfinished sweep are refused without --resume. Returns whether the files of a
// finished sweep (sweep.json at least as new as every view file) are to be cleared.
bool checkOutFolder(const SweepOptions& o, const SweepPlan& plan) {
    const std::filesystem::path out(o.out);
    if (std::filesystem::exists(out / "sweep.plan.json")) {
        const SweepPlan saved = readPlan(out);
        checkIdentity((out / "sweep.plan.json").string(), saved.settings, plan.settings);
        if (planJson(saved) != planJson(plan)) {
            throw UsageError(o.out + " holds a sweep of other cameras; delete it or choose another --out");
        }
    }
    if (o.resume) return false;
    const std::vector<std::size_t> saved = savedViews(out);
    const std::vector<std::size_t> mine = ownViews(plan.cameras.size(), o.shard);
    std::vector<std::size_t> overlap;
    std::set_intersection(saved.begin(), saved.end(), mine.begin(), mine.end(), std::back_inserter(overlap));
    if (overlap.empty()) return false;
    std::error_code error;
    const auto merged = std::filesystem::last_write_time(out / "sweep.json", error);
    bool finished = !error;
    for (std::size_t view : saved) {
        finished = finished && std::filesystem::last_write_time(viewPath(out, view)) <= merged;
    }
    if (finished && o.shard.empty()) return true;
    throw UsageError(o.out + " holds " + std::to_string(overlap.size()) +
                     " view file(s) of an unfinished sweep: add --resume to keep them, or delete the folder");
}

// Testing aid: when LODOPT_TEST_SWEEP_HOLD_RANK equals this rank, the rank stops after searching
// its first view and before writing it, writes its pid to <out>/held_rank_R and waits (up to
// 60 s) to be killed, so a test can kill a rank mid-view whatever the machine's speed.
void holdForTest(const std::filesystem::path& out, int rank) {
    const char* held = std::getenv("LODOPT_TEST_SWEEP_HOLD_RANK");
    if (!held || std::atoi(held) != rank) return;
    scenes::writeTextAtomically((out / ("held_rank_" + std::to_string(rank))).string(), std::to_string(::getpid()));
    std::this_thread::sleep_for(std::chrono::seconds(60));
}

struct SweepRun {
    std::size_t computed = 0;  // views this process searched
    std::size_t resumed = 0;   // views this process found finished
};

// Takes views from `queue` until none is left, writing one file per view.
SweepRun runViews(const SweepOptions& o, PreparedScene& prepared, const SweepPlan& plan, ViewQueue& queue,
                  const OutputOptions& output) {
    const std::filesystem::path out(o.out);
    const optimizer::SearchOptions search = searchOptions(o.optimize, o.optimize.algorithm, o.optimize.seed);
    const evaluation::SearchViewSettings settings = searchViewSettings(o.optimize);
    const std::size_t total = plan.cameras.size();
    const bool reports = queue.rank() == 0 && o.shard.empty();
    Progress progress("sweep", total, output.quiet || !reports, Progress::Style::Lines);
    SweepRun run;
    while (const std::optional<std::size_t> view = queue.next()) {
        const scenes::Camera& camera = plan.cameras[*view];
        if (o.resume && !readViewFile(out, plan, *view).is_null()) {
            ++run.resumed;
        } else {
            const evaluation::SweepViewOutcome outcome =
                evaluation::sweepView(prepared.scene, camera, *prepared.renderer, prepared.metrics, prepared.estimator,
                                      prepared.readFeatures, settings, search);
            if (run.computed == 0) holdForTest(out, queue.rank());
            writeSweepJson(viewPath(out, *view), viewJson(plan, *view, outcome, queue.rank()));
            ++run.computed;
        }
        const std::size_t done = queue.finished();
        if (reports) progress.update(done, camera.name);
        pollInterrupt("sweep", done, total, "view", (out / "views").string());
    }
    progress.finish();
    return run;
}

nlohmann::json summaryJson(const SweepOptions& o, const SweepPlan& plan, const MergeSummary& merged, int ranks,
                           const SweepRun& run, double seconds) {
    return {{"scene", o.optimize.scene},
            {"views", plan.cameras.size()},
            {"objects", plan.objects.size()},
            {"budget_ms", plan.settings.value("budget-ms", 0.0)},
            {"ranks", ranks},
            {"computed_by_rank0", run.computed},
            {"mean_fitness", merged.meanFitness},
            {"mean_predicted_ms", merged.meanPredictedMs},
            {"max_predicted_ms", merged.maxPredictedMs},
            {"infeasible_views", merged.infeasible},
            {"files", merged.files},
            {"seconds", seconds}};
}

void printSummary(const nlohmann::json& s, bool json) {
    if (json) {
        printJson(s);
        return;
    }
    std::cout << "sweep: " << s["views"].get<std::size_t>() << " views of " << s["scene"].get<std::string>()
              << " (budget " << s["budget_ms"].get<double>() << " ms) "
              << (s["ranks"].get<int>() > 0 ? "on " + std::to_string(s["ranks"].get<int>()) + " rank(s)" : "merged")
              << " in " << formatDuration(s["seconds"].get<double>()) << ": mean fitness "
              << s["mean_fitness"].get<double>() << ", mean predicted " << s["mean_predicted_ms"].get<double>()
              << " ms (max " << s["max_predicted_ms"].get<double>() << ")";
    const auto infeasible = s["infeasible_views"].get<std::size_t>();
    if (infeasible > 0) std::cout << "; " << infeasible << " view(s) over budget even at the coarsest levels";
    std::cout << "\n";
    for (const auto& file : s["files"]) std::cout << "wrote " << file.get<std::string>() << "\n";
}

void runMerge(const SweepOptions& o, const OutputOptions& output) {
    std::vector<std::filesystem::path> sources(o.merge.begin(), o.merge.end());
    const SweepPlan plan = readPlan(sources.front());
    for (std::size_t k = 1; k < sources.size(); ++k) {
        if (planJson(readPlan(sources[k])) != planJson(plan)) {
            throw UsageError(sources[k].string() + ": a sweep of other settings or cameras than " +
                             sources.front().string());
        }
    }
    const auto start = std::chrono::steady_clock::now();
    const MergeSummary merged = mergeViews(plan, sources, o.out);
    nlohmann::json summary = summaryJson(o, plan, merged, 0, {}, 0.0);
    summary["scene"] = plan.settings.value("scene", "");
    summary["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary["merged_from"] = o.merge;
    printSummary(summary, output.json);
}

// The work queue replayed (evaluation::simulateWorkQueue) from a finished one-rank sweep's
// measured per-view times, cycled to --scaling-views views: scene load once per rank, the
// per-view overhead the one-rank run measured beyond its views' own seconds, and the merge
// scaled with the view count.
void runScaling(const SweepOptions& o, const OutputOptions& output) {
    const std::filesystem::path folder(o.scaling);
    const CsvTable timing = readCsv((folder / "sweep_timing.csv").string());
    const nlohmann::json measured = readJsonFile((folder / "sweep_run.json").string());
    std::vector<double> measuredViews;
    for (std::size_t r = 0; r < timing.rows.size(); ++r) {
        measuredViews.push_back(timing.number(r, "setup_seconds") + timing.number(r, "search_seconds"));
    }
    if (measuredViews.empty()) throw UsageError(folder.string() + "/sweep_timing.csv: no views");
    const int measuredRanks = measured.value("ranks", 1);
    const double sceneSeconds = measured.value("scene_seconds", 0.0);
    const double wall = measured.value("wall_seconds", 0.0);
    const double mergeSeconds = measured.value("merge_seconds", 0.0);
    double work = 0.0;
    for (double v : measuredViews) work += v;
    // Queue, file writing and the progress line, per view: only a one-rank run separates them.
    const double overhead =
        measuredRanks == 1 && measured.value("resumed_by_rank0", 0) == 0
            ? std::max(0.0, (wall - sceneSeconds - mergeSeconds - work) / double(measuredViews.size()))
            : 0.0;
    const std::size_t views = o.scalingViews > 0 ? std::size_t(o.scalingViews) : measuredViews.size();
    std::vector<double> cycled(views);
    for (std::size_t k = 0; k < views; ++k) cycled[k] = measuredViews[k % measuredViews.size()];
    const double merge = mergeSeconds * double(views) / double(measuredViews.size());
    nlohmann::json rows = nlohmann::json::array();
    for (int ranks : parseIntList(o.scalingRanks, "--scaling-ranks")) {
        if (ranks < 1) throw UsageError("--scaling-ranks: every count must be >= 1");
        const evaluation::QueueSimulation sim =
            evaluation::simulateWorkQueue(cycled, ranks, sceneSeconds, overhead, merge);
        double idle = 0.0;
        for (double seconds : sim.idleSeconds) idle += seconds;
        rows.push_back({{"ranks", ranks},
                        {"makespan_seconds", sim.makespanSeconds},
                        {"efficiency", sim.efficiency},
                        {"mean_idle_seconds", idle / double(ranks)},
                        {"scene_share", sceneSeconds / sim.makespanSeconds},
                        {"merge_share", merge / sim.makespanSeconds}});
    }
    const nlohmann::json document = {{"from", folder.string()},         {"measured_views", measuredViews.size()},
                                     {"measured_ranks", measuredRanks}, {"views", views},
                                     {"scene_seconds", sceneSeconds},   {"per_view_overhead_seconds", overhead},
                                     {"merge_seconds", merge},          {"simulated", rows}};
    if (output.json) return printJson(document);
    const Summary spread = summarize(measuredViews);
    std::cout << "sweep scaling (work queue replayed from " << measuredViews.size() << " measured views of "
              << folder.string() << ", cycled to " << views << "): view seconds median " << spread.median << ", min "
              << spread.min << ", max " << spread.max << "; scene load " << sceneSeconds << " s per rank, overhead "
              << overhead << " s per view, merge " << merge << " s\n";
    std::cout << "ranks  makespan s  efficiency  mean idle s  scene share  merge share\n";
    for (const nlohmann::json& row : rows) {
        std::printf("%5d  %10.1f  %10.3f  %11.1f  %11.3f  %11.3f\n", row["ranks"].get<int>(),
                    row["makespan_seconds"].get<double>(), row["efficiency"].get<double>(),
                    row["mean_idle_seconds"].get<double>(), row["scene_share"].get<double>(),
                    row["merge_share"].get<double>());
    }
}

void runSweep(SweepOptions o, const OutputOptions& output) {
    if (!o.merge.empty()) return runMerge(o, output);
    if (!o.scaling.empty()) return runScaling(o, output);
    checkAlgorithmName(o.optimize.algorithm);
    const bool mpi = launchedByMpi();
    if (mpi && !o.shard.empty()) throw UsageError("--shard: not under mpirun (the ranks already share the views)");
    if (mpi && !builtWithMpi()) {
        throw UsageError("this lodopt was built without MPI (libopenmpi-dev): run it without mpirun, or use --shard");
    }
    if (!o.shard.empty()) makeShardQueue(0, o.shard);  // a bad spec is refused before anything is written
    const auto start = std::chrono::steady_clock::now();
    o.optimize.view = "0";
    PreparedScene prepared = prepareScene(o.optimize);
    SweepPlan plan;
    plan.settings = settingsSignature(o);
    for (const scenes::Object& object : prepared.scene.objects) plan.objects.push_back(object.name);
    plan.cameras = sweepCameras(prepared.scene, o);
    const double sceneSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const bool clear = checkOutFolder(o, plan);  // every rank, before any writes

    std::unique_ptr<MpiSession> session;
    if (mpi) session = std::make_unique<MpiSession>();
    const int rank = session ? session->rank() : 0;
    try {
        if (rank == 0) {
            if (clear) {
                for (std::size_t view : savedViews(o.out)) std::filesystem::remove(viewPath(o.out, view));
                std::filesystem::remove(std::filesystem::path(o.out) / "sweep.json");
            }
            writeSweepJson(std::filesystem::path(o.out) / "sweep.plan.json", planJson(plan));
        }
        std::unique_ptr<ViewQueue> queue = session           ? session->makeQueue(plan.cameras.size())
                                           : o.shard.empty() ? makeLocalQueue(plan.cameras.size())
                                                             : makeShardQueue(plan.cameras.size(), o.shard);
        InterruptGuard interruptGuard;
        const SweepRun run = runViews(o, prepared, plan, *queue, output);
        queue->waitForAll();
        if (!queue->merges()) {
            if (!o.shard.empty() && !output.quiet) {
                std::cerr << "sweep: shard " << o.shard << ": " << run.computed << " view(s) searched, " << run.resumed
                          << " found finished, in " << o.out << "/views; merge the shards with: lodopt sweep --merge "
                          << o.out << " [more folders] --out DIR\n";
            }
            return;
        }
        const auto mergeStart = std::chrono::steady_clock::now();
        MergeSummary merged = mergeViews(plan, {std::filesystem::path(o.out)}, o.out);
        const auto end = std::chrono::steady_clock::now();
        const double seconds = std::chrono::duration<double>(end - start).count();
        // How this run spent its time, for `sweep --scaling` (not part of the merged table).
        const std::filesystem::path runFile = std::filesystem::path(o.out) / "sweep_run.json";
        writeJsonFile(runFile.string(), {{"format", "lodopt-sweep-run"},
                                         {"version", 1},
                                         {"ranks", queue->ranks()},
                                         {"threads", o.optimize.threads},
                                         {"views", plan.cameras.size()},
                                         {"computed_by_rank0", run.computed},
                                         {"resumed_by_rank0", run.resumed},
                                         {"scene_seconds", sceneSeconds},
                                         {"merge_seconds", std::chrono::duration<double>(end - mergeStart).count()},
                                         {"wall_seconds", seconds}});
        merged.files.push_back(runFile.string());
        if (o.printSummary) printSummary(summaryJson(o, plan, merged, queue->ranks(), run, seconds), output.json);
    } catch (const Interrupted& interrupted) {
        if (!session) throw;
        if (rank == 0) std::cerr << "lodopt: " << interrupted.what() << "\n";
        session->abort(kExitInterrupted);
    } catch (const UsageError& error) {
        if (!session) throw;
        std::cerr << "lodopt: rank " << rank << ": error: " << error.what() << "\n";
        session->abort(kExitBadInput);
    } catch (const std::exception& error) {
        if (!session) throw;
        std::cerr << "lodopt: rank " << rank << ": runtime error: " << error.what() << "\n";
        session->abort(kExitRuntime);
    }
}

}  // namespace

void runSweepCommand(const SweepOptions& options, const OutputOptions& output) {
    runSweep(options, output);
}

void addSweepSources(CLI::App& command, SweepOptions& options) {
    command.add_option("--grid", options.grid,
                       "Camera grid CxRxD@H[/P]: columns x rows x directions at height H, "
                       "pitch P degrees (default -10) over the scene's footprint");
    command.add_option("--grid-box", options.gridBox, "The grid's ground box MIN_X,MIN_Z,MAX_X,MAX_Z");
    command.add_option("--path", options.path, "Every frame of a camera path (name or JSON file)");
    command.add_option("--view-count", options.viewCount, "Views sampled around the scene's views")
        ->check(CLI::Range(1, 10000000));
    command.add_option("--sample-seed", options.sampleSeed, "Seed of the sampled views (--view-count)")
        ->capture_default_str();
    command.add_option("--cameras", options.cameras,
                       "JSON list of cameras (position, target, up, fov_y_degrees, near, far, name)");
    addSearchOptions(command, options.optimize);
    command.remove_option(command.get_option("--budget-ms"));
    command.add_option("--budget-ms", options.optimize.budgetMs, "Predicted render-time budget in milliseconds")
        ->check(CLI::PositiveNumber);
    command.add_option("--algo", options.optimize.algorithm, "Algorithm per view: " + algorithmList())
        ->capture_default_str();
}

void addSweepCommand(CLI::App& app) {
    auto options = std::make_shared<SweepOptions>();
    auto output = std::make_shared<OutputOptions>();
    options->optimize.seedFrom = "screensize,mckp";  // as optimize: never below the engine baseline
    CLI::App* command = app.add_subcommand(
        "sweep", "Optimize every viewpoint of a grid, path or camera list (one machine, --shard or mpirun)");
    addSceneOption(*command, options->optimize.scene);
    addSweepSources(*command, *options);
    command->add_option("--out", options->out, "Output folder")->capture_default_str();
    addResumeFlag(*command, options->resume, "the view files of an interrupted sweep (any number of ranks)");
    command->add_option("--shard", options->shard, "Run only views i, i+N, ... (i/N), for job arrays without MPI");
    command->add_option("--merge", options->merge, "Merge the view files of these sweep folders into --out")
        ->expected(1, -1);
    command->add_option("--scaling", options->scaling,
                        "Model the work queue at other rank counts from this finished sweep's measured view times");
    command->add_option("--scaling-ranks", options->scalingRanks, "Rank counts to model (--scaling)")
        ->capture_default_str();
    command
        ->add_option("--scaling-views", options->scalingViews, "Views to model, cycling the measured ones (--scaling)")
        ->check(CLI::Range(1L, 100000000L));
    addOutputOptions(*command, *output);
    command->callback([options, output] {
        if (options->merge.empty() && options->scaling.empty() && !(options->optimize.budgetMs > 0.0)) {
            throw UsageError("sweep: --budget-ms is required (except with --merge or --scaling)");
        }
        runSweep(*options, *output);
    });
}

}  // namespace lodopt::cli
