// Coefficients files: what `lodopt tune` writes and `lodopt schedule --coeffs` reads.
//
// A JSON object:
//   "format": "lodopt-scheduler-coefficients", "version": 1,
//   "importance": {"alpha1": a, "alpha2": a, "alpha3": a, "alpha4": a}   (alpha3/4 optional, 0),
//   "benchmark": {"scale": s}  (B = s × the frame's median denominator), or a fixed object
//                {"distance": d, "view_angle_degrees": θ, "projected_area": s,
//                 "projected_pixels": p, "center_offset": c}  (the last two optional),
//   "distance_thresholds": {"relative_to_radius": true, "values": [t1, t2, ...]}.
// Other keys (the tuning report) are ignored when reading.
#pragma once

#include <stdexcept>
#include <string>

#include "scheduler/scheduler.hpp"

namespace lodopt::scheduler {

// A coefficients file that cannot be used: the message names the file and the field.
class CoefficientsError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The JSON text of `coefficients` (pretty, 2 spaces), without a report.
std::string coefficientsToJson(const SchedulerCoefficients& coefficients);
// `source` names the text in messages. Throws CoefficientsError for bad JSON, a missing or
// mistyped field, or values the scheduler refuses (negative α, unordered thresholds, ...).
SchedulerCoefficients coefficientsFromJson(const std::string& text, const std::string& source);
// Reads and parses a file; throws CoefficientsError when it is missing or unusable.
SchedulerCoefficients loadCoefficients(const std::string& path);

}  // namespace lodopt::scheduler
