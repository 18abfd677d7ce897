// Calibration timing: the statistics of a sample's interleaved timing passes, how well each
// repeats, and which clock to fit.
//
// `lodopt calibrate` times every sample in several passes; each pass gives the least and the
// median wall time of its draws and their median process CPU time (PassTimes). A clock of
// timingClockNames() (profile.hpp) reads one of these per pass and reduces them to the
// sample's time: the least for "wall-min", the median for the others.
//
// Repeatability: a sample's time from its even passes against its odd passes, by the same
// statistic, relative to its time from all passes. This VM's frame speed jumps between levels
// within minutes (docs/timemodel.md "Partial blocks"); a median over passes that straddle a
// jump lands on either level from sample to sample, so on such a run the median-based clocks
// stop repeating while the least stays on the fast level. Other machines show the opposite: a
// long lower tail makes the least scatter (docs/timemodel.md "A steadier statistic"). So with
// kAutoClock the calibration fits the wall clock that repeated best in that run, judged on
// the fitting samples only (the held-out ones stay unseen by every choice).
#pragma once

#include <string>
#include <vector>

#include "timemodel/time_model.hpp"

namespace lodopt::timemodel {

// One sample's timings, one entry per pass (all three the same length), milliseconds.
struct PassTimes {
    std::vector<double> leastWall;   // each pass's least wall time
    std::vector<double> medianWall;  // each pass's median wall time
    std::vector<double> medianCpu;   // each pass's median process CPU time
};

// The middle value, the mean of the two middle ones for an even count; NaN for an empty list
// (JSON null), so that a missing median never reads as a measured 0. The one median of timings
// and of the reports' columns (calibration, the scheduler's walk, the CLI's tables).
double median(std::vector<double> values);

// The per-pass values `clock` (one of timingClockNames()) reduces: leastWall for wall-min and
// wall-min-median, medianWall for wall-median, medianCpu for cpu.
const std::vector<double>& perPassValues(const std::string& clock, const PassTimes& times);

// `clock`'s statistic of `perPass` (non-empty): its least for wall-min, its median otherwise.
double clockStatistic(const std::string& clock, const std::vector<double>& perPass);

// The sample's time on `clock` from all its passes; 0 with no pass.
double timeFromPasses(const std::string& clock, const PassTimes& times);

// Spread of `perPass` (non-empty, median > 0): (greatest − least) / median.
double passSpread(const std::vector<double>& perPass);

// Split-half repeatability on `clock` over the samples i with include[i] (include.size() ==
// times.size()): |even − odd| / all per sample, summarized; samples with fewer than two passes
// or a time ≤ 0 are skipped (count 0 when none is left).
ErrorStats splitHalfRepeatability(const std::string& clock, const std::vector<PassTimes>& times,
                                  const std::vector<bool>& include);

// `--clock auto`: fit the most repeatable wall clock of the run (see the file comment).
inline constexpr const char* kAutoClock = "auto";

struct ClockCandidate {
    std::string clock;
    ErrorStats repeatability;  // splitHalfRepeatability on the included samples
};

struct ClockChoice {
    std::string clock;                       // the chosen clock
    std::vector<ClockCandidate> candidates;  // the wall clocks judged, in the order tried
    bool measured = false;                   // false: no candidate had a repeatability (one pass): the default
};

// The wall clock (wall-min-median, wall-min, wall-median: tried in that order, a tie keeps the
// earlier) whose split-half median over the included samples is lowest; kDefaultTimingClock
// when no clock could be judged. cpu is never chosen: it is the work, not the frame's time.
ClockChoice chooseMostRepeatableClock(const std::vector<PassTimes>& times, const std::vector<bool>& include);

}  // namespace lodopt::timemodel
