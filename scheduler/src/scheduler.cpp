// The real-time scheduler's frame loop and its flat organisation: Dong, Liu, Xia, Fan & Zhang
// 2015, "A time-critical adaptive approach for visualizing natural scenes on different
// devices", PLoS ONE 10(2), §2.4 (importance-ordered raising and lowering, eq. 9 feedback),
// with VMI20 §7's switch control. The tile organisation is in tile_selection.cpp.
#include "scheduler/scheduler.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "scheduler_work.hpp"

namespace lodopt::scheduler {

const char* toString(Organisation organisation) {
    return organisation == Organisation::Tiles ? "tiles" : "flat";
}

void validateParameters(const SchedulerParameters& p, int objectCount) {
    if (!std::isfinite(p.budgetMs) || p.budgetMs <= 0.0) {
        throw std::invalid_argument("scheduler: budget = " + std::to_string(p.budgetMs) +
                                    " ms, must be finite and > 0");
    }
    validateCoefficients(p.coefficients.importance);
    validateThresholds(p.coefficients.thresholds);
    const Benchmark& b = p.coefficients.benchmark;
    if (b.view) {
        const ObjectView& v = *b.view;
        if (!(v.distance >= 0.0) || !(v.viewAngleRadians >= 0.0 && v.viewAngleRadians < 1.5707963267948966) ||
            !(v.projectedArea > 0.0) || !(v.projectedPixels >= 0.0) || !(v.centerOffset >= 0.0)) {
            throw std::invalid_argument(
                "scheduler: the benchmark object needs distance >= 0, angle in [0, 90°), area > 0, pixels >= 0, "
                "centre offset >= 0");
        }
        if (!(importanceDenominator(v, p.coefficients.importance) > 0.0)) {
            throw std::invalid_argument("scheduler: the benchmark object has a zero denominator (B = 0)");
        }
    } else if (!std::isfinite(b.scale) || b.scale <= 0.0) {
        throw std::invalid_argument("scheduler: benchmark scale = " + std::to_string(b.scale) +
                                    ", must be finite and > 0");
    }
    if (!p.objectWeights.empty()) {
        if (int(p.objectWeights.size()) != objectCount) {
            throw std::invalid_argument("scheduler: " + std::to_string(p.objectWeights.size()) +
                                        " object weights for " + std::to_string(objectCount) + " objects");
        }
        for (std::size_t o = 0; o < p.objectWeights.size(); ++o) {
            if (!std::isfinite(p.objectWeights[o]) || p.objectWeights[o] <= 0.0) {
                throw std::invalid_argument("scheduler: objectWeights[" + std::to_string(o) +
                                            "] = " + std::to_string(p.objectWeights[o]) + ", must be finite and > 0");
            }
        }
    }
    validateSwitchControl(p.switchControl);
    const timemodel::FeedbackParameters& f = p.feedback;
    if (!(f.beta > 0.0 && f.beta < 1.0) || !(f.maxRelativeError > 0.0 && f.maxRelativeError <= 1.0) ||
        !(f.maxDrift >= 1.0 && std::isfinite(f.maxDrift))) {
        throw std::invalid_argument(
            "scheduler: feedback needs 0 < beta < 1, 0 < maxRelativeError <= 1, "
            "1 <= maxDrift < inf");
    }
    if (!(p.coarsestShare > 0.0 && p.coarsestShare <= 1.0)) {
        throw std::invalid_argument("scheduler: coarsestShare = " + std::to_string(p.coarsestShare) +
                                    ", must be in (0, 1]");
    }
}

FrameScheduler::FrameScheduler(const SceneIndex& index, std::unique_ptr<timemodel::TimeModel> model,
                               SchedulerParameters parameters)
    : mIndex(index), mModel(std::move(model)), mParameters(std::move(parameters)), mWork(std::make_unique<Work>()) {
    assert(mModel && mModel->fitted());
    validateParameters(mParameters, index.objectCount());
    // The index skipped the features outside its set (left 0): the model must not read them.
    const timemodel::FeatureSet missing = mModel->readFeatures() & ~index.neededFeatures();
    for (timemodel::Feature feature : timemodel::allFeatures()) {
        if (timemodel::contains(missing, feature)) {
            throw std::invalid_argument(std::string("scheduler: the time model reads '") +
                                        timemodel::featureName(feature) +
                                        "', which the scene index was built without (SceneIndex's needed features)");
        }
    }
    // The tile organisation has no hysteresis passes: it filters its decision by VMI20's rule.
    mFilterControl = mParameters.switchControl;
    mFilterControl.enabled =
        mParameters.switchControl.enabled &&
        (mParameters.switchControl.rule == SwitchRule::Vmi20 || mParameters.organisation == Organisation::Tiles);
    mFilterControl.rule = SwitchRule::Vmi20;
    std::vector<ObjectShape> shapes;
    if (mParameters.organisation == Organisation::Tiles) {
        for (int o = 0; o < index.objectCount(); ++o) shapes.push_back(index.shape(o));
        mQuadtree = std::make_unique<Quadtree>(shapes, mParameters.quadtree);
    }
    const std::size_t n = std::size_t(index.objectCount());
    mImportance.assign(n, 0.0);
    mInitial.assign(n, scenes::kNotDrawn);
    mPrevious.assign(n, scenes::kNotDrawn);
    mLastSwitchTime.assign(n, -std::numeric_limits<double>::infinity());
    mRange.assign(n, LevelRange{});
    mDecision.levels.assign(n, scenes::kNotDrawn);
    mWork->reserve(n);
}

FrameScheduler::~FrameScheduler() = default;

void FrameScheduler::reset() {
    std::fill(mPrevious.begin(), mPrevious.end(), scenes::kNotDrawn);
    std::fill(mLastSwitchTime.begin(), mLastSwitchTime.end(), -std::numeric_limits<double>::infinity());
    mHavePrevious = false;
}

void FrameScheduler::setCoefficients(const SchedulerCoefficients& coefficients) {
    SchedulerParameters changed = mParameters;
    changed.coefficients = coefficients;
    validateParameters(changed, mIndex.objectCount());
    mParameters = std::move(changed);
}

void FrameScheduler::setBudgetMs(double budgetMs) {
    assert(std::isfinite(budgetMs) && budgetMs > 0.0);
    mParameters.budgetMs = budgetMs;
}

timemodel::FeedbackResult FrameScheduler::reportMeasuredMs(double measuredMs) {
    return mModel->applyFeedback(mDecision.features, measuredMs, mParameters.feedback);
}

const timemodel::FrameFeatures& FrameScheduler::contribution(int object, int level) const {
    return mFrame.contributions[std::size_t(mIndex.firstLevel(object) + level)];
}

void FrameScheduler::setLevel(int object, int level) {
    int& current = mDecision.levels[object];
    if (current == level) return;
    if (current != scenes::kNotDrawn) mDecision.features -= contribution(object, current);
    if (level != scenes::kNotDrawn) mDecision.features += contribution(object, level);
    current = level;
}

const FrameDecision& FrameScheduler::decide(const scenes::Camera& camera, double timeSeconds) {
    FrameDecision& d = mDecision;
    std::fill(d.levels.begin(), d.levels.end(), scenes::kNotDrawn);
    d.features = mIndex.frameConstant();
    d.predictedMs = d.minimumMs = 0.0;
    d.budgetReachable = d.budgetMet = false;
    d.visibleObjects = d.culledObjects = d.droppedObjects = 0;
    d.protectedLowered = d.forcedSwitches = d.switches = d.heldObjects = 0;
    std::fill(mImportance.begin(), mImportance.end(), 0.0);
    std::fill(mInitial.begin(), mInitial.end(), scenes::kNotDrawn);

    mIndex.beginFrame(camera, mFrame);
    if (mQuadtree) {
        observeTiles();
    } else {
        observeFlat();
    }
    computeImportanceAndRanges(timeSeconds);
    // The cheapest frame without dropping: every visible object at its coarsest level.
    timemodel::FrameFeatures minimum = mIndex.frameConstant();
    for (int o : mWork->visible) minimum += contribution(o, mIndex.levelCount(o) - 1);
    d.minimumMs = estimate(minimum);
    if (mQuadtree) {
        decideTiles();
    } else {
        decideFlat();
    }
    applySwitchControl();
    finishFrame(timeSeconds);
    return d;
}

void FrameScheduler::observeFlat() {
    Work& w = *mWork;
    w.visible.clear();
    for (int o = 0; o < mIndex.objectCount(); ++o) {
        if (mIndex.observe(o, mFrame)) w.visible.push_back(o);
    }
}

void FrameScheduler::computeImportanceAndRanges(double timeSeconds) {
    Work& w = *mWork;
    const SchedulerCoefficients& c = mParameters.coefficients;
    w.denominators.clear();
    for (int o : w.visible) w.denominators.push_back(importanceDenominator(mFrame.views[o], c.importance));
    double benchmark = 1.0;
    if (c.benchmark.view) {
        benchmark = importanceDenominator(*c.benchmark.view, c.importance);
    } else if (!w.visible.empty()) {
        w.scratch.assign(w.denominators.begin(), w.denominators.end());
        const std::size_t middle = w.scratch.size() / 2;
        std::nth_element(w.scratch.begin(), w.scratch.begin() + middle, w.scratch.end());
        double median = w.scratch[middle];
        if (w.scratch.size() % 2 == 0) {
            median = 0.5 * (median + *std::max_element(w.scratch.begin(), w.scratch.begin() + middle));
        }
        benchmark = median * c.benchmark.scale;
        if (!(benchmark > 0.0)) benchmark = 1.0;  // every visible object at the eye: all infinitely important
    }
    const SwitchControlParameters& control = mFilterControl;
    for (std::size_t i = 0; i < w.visible.size(); ++i) {
        const int o = w.visible[i];
        const double weight = mParameters.objectWeights.empty() ? 1.0 : mParameters.objectWeights[o];
        const double denominator = w.denominators[i];
        mImportance[o] = denominator > 0.0 ? weight * benchmark / denominator : std::numeric_limits<double>::infinity();
        const int levels = mIndex.levelCount(o);
        const double radius = std::max(double(mIndex.shape(o).radius), 1e-9);
        const double x = c.thresholds.relativeToRadius ? mFrame.views[o].distance / radius : mFrame.views[o].distance;
        LevelRange range{0, levels - 1};
        if (control.enabled && mHavePrevious && mPrevious[o] != scenes::kNotDrawn) {
            range = allowedLevels(mPrevious[o], timeSeconds - mLastSwitchTime[o], x, mIndex.rates(o), control);
        }
        mRange[o] = range;
        mInitial[o] = distanceLevel(x, c.thresholds.values, levels);
    }
}

void FrameScheduler::sortByImportance(bool increasing) {
    Work& w = *mWork;
    w.order.assign(w.visible.begin(), w.visible.end());
    // Ties by object index so that the decision is deterministic.
    std::sort(w.order.begin(), w.order.end(), [&](int a, int b) {
        if (mImportance[a] != mImportance[b])
            return increasing ? mImportance[a] < mImportance[b] : mImportance[a] > mImportance[b];
        return a < b;
    });
}

double FrameScheduler::lowerToBudget(double ms, LowerLimit limit) {
    const Work& w = *mWork;
    FrameDecision& d = mDecision;
    const double budget = mParameters.budgetMs;
    const bool protect = mParameters.protectImportant;
    auto coarsestAllowed = [&](int o) {
        switch (limit) {
            case LowerLimit::SwitchRange:
                return mRange[o].coarsest;
            case LowerLimit::WithoutSwitch:
                // Only objects with I <= 1 are held back to spare a switch: holding the important
                // ones at last frame's coarser level, to lower none beyond its own, cost the city
                // 1.7% of fitness against no control (docs/scheduler.md, Goal 4).
                if (mImportance[o] > 1.0) return d.levels[o];
                if (mPrevious[o] != scenes::kNotDrawn) return mPrevious[o];
                break;
            case LowerLimit::Coarsest:
                break;
        }
        return mIndex.levelCount(o) - 1;
    };
    // Increasing importance (w.order), objects with I <= 1 first: those with I > 1 only when
    // lowering every other object as far as allowed was not enough.
    for (int pass = 0; pass < (protect ? 2 : 1) && ms > budget; ++pass) {
        for (int o : w.order) {
            if (ms <= budget) break;
            if (protect && (mImportance[o] > 1.0) != (pass == 1)) continue;
            if (d.levels[o] == scenes::kNotDrawn) continue;
            const int coarsest = coarsestAllowed(o);
            while (ms > budget && d.levels[o] < coarsest) {
                setLevel(o, d.levels[o] + 1);
                ms = estimate(d.features);
            }
        }
    }
    return ms;
}

void FrameScheduler::decideFlat() {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    const double budget = mParameters.budgetMs;
    const bool hysteresisRule = mParameters.switchControl.enabled && !mFilterControl.enabled;
    const bool hysteresis = hysteresisRule && mHavePrevious;
    decideFlatLevels(hysteresis);
    // Refill: a frame the decision left far under the budget (under (1 − refillBelow) of it:
    // at the default 0.05, where the few percent a measured time strays from its prediction
    // take it out of the ±10% band Goal 1 asks for) may switch. Holding it there would save a
    // switch at the cost of a frame that misses the band often. First raise into the whole
    // budget from where it stands; if the coarse steps of a few large objects leave it under
    // still, take the decision without switch control when that comes nearer the budget, and
    // then exchange levels between objects (raising alone never lowers one object to raise
    // another).
    const double refill = mParameters.switchControl.refillBelow;
    const double bandFloor = budget * (1.0 - refill);
    if (!hysteresisRule || refill <= 0.0 || estimate(d.features) >= bandFloor) return;
    if (hysteresis) {
        for (int o : w.order) raiseWhileFits(o, 0, budget);  // w.order: decreasing importance
        const double raised = estimate(d.features);
        if (raised >= bandFloor) return;
        w.held.save(d);
        decideFlatLevels(false);
        if (estimate(d.features) <= raised) w.held.restore(d);
    }
    exchangeTowardBudget(bandFloor);  // nothing to do if the frame is in the band already
}

// One level finer for one object, paid for by coarser levels of the least important others,
// kept when the frame comes nearer the budget; the first such exchange in decreasing importance
// of the raised object, again until the frame is in the band or none helps. The harbor's
// approach at 8 ms: decisions in the band 91.1% -> 96.9% (docs/scheduler.md, "Hysteresis").
void FrameScheduler::exchangeTowardBudget(double bandFloor) {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    const double budget = mParameters.budgetMs;
    double ms = estimate(d.features);  // w.order: decreasing importance (decideFlatLevels)
    // Each accepted exchange raises the prediction, so this ends; the trials' cap bounds the
    // decision time where many objects are visible (a trial that cannot be paid for walks all).
    constexpr int kMaxTrials = 64;
    int trials = 0;
    for (bool exchanged = true; exchanged && ms < bandFloor && trials < kMaxTrials;) {
        exchanged = false;
        for (std::size_t i = 0; i < w.order.size() && !exchanged && trials < kMaxTrials; ++i) {
            const int raisedObject = w.order[i];
            if (d.levels[raisedObject] == scenes::kNotDrawn || d.levels[raisedObject] == 0) continue;
            ++trials;
            w.beforeExchange.save(d);
            setLevel(raisedObject, d.levels[raisedObject] - 1);
            double trial = estimate(d.features);
            // Paid for by the least important objects first.
            for (std::size_t j = w.order.size(); j-- > 0 && trial > budget;) {
                const int lowered = w.order[j];
                if (j == i || d.levels[lowered] == scenes::kNotDrawn) continue;
                while (trial > budget && d.levels[lowered] < mIndex.levelCount(lowered) - 1) {
                    setLevel(lowered, d.levels[lowered] + 1);
                    trial = estimate(d.features);
                }
            }
            if (trial <= budget && trial > ms) {
                ms = trial;
                exchanged = true;
            } else {
                w.beforeExchange.restore(d);
            }
        }
    }
}

void FrameScheduler::decideFlatLevels(bool hysteresis) {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    const double budget = mParameters.budgetMs;
    for (int o : w.visible) {
        // Hysteresis: an object with I <= 1 drawn coarser last frame starts there, so that its
        // distance level is a raise like any other (within the margin), not a switch for free.
        // Those with I > 1 start at their distance level (DONG15: not to be lowered); starting
        // them coarser too cost the city 1.5% of fitness (docs/scheduler.md).
        const int previous = mPrevious[o];
        const bool startCoarser = hysteresis && previous != scenes::kNotDrawn && mImportance[o] <= 1.0;
        setLevel(o, startCoarser ? std::max(mInitial[o], previous) : mInitial[o]);
    }
    double ms = estimate(d.features);
    if (ms > budget) {
        sortByImportance(true);
        if (hysteresis) ms = lowerToBudget(ms, LowerLimit::WithoutSwitch);
        lowerToBudget(ms, LowerLimit::Coarsest);
    }
    sortByImportance(false);
    if (hysteresis) restorePreviousLevels();
    // Raise in decreasing importance, each object as far toward level 0 as the budget allows
    // (an object whose next step does not fit is passed over). After lowering this spends what
    // the last, often large, step down left over: the objects just lowered do not fit a step
    // back, more important ones may. Hysteresis: a raise that is a switch (the object was drawn
    // last frame) only within (1 − margin) of the budget.
    const double switchBudget = hysteresis ? budget * (1.0 - mParameters.switchControl.raiseMargin) : budget;
    for (int o : w.order) raiseWhileFits(o, 0, mPrevious[o] == scenes::kNotDrawn ? budget : switchBudget);
}

void FrameScheduler::restorePreviousLevels() {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    for (int o : w.order) {
        const int previous = mPrevious[o];
        if (previous == scenes::kNotDrawn || previous >= d.levels[o]) continue;
        // All the way or not at all: a partial return is a switch now and, as the budget
        // tightens, another one next frame (measured: the city's frames 0-299 went from 2.01
        // to 1.78 switches per frame against partial returns).
        w.trial = d.features;
        w.trial += contribution(o, previous);
        w.trial -= contribution(o, d.levels[o]);
        if (estimate(w.trial) <= mParameters.budgetMs) setLevel(o, previous);
    }
}

void FrameScheduler::raiseWhileFits(int object, int finest, double budgetMs) {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    while (d.levels[object] > finest) {
        const int level = d.levels[object];
        w.trial = d.features;
        w.trial += contribution(object, level - 1);
        w.trial -= contribution(object, level);
        if (estimate(w.trial) > budgetMs) break;
        setLevel(object, level - 1);
    }
}

void FrameScheduler::applySwitchControl() {
    if (!mFilterControl.enabled || !mHavePrevious) return;
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    for (int o : w.visible) {
        const int previous = mPrevious[o];
        const int desired = d.levels[o];
        if (previous == scenes::kNotDrawn || desired == scenes::kNotDrawn || desired == previous) continue;
        const int allowed = std::clamp(desired, mRange[o].finest, mRange[o].coarsest);
        if (allowed != desired) {
            setLevel(o, allowed);
            ++d.heldObjects;
        }
    }
    double ms = estimate(d.features);
    if (ms <= mParameters.budgetMs) {
        // Budget left (objects held coarser than decided): objects the decision lowered keep
        // their previous level, or come as close to it as the budget allows, in decreasing
        // importance. A change avoided is a switch saved.
        sortByImportance(false);
        for (int o : w.order) {
            if (mPrevious[o] == scenes::kNotDrawn || d.levels[o] == scenes::kNotDrawn) continue;
            raiseWhileFits(o, mPrevious[o], mParameters.budgetMs);
        }
        raiseWithinRange();
        return;
    }
    // Held objects cost more than the decision wanted: lower in increasing importance, first
    // as far as the control allows, then beyond it (forced switches).
    sortByImportance(true);
    ms = lowerToBudget(ms, LowerLimit::SwitchRange);
    ms = lowerToBudget(ms, LowerLimit::Coarsest);
    if (!mQuadtree) return;
    // Tiles: as Algorithm 1 would have, leave out the last objects of the tile order.
    for (auto it = w.visible.rbegin(); it != w.visible.rend() && ms > mParameters.budgetMs; ++it) {
        if (d.levels[*it] == scenes::kNotDrawn) continue;
        setLevel(*it, scenes::kNotDrawn);
        ms = estimate(d.features);
    }
}

void FrameScheduler::raiseWithinRange() {
    Work& w = *mWork;
    FrameDecision& d = mDecision;
    // w.order is in decreasing importance (applySwitchControl sorted it).
    for (int o : w.order) {
        if (d.levels[o] != scenes::kNotDrawn) raiseWhileFits(o, mRange[o].finest, mParameters.budgetMs);
    }
}

void FrameScheduler::finishFrame(double timeSeconds) {
    FrameDecision& d = mDecision;
    const Work& w = *mWork;
    // Recomputed from scratch so that the incremental sums leave no rounding drift.
    d.features = mIndex.frameConstant();
    int drawn = 0;
    for (int o = 0; o < mIndex.objectCount(); ++o) {
        const int level = d.levels[o];
        if (level == scenes::kNotDrawn) continue;
        ++drawn;
        d.features += contribution(o, level);
        if (level > mRange[o].coarsest || level < mRange[o].finest) ++d.forcedSwitches;
        if (mImportance[o] > 1.0 && level > mInitial[o]) ++d.protectedLowered;
        if (mHavePrevious && mPrevious[o] != scenes::kNotDrawn && mPrevious[o] != level) {
            ++d.switches;
            mLastSwitchTime[o] = timeSeconds;
        }
    }
    d.predictedMs = estimate(d.features);
    d.visibleObjects = int(w.visible.size());
    d.culledObjects = mIndex.objectCount() - d.visibleObjects;
    d.droppedObjects = d.visibleObjects - drawn;
    // A relative slack of 1e-9 absorbs the rounding between incremental and fresh sums.
    const double slack = 1e-9 * std::max(1.0, mParameters.budgetMs);
    d.budgetMet = d.predictedMs <= mParameters.budgetMs + slack;
    d.budgetReachable = d.minimumMs <= mParameters.budgetMs + slack;
    std::copy(d.levels.begin(), d.levels.end(), mPrevious.begin());
    mHavePrevious = true;
}

}  // namespace lodopt::scheduler
