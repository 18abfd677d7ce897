// Baselines without hints. Greedy after T. A. Funkhouser and C. H. Séquin, "Adaptive display
// algorithm for interactive frame rates during visualization of complex virtual
// environments", SIGGRAPH 1993 (benefit/cost ordering); exhaustive enumeration; random search.
#include "optimizer/baselines.hpp"

#include <limits>
#include <stdexcept>

#include "optimizer/mckp.hpp"
#include "optimizer/random.hpp"
#include "optimizer/repair.hpp"
#include "optimizer/search_state.hpp"

namespace lodopt::optimizer {

Greedy::Greedy(GreedyParameters parameters) : mParameters(parameters) {}

Result Greedy::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), false);
    const bool useSurrogate = mParameters.benefit == BenefitSource::Surrogate;
    std::vector<std::vector<double>> measured;
    if (useSurrogate && problem.surrogateLoss.empty()) {
        const std::int64_t needed = surrogateEvaluations(problem.levelCounts) + 1;
        if (state.evaluator().remainingEvaluations() < needed) {
            throw std::invalid_argument("greedy: maxEvaluations = " + std::to_string(termination.maxEvaluations) +
                                        " is below the " + std::to_string(needed) +
                                        " evaluations needed to measure the surrogate loss and score the result");
        }
        measured = measureSurrogateLoss(problem, state.evaluator());
    }
    const auto& surrogate = problem.surrogateLoss.empty() ? measured : problem.surrogateLoss;

    Combination current = coarsestCombination(problem);
    std::vector<Combination> steps;
    std::vector<int> stepVariable;
    std::vector<double> stepExtraMs;
    std::vector<Score> scores(1);
    std::vector<double> predictedMs(1);
    double currentFitness = 0.0;
    if (!useSurrogate) {
        if (state.evaluate(std::span<const Combination>(&current, 1), scores, predictedMs) == 0) {
            throw std::invalid_argument("greedy: the evaluation budget is spent before the first evaluation");
        }
        currentFitness = scores[0].fitness;
        if (state.endIteration(currentFitness)) return state.finish();
    }

    for (;;) {
        // Candidate steps: one variable one level finer, within the budget.
        steps.clear();
        stepVariable.clear();
        stepExtraMs.clear();
        const double currentMs = problem.cost->predictMs(current);
        for (std::size_t i = 0; i < current.size(); ++i) {
            if (current[i] == 0) continue;
            Combination step = current;
            --step[i];
            const double stepMs = problem.cost->predictMs(step);
            if (stepMs > problem.budgetMs) continue;
            steps.push_back(std::move(step));
            stepVariable.push_back(static_cast<int>(i));
            stepExtraMs.push_back(stepMs - currentMs);
        }
        if (steps.empty()) break;

        std::size_t scored = steps.size();
        if (!useSurrogate) {
            scores.resize(steps.size());
            predictedMs.resize(steps.size());
            scored = state.evaluate(steps, scores, predictedMs);
        }
        // Highest gain per extra millisecond; a step costing <= 0 ms ranks first, by gain.
        int chosen = -1;
        double chosenGain = 0.0;
        double chosenRatio = 0.0;
        for (std::size_t k = 0; k < scored; ++k) {
            const auto variable = static_cast<std::size_t>(stepVariable[k]);
            const double gain = useSurrogate ? surrogate[variable][static_cast<std::size_t>(current[variable])] -
                                                   surrogate[variable][static_cast<std::size_t>(steps[k][variable])]
                                             : scores[k].fitness - currentFitness;
            if (!(gain > 0.0)) continue;
            const double ratio = stepExtraMs[k] > 0.0 ? gain / stepExtraMs[k] : std::numeric_limits<double>::infinity();
            if (chosen < 0 || ratio > chosenRatio || (ratio == chosenRatio && gain > chosenGain)) {
                chosen = static_cast<int>(k);
                chosenGain = gain;
                chosenRatio = ratio;
            }
        }
        if (chosen >= 0) {
            current = steps[static_cast<std::size_t>(chosen)];
            if (!useSurrogate) currentFitness = scores[static_cast<std::size_t>(chosen)].fitness;
        }
        if (!useSurrogate && state.endIteration(meanFitness(scores, scored))) return state.finish();
        if (chosen < 0) break;
    }

    if (useSurrogate) {
        if (state.evaluate(std::span<const Combination>(&current, 1), scores, predictedMs) == 0) {
            throw std::invalid_argument("greedy: the evaluation budget is spent before the final evaluation");
        }
        state.endIteration(scores[0].fitness);
    }
    state.complete();
    return state.finish();
}

Exhaustive::Exhaustive(ExhaustiveParameters parameters) : mParameters(parameters) {
    if (!(mParameters.maxCombinations >= 1.0)) {
        throw std::invalid_argument("exhaustive: maxCombinations = " + std::to_string(mParameters.maxCombinations) +
                                    ", must be >= 1");
    }
    if (mParameters.batchSize < 1) {
        throw std::invalid_argument("exhaustive: batchSize = " + std::to_string(mParameters.batchSize) +
                                    ", must be >= 1");
    }
}

Result Exhaustive::run(const Problem& problem, const Termination& termination) const {
    // Check the size before anything is evaluated.
    if (!problem.levelCounts.empty()) {
        const double count = combinationCount(problem.levelCounts);
        if (count > mParameters.maxCombinations) {
            throw ProblemError("exhaustive: " + std::to_string(problem.levelCounts.size()) + " variables give " +
                               std::to_string(count) + " combinations, more than the limit of " +
                               std::to_string(mParameters.maxCombinations));
        }
    }
    SearchState state(problem, termination, name(), false);
    const auto batchSize = static_cast<std::size_t>(mParameters.batchSize);
    std::vector<Combination> batch;
    batch.reserve(batchSize);
    std::vector<Score> scores(batchSize);
    std::vector<double> predictedMs(batchSize);

    // Evaluates the batch; true when the search must stop early.
    auto flush = [&]() {
        const std::size_t scored = state.evaluate(batch, std::span<Score>(scores.data(), batch.size()),
                                                  std::span<double>(predictedMs.data(), batch.size()));
        const bool stop = state.endIteration(meanFitness(scores, scored));
        batch.clear();
        // A budget spent exactly is not a reason to stop: the next feasible candidate decides.
        return stop && !(state.stopReason() == StopReason::MaxEvaluations && !state.truncated());
    };

    Combination combination(problem.levelCounts.size(), 0);
    for (bool done = false; !done;) {
        if (problem.cost->predictMs(combination) <= problem.budgetMs) {
            batch.push_back(combination);
            if (batch.size() == batchSize && flush()) return state.finish();
        }
        // Next combination, last variable fastest; done after the last one wraps around.
        for (std::size_t i = combination.size();;) {
            if (i == 0) {
                done = true;
                break;
            }
            --i;
            if (++combination[i] < problem.levelCounts[i]) break;
            combination[i] = 0;
        }
    }
    if (!batch.empty() && flush()) return state.finish();
    state.complete();
    return state.finish();
}

RandomSearch::RandomSearch(RandomSearchParameters parameters) : mParameters(parameters) {
    if (mParameters.samplesPerIteration < 1) {
        throw std::invalid_argument("random: samplesPerIteration = " + std::to_string(mParameters.samplesPerIteration) +
                                    ", must be >= 1");
    }
}

Result RandomSearch::run(const Problem& problem, const Termination& termination) const {
    SearchState state(problem, termination, name(), true);
    Random random(mParameters.seed);
    const auto count = static_cast<std::size_t>(mParameters.samplesPerIteration);
    std::vector<Combination> batch(count, Combination(problem.levelCounts.size()));
    std::vector<Score> scores(count);
    std::vector<double> predictedMs(count);
    do {
        for (Combination& combination : batch) {
            for (std::size_t i = 0; i < combination.size(); ++i)
                combination[i] = random.belowInt(problem.levelCounts[i]);
            repairToBudget(problem, combination);
        }
        const std::size_t scored = state.evaluate(batch, scores, predictedMs);
        if (state.endIteration(meanFitness(scores, scored))) break;
    } while (true);
    return state.finish();
}

}  // namespace lodopt::optimizer
