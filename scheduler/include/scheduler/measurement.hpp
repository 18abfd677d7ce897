// How precisely this machine measures a frame, and what that allows a scheduler.
//
// A scheduler chooses what to draw; the clock decides what is measured. When one and the same
// frame, timed again and again, scatters by ±15 %, no choice of levels puts 90 % of the measured
// frames within ±10 % of a budget. bandCeiling() makes that bound a number: given repeated
// measurements of one frame, the largest share of them any single target could hold within
// [(1 − t)·B, (1 + t)·B]. If the noise is multiplicative and alike from frame to frame (the
// same scatter whatever is drawn), a scheduler that even knew each frame's true time could not
// expect a larger share of its frames in the band: choosing a frame of true time T only moves
// the band over the same scatter, by the factor B / T. `lodopt schedule --render` reports it
// (summary.json "measurement_ceiling"; docs/scheduler.md "Measurement ceiling").
#pragma once

#include <span>

namespace lodopt::scheduler {

// The largest share of `measurements` (positive times of one frame; others are ignored)
// within [(1 − tolerance)·B, (1 + tolerance)·B] for the best B: a window whose upper end is
// (1 + tolerance) / (1 − tolerance) times its lower end, slid over the sorted times.
// 0 when no measurement is positive; tolerance in (0, 1).
double bandCeiling(std::span<const double> measurements, double tolerance = 0.1);

}  // namespace lodopt::scheduler
