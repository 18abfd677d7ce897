#include "schedule_rows.hpp"

#include <iomanip>
#include <sstream>

namespace lodopt::cli {

std::string csvNumber(double value) {
    if (std::isnan(value)) return "";
    std::ostringstream out;
    out << std::setprecision(8) << value;
    return out.str();
}

std::string framesCsv(const std::vector<evaluation::WalkFrame>& rows, int maxLevels) {
    std::ostringstream csv;
    csv << "frame,time_s,decision_us,predicted_ms,measured_ms,finest_predicted_ms,baseline_predicted_ms,"
           "baseline_measured_ms,exact_predicted_ms,budget_reachable,budget_met,fitness,baseline_fitness,visible,"
           "culled,dropped,drawn,"
           "protected_lowered,forced_switches,switches,held,feedback_scale";
    for (int l = 0; l < maxLevels; ++l) csv << ",level_" << l;
    csv << "\n";
    for (const evaluation::WalkFrame& r : rows) {
        const scheduler::FrameDecision& d = r.decision;
        const int drawn = d.visibleObjects - d.droppedObjects;
        csv << r.frame << ',' << csvNumber(r.timeSeconds) << ',' << csvNumber(r.decisionMicroseconds) << ','
            << csvNumber(r.predictedMs) << ',' << csvNumber(r.measuredMs) << ',' << csvNumber(r.finestPredictedMs)
            << ',' << csvNumber(r.baselinePredictedMs) << ',' << csvNumber(r.baselineMeasuredMs) << ','
            << csvNumber(r.exactPredictedMs) << ',' << int(d.budgetReachable) << ',' << int(d.budgetMet) << ','
            << csvNumber(r.fitness) << ',' << csvNumber(r.baselineFitness) << ',' << d.visibleObjects << ','
            << d.culledObjects << ',' << d.droppedObjects << ',' << drawn << ',' << d.protectedLowered << ','
            << d.forcedSwitches << ',' << d.switches << ',' << d.heldObjects << ',' << csvNumber(r.feedbackScale);
        for (int count : r.histogram) csv << ',' << count;
        csv << "\n";
    }
    return csv.str();
}

nlohmann::json sharesJson(const BudgetShares& s) {
    return {{"frames", s.frames}, {"within_10_percent", s.within10}, {"at_most_110_percent", s.atMost110}};
}

nlohmann::json spreadJson(const Spread& s) {
    return {{"median", s.median}, {"p90", s.p90}, {"max", s.max}, {"mean", s.mean}};
}

}  // namespace lodopt::cli
