#include "optimizer/algorithm.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "optimizer/baselines.hpp"
#include "optimizer/engine_rules.hpp"
#include "optimizer/gapso.hpp"
#include "optimizer/heuristics.hpp"
#include "optimizer/mckp.hpp"

namespace lodopt::optimizer {

Termination Termination::paper() {
    Termination termination = none();
    termination.maxIterations = 20;
    return termination;
}

Termination Termination::none() {
    Termination termination;
    termination.maxIterations = 0;
    termination.stableIterations = 0;
    termination.maxEvaluations = 0;
    termination.maxSeconds = 0.0;
    return termination;
}

void Termination::validate() const {
    if (maxIterations < 0) {
        throw std::invalid_argument("termination: maxIterations = " + std::to_string(maxIterations) + ", must be >= 0");
    }
    if (stableIterations < 0) {
        throw std::invalid_argument("termination: stableIterations = " + std::to_string(stableIterations) +
                                    ", must be >= 0");
    }
    if (!std::isfinite(stableTolerance) || stableTolerance < 0.0) {
        throw std::invalid_argument("termination: stableTolerance = " + std::to_string(stableTolerance) +
                                    ", must be finite and >= 0");
    }
    if (maxEvaluations < 0) {
        throw std::invalid_argument("termination: maxEvaluations = " + std::to_string(maxEvaluations) +
                                    ", must be >= 0");
    }
    if (!std::isfinite(maxSeconds) || maxSeconds < 0.0) {
        throw std::invalid_argument("termination: maxSeconds = " + std::to_string(maxSeconds) +
                                    ", must be finite and >= 0");
    }
}

bool Termination::guaranteesStop() const {
    return maxIterations > 0 || stableIterations > 0 || maxSeconds > 0.0;
}

std::string_view toString(StopReason reason) {
    switch (reason) {
        case StopReason::Completed:
            return "completed";
        case StopReason::MaxIterations:
            return "max-iterations";
        case StopReason::Stable:
            return "stable";
        case StopReason::MaxEvaluations:
            return "max-evaluations";
        case StopReason::WallTime:
            return "wall-time";
    }
    return "unknown";
}

bool isBetter(double fitnessA, double msA, const Combination& a, double fitnessB, double msB, const Combination& b) {
    if (fitnessA != fitnessB) return fitnessA > fitnessB;
    if (msA != msB) return msA < msB;
    return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end());
}

namespace {

struct Registered {
    AlgorithmMaker make;
    bool seeded = false;
};

// lodopt's own names, then the registered ones.
std::vector<std::string>& names() {
    static std::vector<std::string> list = {"gapso",      "pso",        "ga",   "greedy",     "distance",
                                            "importance", "screensize", "pixelerror", "unreal-auto", "mckp",
                                            "exhaustive", "random"};
    return list;
}

std::map<std::string, Registered, std::less<>>& registered() {
    static std::map<std::string, Registered, std::less<>> algorithms;
    return algorithms;
}

}  // namespace

const std::vector<std::string>& algorithmNames() {
    return names();
}

bool isSeededAlgorithm(std::string_view name) {
    if (name == "gapso" || name == "pso" || name == "ga" || name == "random") return true;
    const auto found = registered().find(name);
    return found != registered().end() && found->second.seeded;
}

void registerAlgorithm(const std::string& name, AlgorithmMaker make, bool seeded) {
    if (name.empty() || !make) throw std::invalid_argument("registerAlgorithm: an empty name or maker");
    if (std::find(names().begin(), names().end(), name) != names().end()) {
        throw std::invalid_argument("registerAlgorithm: '" + name + "' is already an algorithm");
    }
    registered()[name] = Registered{std::move(make), seeded};
    names().push_back(name);
}

std::unique_ptr<Algorithm> makeAlgorithm(std::string_view name, std::uint64_t seed) {
    if (name == "gapso" || name == "pso" || name == "ga") {
        GapsoParameters parameters;
        parameters.seed = seed;
        parameters.pso = name != "ga";
        parameters.ga = name != "pso";
        return std::make_unique<Gapso>(parameters);
    }
    if (name == "greedy") return std::make_unique<Greedy>();
    if (name == "distance") return std::make_unique<DistanceHeuristic>();
    if (name == "importance") return std::make_unique<ImportanceHeuristic>();
    if (name == "screensize") return std::make_unique<ScreenSizeHeuristic>();
    if (name == "pixelerror") return std::make_unique<EngineRuleHeuristic>(EngineRule::PixelError);
    if (name == "unreal-auto") return std::make_unique<EngineRuleHeuristic>(EngineRule::UnrealAuto);
    if (name == "mckp") return std::make_unique<Mckp>();
    if (name == "exhaustive") return std::make_unique<Exhaustive>();
    if (name == "random") {
        RandomSearchParameters parameters;
        parameters.seed = seed;
        return std::make_unique<RandomSearch>(parameters);
    }
    if (const auto found = registered().find(name); found != registered().end()) return found->second.make(seed);
    std::string valid;
    for (const std::string& known : algorithmNames()) valid += (valid.empty() ? "" : ", ") + known;
    throw std::invalid_argument("unknown algorithm '" + std::string(name) + "' (valid: " + valid + ")");
}

}  // namespace lodopt::optimizer
