// lodopt metrics A.png B.png: every image metric of candidate A against reference B
// (docs/metrics.md), the fused fitness, and the judge's distance (butteraugli, metrics/judge.hpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli_common.hpp"
#include "metrics/metrics.hpp"
#include "renderer/renderer.hpp"

namespace lodopt::cli {

namespace {

struct MetricsOptions {
    std::string candidate;
    std::string reference;
    std::string weights = "1,1,1";
    std::string gray = "paper";
    std::string boundaryMode = "histogram";
    std::string informationMode = "histogram";
    int tolerance = 8;
    JudgeOptions judge;
    OutputOptions output;
};

// "1,1,1" -> SSIM, boundary entropy, information entropy weights: finite, >= 0, one > 0.
renderer::LoadedImage loadImage(const std::string& path) {
    try {
        return renderer::readImage(path);
    } catch (const renderer::RenderError& error) {
        throw UsageError(error.what());
    }
}

// An RGB image next to an RGBA one gets alpha 255 (what a renderer writes), so a PNG saved
// without alpha still compares with one saved with it. Gray against color is refused: the
// metrics would compare a gray level with a color.
void matchChannels(renderer::LoadedImage& a, const std::string& pathA, renderer::LoadedImage& b,
                   const std::string& pathB) {
    if (a.width != b.width || a.height != b.height) {
        throw UsageError("image sizes differ: " + pathA + " is " + std::to_string(a.width) + "x" +
                         std::to_string(a.height) + ", " + pathB + " is " + std::to_string(b.width) + "x" +
                         std::to_string(b.height));
    }
    if (a.channels == b.channels) return;
    auto toRgba = [](renderer::LoadedImage& image) {
        std::vector<std::uint8_t> rgba(std::size_t(image.width) * image.height * 4, 255);
        for (std::size_t i = 0, n = std::size_t(image.width) * image.height; i < n; ++i) {
            std::copy_n(image.pixels.data() + i * 3, 3, rgba.data() + i * 4);
        }
        image.pixels = std::move(rgba);
        image.channels = 4;
    };
    if (a.channels == 3 && b.channels == 4) return toRgba(a);
    if (a.channels == 4 && b.channels == 3) return toRgba(b);
    throw UsageError("channel counts differ: " + pathA + " has " + std::to_string(a.channels) + ", " + pathB + " has " +
                     std::to_string(b.channels) + " (gray and color images cannot be compared)");
}

nlohmann::json componentJson(bool computed, double candidate, double reference, double fidelity, double weight) {
    if (!computed) {
        return {{"computed", false},
                {"candidate", nullptr},
                {"reference", nullptr},
                {"fidelity", nullptr},
                {"weight", weight}};
    }
    return {{"computed", true},
            {"candidate", candidate},
            {"reference", reference},
            {"fidelity", fidelity},
            {"weight", weight}};
}

void printComponent(const char* name, bool computed, double candidate, double reference, double fidelity,
                    double weight) {
    char line[160];
    if (computed) {
        std::snprintf(line, sizeof line, "%-20s %12.6f %12.6f %10.6f %8g\n", name, candidate, reference, fidelity,
                      weight);
    } else {
        std::snprintf(line, sizeof line, "%-20s %12s %12s %10s %8g\n", name, "-", "-", "-", weight);
    }
    std::cout << line;
}

void runMetrics(const MetricsOptions& options) {
    metrics::MetricParameters parameters;
    parseWeights(options.weights, parameters);
    parameters.grayWeights = options.gray == "bt601"   ? metrics::GrayWeights::Bt601
                             : options.gray == "bt709" ? metrics::GrayWeights::Bt709
                                                       : metrics::GrayWeights::Paper;
    parameters.boundaryEntropyMode =
        options.boundaryMode == "paper" ? metrics::EntropyMode::Paper : metrics::EntropyMode::Histogram;
    parameters.informationEntropyMode =
        options.informationMode == "paper" ? metrics::EntropyMode::Paper : metrics::EntropyMode::Histogram;
    parameters.matchTolerance = options.tolerance;

    renderer::LoadedImage candidate = loadImage(options.candidate);
    renderer::LoadedImage reference = loadImage(options.reference);
    matchChannels(candidate, options.candidate, reference, options.reference);
    const metrics::JudgeParameters judgeSettings = *judgeParameters(options.judge);
    metrics::MetricResult result;
    std::optional<metrics::JudgeResult> verdict;
    try {
        result = metrics::evaluate(
            metrics::makeImageView(candidate.pixels.data(), candidate.width, candidate.height, candidate.channels),
            metrics::makeImageView(reference.pixels.data(), reference.width, reference.height, reference.channels),
            parameters);
        verdict = metrics::judge(
            metrics::makeImageView(candidate.pixels.data(), candidate.width, candidate.height, candidate.channels),
            metrics::makeImageView(reference.pixels.data(), reference.width, reference.height, reference.channels),
            judgeSettings);
    } catch (const metrics::MetricError& error) {
        throw UsageError(error.what());
    }

    if (options.output.json) {
        printJson(
            {{"candidate_file", options.candidate},
             {"reference_file", options.reference},
             {"width", candidate.width},
             {"height", candidate.height},
             {"channels", candidate.channels},
             {"gray", options.gray},
             {"ssim", componentJson(result.ssimComputed, result.ssim, 1.0, result.ssimFidelity, parameters.ssimWeight)},
             {"boundary_entropy", componentJson(result.boundaryEntropy.computed, result.boundaryEntropy.candidate,
                                                result.boundaryEntropy.reference, result.boundaryEntropy.fidelity,
                                                parameters.boundaryEntropyWeight)},
             {"information_entropy",
              componentJson(result.informationEntropy.computed, result.informationEntropy.candidate,
                            result.informationEntropy.reference, result.informationEntropy.fidelity,
                            parameters.informationEntropyWeight)},
             {"boundary_entropy_mode", options.boundaryMode},
             {"information_entropy_mode", options.informationMode},
             {"precision", result.precision},
             {"recall", result.recall},
             {"true_positives", result.truePositives},
             {"false_positives", result.falsePositives},
             {"false_negatives", result.falseNegatives},
             {"match_tolerance", options.tolerance},
             {"fitness", result.fitness},
             {"judge", judgeJson(verdict, judgeSettings)}});
        return;
    }
    std::cout << "candidate " << options.candidate << " vs reference " << options.reference << " (" << candidate.width
              << "x" << candidate.height << ", " << candidate.channels << " channels, gray " << options.gray << ")\n";
    char header[160];
    std::snprintf(header, sizeof header, "%-20s %12s %12s %10s %8s\n", "component", "candidate", "reference",
                  "fidelity", "weight");
    std::cout << header;
    printComponent("ssim", result.ssimComputed, result.ssim, 1.0, result.ssimFidelity, parameters.ssimWeight);
    printComponent("boundary_entropy", result.boundaryEntropy.computed, result.boundaryEntropy.candidate,
                   result.boundaryEntropy.reference, result.boundaryEntropy.fidelity, parameters.boundaryEntropyWeight);
    printComponent("information_entropy", result.informationEntropy.computed, result.informationEntropy.candidate,
                   result.informationEntropy.reference, result.informationEntropy.fidelity,
                   parameters.informationEntropyWeight);
    char line[200];
    std::snprintf(line, sizeof line, "precision %.6f  recall %.6f  (TP %llu, FP %llu, FN %llu, tolerance %d)\n",
                  result.precision, result.recall, static_cast<unsigned long long>(result.truePositives),
                  static_cast<unsigned long long>(result.falsePositives),
                  static_cast<unsigned long long>(result.falseNegatives), options.tolerance);
    std::cout << line;
    std::snprintf(line, sizeof line, "fitness %.6f\n", result.fitness);
    std::cout << line;
    std::snprintf(line, sizeof line, "judge: butteraugli %g-norm %.6f, max %.6f (%g nits, display scale %d)\n",
                  judgeSettings.pnorm, verdict->distance, verdict->maxDistance, judgeSettings.intensityTargetNits,
                  judgeSettings.displayScale);
    std::cout << line;
}

}  // namespace

void addMetricsCommand(CLI::App& app) {
    auto options = std::make_shared<MetricsOptions>();
    CLI::App* command = app.add_subcommand("metrics",
                                           "Score image A (candidate) against image B (reference): SSIM, entropies, "
                                           "precision/recall, fused fitness");
    command->add_option("candidate", options->candidate, "Candidate image A (PNG, JPEG or binary PNM)")->required();
    command->add_option("reference", options->reference, "Reference image B")->required();
    addWeightsOption(*command, options->weights);
    command->add_option("--gray", options->gray, "Gray weights: paper (0.30/0.59/0.11), bt601 or bt709")
        ->check(CLI::IsMember({"paper", "bt601", "bt709"}))
        ->capture_default_str();
    command
        ->add_option("--boundary-entropy", options->boundaryMode,
                     "histogram (Sobel magnitude histogram) or paper (literal Roberts-cross sum)")
        ->check(CLI::IsMember({"histogram", "paper"}))
        ->capture_default_str();
    command
        ->add_option("--information-entropy", options->informationMode,
                     "histogram (256-level gray histogram) or paper (literal intensity shares)")
        ->check(CLI::IsMember({"histogram", "paper"}))
        ->capture_default_str();
    command->add_option("--tolerance", options->tolerance, "Largest channel difference of matching pixels")
        ->check(CLI::Range(0, 255))
        ->capture_default_str();
    addJudgeOptions(*command, options->judge, false);
    addOutputOptions(*command, options->output);
    command->callback([options] { runMetrics(*options); });
}

}  // namespace lodopt::cli
