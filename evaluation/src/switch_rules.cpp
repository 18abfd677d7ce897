#include "evaluation/switch_rules.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "metrics/incremental_evaluator.hpp"
#include "optimizer/engine_rules.hpp"
#include "scenes/engine_lod.hpp"
#include "scenes/viewpoints.hpp"
#include "scheduler/screen_thresholds.hpp"

namespace lodopt::evaluation {

namespace {

// `given` continued to `count` values with its last ratio (a single value: halving).
std::vector<double> continued(std::vector<double> given, int count) {
    while (int(given.size()) < count) {
        const std::size_t n = given.size();
        const double ratio = n >= 2 ? given[n - 1] / given[n - 2] : 0.5;
        given.push_back(given.back() * ratio);
    }
    given.resize(std::size_t(std::max(count, 0)));
    return given;
}

ObjectThresholdList fromUnityHeights(const scenes::Scene& scene, const std::vector<double>& heights) {
    ObjectThresholdList list;
    for (const scenes::Object& object : scene.objects) {
        const scenes::Bounds bounds = scenes::worldBounds(object, 0);
        std::vector<double> sizes;
        for (double h : continued(heights, int(object.levels.size()) - 1)) {
            sizes.push_back(scenes::screenSizeFromUnityRelativeHeight(h, bounds));
        }
        list.push_back(std::move(sizes));
    }
    return list;
}

// The scene's own thresholds, when every object with levels has a usable one per switch.
std::optional<ObjectThresholdList> fileThresholds(const scenes::Scene& scene) {
    ObjectThresholdList list;
    for (const scenes::Object& object : scene.objects) {
        std::vector<double> sizes;
        for (std::size_t k = 0; k + 1 < object.levels.size(); ++k) {
            const std::optional<float>& coverage = object.levels[k].screenCoverage;
            if (!coverage || !(*coverage > 0.0f) || !std::isfinite(*coverage)) return std::nullopt;
            sizes.push_back(std::min(double(*coverage), sizes.empty() ? INFINITY : sizes.back()));
        }
        list.push_back(std::move(sizes));
    }
    return list;
}

void checkViews(const scenes::Scene& scene, std::span<const ViewChoices> views) {
    for (const ViewChoices& view : views) {
        if (view.screenSizes.size() != scene.objects.size()) {
            throw std::invalid_argument("switch rules: a view needs one screen size per object");
        }
        for (int object : view.searched) {
            if (object < 0 || std::size_t(object) >= scene.objects.size()) {
                throw std::invalid_argument("switch rules: a view names object " + std::to_string(object));
            }
        }
    }
}

double mean(const std::vector<double>& values) {
    double sum = 0.0;
    for (double v : values) sum += v;
    return values.empty() ? NAN : sum / double(values.size());
}

// Thresholds from each level's own screen size (levelSize(object, k) for k >= 1, the size at or
// below which the engine allows level k): t_k = the largest size of the levels coarser than k,
// so an object takes the coarsest level its size allows. Infinite sizes (a level identical to
// level 0) become a size no object reaches from below. Null when a level has no geometric error.
template <typename LevelSize>
std::optional<ObjectThresholdList> geometricThresholds(const scenes::Scene& scene, LevelSize levelSize) {
    constexpr double kAlways = 1e12;
    ObjectThresholdList list;
    for (const scenes::Object& object : scene.objects) {
        const int levels = int(object.levels.size());
        std::vector<double> sizes(std::size_t(std::max(levels - 1, 0)), 0.0);
        double largest = 0.0;
        for (int k = levels - 1; k >= 1; --k) {
            if (!object.levels[std::size_t(k)].geometricError) return std::nullopt;
            largest = std::max(largest, std::min(levelSize(object, k), kAlways));
            sizes[std::size_t(k - 1)] = largest;
        }
        list.push_back(std::move(sizes));
    }
    return list;
}

}  // namespace

std::vector<SwitchRuleThresholds> defaultSwitchRules(const scenes::Scene& scene, int viewportHeight) {
    std::vector<SwitchRuleThresholds> rules;
    if (std::optional<ObjectThresholdList> file = fileThresholds(scene)) rules.push_back({"file", std::move(*file)});
    rules.push_back({"msft_default", fromUnityHeights(scene, {0.5, 0.2, 0.01})});
    rules.push_back({"unitygltf_halving", fromUnityHeights(scene, {0.5})});
    ObjectThresholdList unreal;
    for (const scenes::Object& object : scene.objects) {
        unreal.push_back(continued({0.75, 0.75 * 0.75}, int(object.levels.size()) - 1));
    }
    rules.push_back({"unreal_075", std::move(unreal)});
    if (viewportHeight > 0) {
        auto radius = [](const scenes::Object& object) {
            return std::max(double(scenes::worldBounds(object, 0).sphereRadius), 1e-9);
        };
        if (auto pixel = geometricThresholds(scene, [&](const scenes::Object& object, int k) {
                return optimizer::pixelErrorScreenSize(*object.levels[std::size_t(k)].geometricError, radius(object),
                                                       1.0, double(viewportHeight));
            })) {
            rules.push_back({"pixelerror", std::move(*pixel)});
        }
        if (auto unrealAuto = geometricThresholds(scene, [&](const scenes::Object& object, int k) {
                return optimizer::unrealAutoScreenSize(*object.levels[std::size_t(k)].geometricError, radius(object),
                                                       1.0);
            })) {
            rules.push_back({"unreal_auto", std::move(*unrealAuto)});
        }
    }
    return rules;
}

scenes::Combination ruleCombination(const scenes::Scene& scene, const ObjectThresholdList& thresholds,
                                    const ViewChoices& view, double bias) {
    scenes::Combination levels = scenes::coarsestCombination(scene);
    for (int object : view.searched) {
        const std::size_t i = std::size_t(object);
        levels[i] = scheduler::levelForScreenSize(thresholds.at(i), view.screenSizes[i] * bias);
    }
    return levels;
}

RuleSwitches countRuleSwitches(const scenes::Scene& scene, const ObjectThresholdList& thresholds,
                               std::span<const scenes::Camera> path, double hysteresis) {
    if (!(hysteresis >= 0.0 && hysteresis < 1.0)) throw std::invalid_argument("countRuleSwitches: hysteresis in [0, 1)");
    if (thresholds.size() != scene.objects.size()) throw std::invalid_argument("countRuleSwitches: one list per object");
    RuleSwitches result;
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const std::vector<double>& t = thresholds[i];
        if (t.empty()) continue;
        const scenes::Bounds bounds = scenes::worldBounds(scene.objects[i], 0);
        int current = -1;
        for (const scenes::Camera& camera : path) {
            const double size = scenes::screenSize(bounds, camera);
            int level = int(t.size());
            for (std::size_t k = 0; k < t.size(); ++k) {
                const double threshold = int(k) == current - 1 ? t[k] / (1.0 - hysteresis) : t[k];
                if (size >= threshold) {
                    level = int(k);
                    break;
                }
            }
            if (current >= 0) {
                result.switches += level != current ? 1 : 0;
                ++result.objectFrames;
            }
            current = level;
        }
    }
    return result;
}

LodBias fitLodBias(const scenes::Scene& scene, const ObjectThresholdList& thresholds, std::span<const ViewChoices> views,
                   const ViewTimeMs& predictMs, double budgetMs) {
    if (views.empty()) throw std::invalid_argument("fitLodBias: no views");
    if (!(budgetMs > 0.0) || !std::isfinite(budgetMs)) throw std::invalid_argument("fitLodBias: the budget must be > 0");
    checkViews(scene, views);
    // Every bias at which some needed object changes level: s * b reaches a threshold.
    std::vector<double> crossings;
    for (const ViewChoices& view : views) {
        for (int object : view.searched) {
            const double size = view.screenSizes[std::size_t(object)];
            if (!(size > 0.0) || !std::isfinite(size)) continue;
            for (double t : thresholds.at(std::size_t(object))) crossings.push_back(t / size);
        }
    }
    std::sort(crossings.begin(), crossings.end());
    crossings.erase(std::unique(crossings.begin(), crossings.end()), crossings.end());
    auto meanMs = [&](double bias) {
        double sum = 0.0;
        for (std::size_t v = 0; v < views.size(); ++v) {
            sum += predictMs(v, ruleCombination(scene, thresholds, views[v], bias));
        }
        return sum / double(views.size());
    };
    // Below the first crossing every needed object is coarsest.
    const double coarsestBias = crossings.empty() ? 1.0 : crossings.front() / 2.0;
    LodBias result{coarsestBias, meanMs(coarsestBias), false};
    result.meetsBudget = result.meanPredictedMs <= budgetMs;
    if (!result.meetsBudget) return result;
    // The mean is a step function of the bias, constant from one crossing to the next: find the
    // last crossing whose mean is within the budget.
    std::size_t low = 0, high = crossings.size();  // crossings[0, low) fit; [high, end) do not
    while (low < high) {
        const std::size_t middle = low + (high - low) / 2;
        if (meanMs(crossings[middle]) <= budgetMs) low = middle + 1;
        else high = middle;
    }
    if (low > 0) {
        result.bias = crossings[low - 1];
        result.meanPredictedMs = meanMs(result.bias);
    }
    return result;
}

RuleComparison compareSwitchRules(const scenes::Scene& scene, std::span<const ScoredView> views,
                                  std::span<const SwitchRuleThresholds> rules, renderer::Renderer& renderer,
                                  const metrics::MetricParameters& metrics, const FrameTimeEstimator& estimator,
                                  const timemodel::FeatureSet& readFeatures, const RuleComparisonSettings& settings) {
    std::vector<ScoredView> heldOut;
    std::vector<ViewChoices> fitting;
    std::vector<scenes::Camera> fittingCameras;
    for (std::size_t v = 0; v < views.size(); ++v) {
        if (isHeldOutView(v, settings.holdoutEvery)) {
            heldOut.push_back(views[v]);
        } else {
            fitting.push_back(views[v].choices);
            fittingCameras.push_back(views[v].camera);
        }
    }
    if (fitting.empty()) throw std::invalid_argument("compareSwitchRules: no fitting view");
    auto tableOf = [&](const scenes::Camera& camera) {
        return timemodel::FeatureTable(scene, camera, settings.width, settings.height,
                                       timemodel::FeatureTable::kDepthPassCells, readFeatures);
    };
    std::vector<timemodel::FeatureTable> fittingTables, heldOutTables;
    for (const scenes::Camera& camera : fittingCameras) fittingTables.push_back(tableOf(camera));
    for (const ScoredView& view : heldOut) heldOutTables.push_back(tableOf(view.camera));
    auto predictOn = [&](const std::vector<timemodel::FeatureTable>& tables) -> ViewTimeMs {
        return [&tables, &estimator](std::size_t v, const scenes::Combination& levels) {
            return estimator(tables[v].features(levels));
        };
    };

    RuleComparison comparison;
    comparison.fittingViews = int(fitting.size());
    comparison.heldOutViews = int(heldOut.size());
    for (const SwitchRuleThresholds& rule : rules) {
        RuleOutcome outcome;
        outcome.rule = rule.name;
        outcome.bias = fitLodBias(scene, rule.thresholds, fitting, predictOn(fittingTables), settings.budgetMs);
        comparison.rules.push_back(outcome);
    }

    // Per held-out view: the reference, the all-coarsest combination, then each rule's.
    std::vector<double> optimizerFitness, coarsestFitness;
    std::vector<std::vector<double>> ruleFitness(rules.size()), ruleMs(rules.size());
    std::vector<double> ruleGain(rules.size(), 0.0);
    double optimizerGainSum = 0.0;
    renderer::Frame frame;
    auto fitnessOf = [&](metrics::IncrementalEvaluator& scorer, const scenes::Combination& levels,
                         const scenes::Camera& camera) {
        renderer.render(levels, camera, frame);
        scorer.setCandidate(metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4));
        return scorer.result().fitness;
    };
    for (std::size_t v = 0; v < heldOut.size(); ++v) {
        const ScoredView& view = heldOut[v];
        renderer.render(scenes::referenceCombination(scene), view.camera, frame);
        metrics::IncrementalEvaluator scorer(metrics::makeImageView(frame.rgba.data(), frame.width, frame.height, 4),
                                             metrics);
        const double coarsest = fitnessOf(scorer, scenes::coarsestCombination(scene), view.camera);
        optimizerFitness.push_back(view.fitness);
        coarsestFitness.push_back(coarsest);
        const double optimizerGain = view.fitness - coarsest;
        for (std::size_t r = 0; r < rules.size(); ++r) {
            const scenes::Combination levels =
                ruleCombination(scene, rules[r].thresholds, view.choices, comparison.rules[r].bias.bias);
            const double fitness = fitnessOf(scorer, levels, view.camera);
            ruleFitness[r].push_back(fitness);
            ruleMs[r].push_back(estimator(heldOutTables[v].features(levels)));
            if (optimizerGain > kMinOptimizerGain) ruleGain[r] += fitness - coarsest;
        }
        if (optimizerGain > kMinOptimizerGain) {
            ++comparison.gainViews;
            optimizerGainSum += optimizerGain;
        }
    }
    comparison.optimizerMeanFitness = mean(optimizerFitness);
    comparison.coarsestMeanFitness = mean(coarsestFitness);
    for (std::size_t r = 0; r < rules.size(); ++r) {
        RuleOutcome& outcome = comparison.rules[r];
        outcome.meanFitness = mean(ruleFitness[r]);
        outcome.gainFraction = comparison.gainViews > 0 ? ruleGain[r] / optimizerGainSum : NAN;
        outcome.meanPredictedMs = mean(ruleMs[r]);
        const auto over = std::count_if(ruleMs[r].begin(), ruleMs[r].end(),
                                        [&](double ms) { return ms > settings.budgetMs; });
        outcome.overBudgetShare = ruleMs[r].empty() ? NAN : double(over) / double(ruleMs[r].size());
    }
    return comparison;
}

}  // namespace lodopt::evaluation
