// Calibration timing statistics and the choice of the statistic to learn from (timing.hpp).
#include "timemodel/timing.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <set>

#include "timemodel/calibration.hpp"

namespace lodopt::timemodel {

std::vector<std::string> timingStatisticNames() {
    return {"median", "least-median", "least", "cpu"};
}

std::string canonicalStatistic(const std::string& name) {
    if (name == "wall-median") return "median";
    if (name == "wall-min-median") return "least-median";
    if (name == "wall-min") return "least";
    for (const std::string& known : timingStatisticNames()) {
        if (name == known) return name;
    }
    return "";
}

double median(std::vector<double> values) {
    if (values.empty()) return NAN;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

const std::vector<double>& perPassValues(const std::string& statistic, const PassTimes& times) {
    if (statistic == "cpu") return times.cpu;
    if (statistic == "median") return times.median;
    return times.least;
}

double reducePasses(const std::string& statistic, const std::vector<double>& perPass) {
    assert(!perPass.empty());
    return statistic == "least" ? *std::min_element(perPass.begin(), perPass.end()) : median(perPass);
}

double timeFromPasses(const std::string& statistic, const PassTimes& times) {
    const std::vector<double>& perPass = perPassValues(statistic, times);
    return perPass.empty() ? 0.0 : reducePasses(statistic, perPass);
}

double passSpread(const std::vector<double>& perPass) {
    assert(!perPass.empty());
    const auto [low, high] = std::minmax_element(perPass.begin(), perPass.end());
    return (*high - *low) / median(perPass);
}

std::vector<double> passTimeFactors(const std::vector<PassTimes>& times) {
    const std::size_t passes = times.empty() ? 0 : times.front().median.size();
    if (passes == 0) return {};
    std::vector<std::vector<double>> ratios(passes);
    for (const PassTimes& t : times) {
        if (t.median.size() != passes || *std::min_element(t.median.begin(), t.median.end()) <= 0.0) continue;
        const double all = median(t.median);
        for (std::size_t p = 0; p < passes; ++p) ratios[p].push_back(t.median[p] / all);
    }
    std::vector<double> factors;
    factors.reserve(passes);
    for (const std::vector<double>& r : ratios) {
        if (r.empty()) return {};
        factors.push_back(median(r));
    }
    return factors;
}

double passDrift(const std::vector<double>& factors) {
    if (factors.size() < 2) return 0.0;
    const auto [low, high] = std::minmax_element(factors.begin(), factors.end());
    return *high / *low - 1.0;
}

ErrorStats splitHalfRepeatability(const std::string& statistic, const std::vector<PassTimes>& times,
                                  const std::vector<bool>& include) {
    assert(include.size() == times.size());
    std::vector<double> halves;
    std::vector<double> even, odd;
    for (std::size_t i = 0; i < times.size(); ++i) {
        if (!include[i]) continue;
        const std::vector<double>& perPass = perPassValues(statistic, times[i]);
        if (perPass.size() < 2) continue;
        const double all = reducePasses(statistic, perPass);
        if (!(all > 0.0)) continue;
        even.clear();
        odd.clear();
        for (std::size_t k = 0; k < perPass.size(); ++k) (k % 2 ? odd : even).push_back(perPass[k]);
        halves.push_back(std::abs(reducePasses(statistic, even) - reducePasses(statistic, odd)) / all);
    }
    return summarizeErrors(halves);
}

double learnedScale(const std::vector<double>& learned, const std::vector<double>& predicted) {
    assert(learned.size() == predicted.size());
    std::vector<double> ratios;
    for (std::size_t i = 0; i < learned.size(); ++i) {
        if (learned[i] > 0.0 && predicted[i] > 0.0) ratios.push_back(predicted[i] / learned[i]);
    }
    return ratios.empty() ? 1.0 : median(ratios);
}

LearnChoice chooseStatisticToLearn(const std::vector<ProfileSample>& samples, const std::string& model) {
    LearnChoice choice;
    choice.statistic = kPredictedStatistic;
    std::vector<Sample> fitting;
    std::vector<double> predicted;
    std::vector<int> fittingFolds;
    std::vector<const ProfileSample*> kept;
    for (std::size_t i = 0; i < samples.size(); ++i) {
        if (samples[i].heldOut || !(samples[i].medianMs > 0.0)) continue;
        kept.push_back(&samples[i]);
        predicted.push_back(samples[i].medianMs);
        fittingFolds.push_back(samples[i].sample.viewpoint);
    }
    const bool judgeable = std::set<int>(fittingFolds.begin(), fittingFolds.end()).size() >= 2;
    double best = 0.0;
    for (const char* statistic : {"median", "least-median", "least"}) {
        LearnCandidate candidate;
        candidate.statistic = statistic;
        fitting.clear();
        std::vector<double> learned;
        bool complete = true;
        for (const ProfileSample* s : kept) {
            Sample sample = s->sample;
            sample.measuredMs = timeOfStatistic(*s, statistic);
            complete = complete && sample.measuredMs > 0.0;
            learned.push_back(sample.measuredMs);
            fitting.push_back(sample);
        }
        candidate.scale = learnedScale(learned, predicted);
        if (judgeable && complete) {
            candidate.crossValidated = rotatedHeldOutErrors(fitting, predicted, fittingFolds, {model}).front();
        }
        const bool judged = candidate.crossValidated.count > 0;
        if (judged && (!choice.measured || candidate.crossValidated.mean < best)) {
            choice.statistic = statistic;
            best = candidate.crossValidated.mean;
            choice.measured = true;
        }
        choice.candidates.push_back(candidate);
    }
    return choice;
}

namespace {

// The fitting samples learning from `statistic` (scaled) and the held-out ones measured by the median.
void splitSamples(const std::vector<ProfileSample>& samples, const std::string& statistic, double scale,
                  std::vector<Sample>& fit, std::vector<Sample>& heldOut) {
    fit.clear();
    heldOut.clear();
    for (const ProfileSample& recorded : samples) {
        Sample sample = recorded.sample;
        sample.measuredMs = recorded.heldOut ? recorded.medianMs : scale * timeOfStatistic(recorded, statistic);
        (recorded.heldOut ? heldOut : fit).push_back(sample);
    }
}

double scaleTowardsMedian(const std::vector<ProfileSample>& samples, const std::string& statistic) {
    std::vector<double> learned, predicted;
    for (const ProfileSample& s : samples) {
        if (s.heldOut) continue;
        learned.push_back(timeOfStatistic(s, statistic));
        predicted.push_back(s.medianMs);
    }
    return learnedScale(learned, predicted);
}

}  // namespace

std::vector<int> profileFolds(const DeviceProfile& profile) {
    const bool stored =
        std::all_of(profile.samples.begin(), profile.samples.end(), [](const ProfileSample& s) { return s.fold >= 0; });
    std::vector<int> folds;
    std::map<int, int> foldOfViewpoint;
    for (const ProfileSample& s : profile.samples) {
        if (stored) {
            folds.push_back(s.fold);
        } else if (s.heldOut) {
            folds.push_back(0);
        } else {
            const auto [it, added] = foldOfViewpoint.emplace(s.sample.viewpoint, int(foldOfViewpoint.size()) + 1);
            folds.push_back(it->second);
        }
    }
    return folds;
}

ProfileFit fitProfile(DeviceProfile& profile, const std::vector<int>& folds, const std::string& learnFrom) {
    const std::string requested = learnFrom == kAutoStatistic ? learnFrom : canonicalStatistic(learnFrom);
    if (requested.empty()) throw TimeModelError("unknown timing statistic '" + learnFrom + "'");
    if (folds.size() != profile.samples.size()) throw TimeModelError("fitProfile: one fold per sample is needed");
    for (std::size_t i = 0; i < profile.samples.size(); ++i) {
        ProfileSample& s = profile.samples[i];
        if (!(s.medianMs > 0.0)) {
            throw TimeModelError("sample " + std::to_string(i) + " has no recorded median frame time: recalibrate");
        }
        s.sample.measuredMs = s.medianMs;
    }
    ProfileFit result;
    result.choice = chooseStatisticToLearn(profile.samples, profile.defaultModel);
    const std::string statistic = requested == kAutoStatistic ? result.choice.statistic : requested;
    const double scale = scaleTowardsMedian(profile.samples, statistic);

    std::vector<Sample> fit, heldOut;
    splitSamples(profile.samples, statistic, scale, fit, heldOut);
    profile.models = fitAllModels(fit, heldOut);
    std::vector<Sample> learned;
    std::vector<double> medians;
    for (const ProfileSample& s : profile.samples) {
        learned.push_back(s.sample);
        learned.back().measuredMs = timeOfStatistic(s, statistic);
        medians.push_back(s.medianMs);
    }
    const std::vector<ErrorStats> rotated = rotatedHeldOutErrors(learned, medians, folds, timeModelNames());
    for (std::size_t m = 0; m < profile.models.size() && m < rotated.size(); ++m) {
        profile.models[m].rotatedErrors = rotated[m];
    }
    if (std::none_of(profile.models.begin(), profile.models.end(), [](const ModelResult& r) { return r.fitted; })) {
        std::string reasons;
        for (const ModelResult& r : profile.models) reasons += "\n  " + r.name + ": " + r.failure;
        throw TimeModelError("no time model could be fitted:" + reasons);
    }
    profile.timing.predicts = kPredictedStatistic;
    profile.timing.learnedFrom = statistic;
    profile.timing.learnedScale = scale;
    profile.timing.learnRequest = requested;

    for (const std::string& other : timingStatisticNames()) {
        if (other == statistic) continue;
        if (std::any_of(profile.samples.begin(), profile.samples.end(),
                        [&](const ProfileSample& s) { return !(timeOfStatistic(s, other) > 0.0); })) {
            continue;  // not recorded (cpu in some older profiles)
        }
        StatisticFit otherFit;
        otherFit.statistic = other;
        otherFit.scale = scaleTowardsMedian(profile.samples, other);
        splitSamples(profile.samples, other, otherFit.scale, fit, heldOut);
        otherFit.models = fitAllModels(fit, heldOut);
        result.others.push_back(std::move(otherFit));
    }
    return result;
}

ProfileFit refitProfile(DeviceProfile& profile, const std::string& learnFrom) {
    const std::vector<int> folds = profileFolds(profile);
    for (std::size_t i = 0; i < folds.size(); ++i) profile.samples[i].fold = folds[i];
    return fitProfile(profile, folds, learnFrom);
}

}  // namespace lodopt::timemodel
