// Test fixtures for the optimizer: tiny problems whose optimum can be worked out by hand,
// formula evaluators, a non-additive cost and a thread-pool evaluator.
#pragma once

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "optimizer/optimizer.hpp"

namespace lodopt::optimizer::testing {

// fitness = 1 - sum_i loss[i][level_i]; counts the evaluate() calls it really makes.
class TableEvaluator final : public Evaluator {
public:
    explicit TableEvaluator(std::vector<std::vector<double>> loss) : mLoss(std::move(loss)) {}
    Score evaluate(const Combination& combination) override {
        ++mCalls;
        Score score;
        score.fitness = 1.0;
        for (std::size_t i = 0; i < combination.size(); ++i)
            score.fitness -= mLoss[i][static_cast<std::size_t>(combination[i])];
        return score;
    }
    const std::vector<std::vector<double>>& loss() const { return mLoss; }
    int calls() const { return mCalls.load(); }

private:
    std::vector<std::vector<double>> mLoss;
    std::atomic<int> mCalls{0};
};

// Any formula; counts calls. The formula must be thread-safe for ThreadPoolEvaluator.
class FormulaEvaluator final : public Evaluator {
public:
    explicit FormulaEvaluator(std::function<double(const Combination&)> formula) : mFormula(std::move(formula)) {}
    Score evaluate(const Combination& combination) override {
        ++mCalls;
        Score score;
        score.fitness = mFormula(combination);
        return score;
    }
    int calls() const { return mCalls.load(); }

private:
    std::function<double(const Combination&)> mFormula;
    std::atomic<int> mCalls{0};
};

// Spreads each batch over a small persistent pool of worker threads that take candidates in
// whatever order they get to them; `inner.evaluate` must be thread-safe.
class ThreadPoolEvaluator final : public Evaluator {
public:
    ThreadPoolEvaluator(Evaluator& inner, int threads) : mInner(inner) {
        for (int t = 0; t < threads; ++t) mWorkers.emplace_back([this] { work(); });
    }
    ~ThreadPoolEvaluator() override {
        {
            std::lock_guard lock(mMutex);
            mQuit = true;
        }
        mWake.notify_all();
        for (auto& worker : mWorkers) worker.join();
    }
    Score evaluate(const Combination& combination) override { return mInner.evaluate(combination); }
    void evaluateBatch(std::span<const Combination> combinations, std::span<Score> scores) override {
        std::unique_lock lock(mMutex);
        mCombinations = combinations;
        mScores = scores;
        mNext = 0;
        mDone = 0;
        ++mGeneration;
        mWake.notify_all();
        mFinished.wait(lock, [&] { return mDone == mCombinations.size(); });
        ++mBatches;
    }
    int batches() const { return mBatches; }

private:
    void work() {
        std::size_t seen = 0;
        std::unique_lock lock(mMutex);
        for (;;) {
            mWake.wait(lock, [&] { return mQuit || (mGeneration != seen && mNext < mCombinations.size()); });
            if (mQuit) return;
            const std::size_t k = mNext++;
            if (mNext >= mCombinations.size()) seen = mGeneration;
            lock.unlock();
            const Score score = mInner.evaluate(mCombinations[k]);
            lock.lock();
            mScores[k] = score;
            if (++mDone == mCombinations.size()) mFinished.notify_all();
        }
    }

    Evaluator& mInner;
    std::vector<std::thread> mWorkers;
    std::mutex mMutex;
    std::condition_variable mWake;
    std::condition_variable mFinished;
    std::span<const Combination> mCombinations;
    std::span<Score> mScores;
    std::size_t mNext = 0;
    std::size_t mDone = 0;
    std::size_t mGeneration = 0;
    bool mQuit = false;
    int mBatches = 0;
};

// Non-additive cost after CITY17: base + max(sum gpu, sum cpu); deltaMs is the default.
class MaxCost final : public Cost {
public:
    MaxCost(double baseMs, std::vector<std::vector<double>> gpuMs, std::vector<std::vector<double>> cpuMs)
        : mBaseMs(baseMs), mGpuMs(std::move(gpuMs)), mCpuMs(std::move(cpuMs)) {}
    double predictMs(const Combination& combination) const override {
        double gpu = 0.0;
        double cpu = 0.0;
        for (std::size_t i = 0; i < combination.size(); ++i) {
            gpu += mGpuMs[i][static_cast<std::size_t>(combination[i])];
            cpu += mCpuMs[i][static_cast<std::size_t>(combination[i])];
        }
        return mBaseMs + std::max(gpu, cpu);
    }

private:
    double mBaseMs;
    std::vector<std::vector<double>> mGpuMs;
    std::vector<std::vector<double>> mCpuMs;
};

// The 3-object problem whose optimum is worked out by hand (dyadic numbers, so sums are exact):
//
//   variable      A (3 levels)        B (2 levels)    C (3 levels)
//   level         0     1     2       0     1         0      1     2
//   loss          0   .125  .375      0   .25         0   .0625  .25
//   ms            4     2     1       5     2         3      2     1      base 0, budget 8
//
// Feasible combinations within 8 ms and their loss: [0,1,1] 8 ms .3125 (the optimum, fitness
// .6875), [1,0,2] 8 ms .375, [1,1,0] 7 ms .375, [1,1,1] 6 ms .4375, [2,0,1] 8 ms .4375, ...
// The cheapest (all coarsest, [2,1,2]) costs 4 ms; all finest 12 ms.
struct HandProblem {
    TableEvaluator evaluator{{{0.0, 0.125, 0.375}, {0.0, 0.25}, {0.0, 0.0625, 0.25}}};
    AdditiveCost cost{0.0, {{4.0, 2.0, 1.0}, {5.0, 2.0}, {3.0, 2.0, 1.0}}};
    Problem problem(double budgetMs = 8.0) {
        Problem p;
        p.levelCounts = {3, 2, 3};
        p.evaluator = &evaluator;
        p.cost = &cost;
        p.budgetMs = budgetMs;
        return p;
    }
};

// The harbor shape of GAPSO15's test scene: aircraft (5 levels), ship (5), sea (6). Costs
// follow the paper's polygon counts (1 ms per 1000 polygons; the sea's effects 3.0 → 0.3 ms);
// the loss is non-additive: the ship's boundary against a coarse sea loses extra fitness.
//   fitness = 1 - 0.25 q_air - 0.35 q_ship - 0.2 q_sea - 0.2 q_ship q_sea,
//   q = 1 - polygons(l) / polygons(0) normalised to 1 at the coarsest level (sea: l / 5).
struct HarborProblem {
    static double degradation(const std::vector<double>& polygons, int level) {
        return (polygons[0] - polygons[static_cast<std::size_t>(level)]) / (polygons.front() - polygons.back());
    }
    inline static const std::vector<double> kAircraft{1228, 822, 600, 450, 393};
    inline static const std::vector<double> kShip{6578, 6013, 5317, 3341, 3071};
    FormulaEvaluator evaluator{[](const Combination& c) {
        const double air = degradation(kAircraft, c[0]);
        const double ship = degradation(kShip, c[1]);
        const double sea = c[2] / 5.0;
        return 1.0 - 0.25 * air - 0.35 * ship - 0.2 * sea - 0.2 * ship * sea;
    }};
    AdditiveCost cost{
        0.5,
        {{1.228, 0.822, 0.600, 0.450, 0.393}, {6.578, 6.013, 5.317, 3.341, 3.071}, {3.0, 2.4, 1.8, 1.2, 0.7, 0.3}}};
    Problem problem(double budgetMs) {
        Problem p;
        p.levelCounts = {5, 5, 6};
        p.evaluator = &evaluator;
        p.cost = &cost;
        p.budgetMs = budgetMs;
        return p;
    }
};

// Every field of two logs except the wall clock.
inline bool sameLog(const std::vector<IterationLog>& a, const std::vector<IterationLog>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t k = 0; k < a.size(); ++k) {
        if (a[k].iteration != b[k].iteration || a[k].bestFitness != b[k].bestFitness ||
            a[k].meanFitness != b[k].meanFitness || a[k].bestPredictedMs != b[k].bestPredictedMs ||
            a[k].evaluations != b[k].evaluations || a[k].cacheHits != b[k].cacheHits) {
            return false;
        }
    }
    return true;
}

// Three objects with hints; additive cost 4 ms per object at level 0, 2 at 1, 1 at 2.
//   object        near      middle    far
//   distance        5         11       20
//   area           10          5        2
// With thresholds {8, 16}: levels [0, 1, 2]; importance decreases near → far.
struct HintProblem {
    TableEvaluator evaluator{{{0, 0.2, 0.4}, {0, 0.1, 0.2}, {0, 0.05, 0.1}}};
    AdditiveCost cost{0.0, {{4, 2, 1}, {4, 2, 1}, {4, 2, 1}}};
    Problem problem(double budgetMs) {
        Problem p;
        p.levelCounts = {3, 3, 3};
        p.evaluator = &evaluator;
        p.cost = &cost;
        p.budgetMs = budgetMs;
        p.hints.resize(3);
        const double distance[] = {5, 11, 20};
        const double area[] = {10, 5, 2};
        const double coverage[] = {0.6, 0.3, 0.1};
        for (int i = 0; i < 3; ++i) {
            p.hints[i].distance = distance[i];
            p.hints[i].projectedArea = area[i];
            p.hints[i].screenCoverage = coverage[i];
        }
        return p;
    }
};

}  // namespace lodopt::optimizer::testing
