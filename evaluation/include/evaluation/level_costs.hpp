// What each level of each searched object costs at a view the optimizer answered: the price a
// screen-size switch rule pays for drawing level k there instead of the answer's level, which
// `lodopt thresholds` fits its thresholds to (engine_thresholds.hpp).
//
// At the answer A (the most fitness F within the budget), moving object i alone to level k
// changes the fitness by dF_ik (the fast path's score of the moved combination minus A's) and the
// predicted time by dT_ik. A rule has no budget of its own (a global bias sets its cost later), so
// time and fitness are put in one unit by the view's exchange rate lambda, fitness per
// millisecond: the rate under which A is the best of its single moves, that is
// dF_ik <= lambda dT_ik for every move (finer moves gain at most lambda per millisecond they
// add; coarser moves lose at least lambda per millisecond they save). Such a lambda exists when A
// is a local optimum of the Lagrangian F - lambda T; the search is a heuristic, so lambda is the
// rate minimising the summed violations, sum max(0, dF - lambda dT) (convex and piecewise
// linear: its minimum lies at one of the moves' ratios dF / dT; the middle, geometrically, of a
// flat minimum). Then
//     cost_ik = lambda dT_ik - dF_ik,     0 at the answer's level,
// the fitness-equivalent loss of the move. A level merged into a coarser identical one (the same
// image) has that level's fitness and its own time.
#pragma once

#include <span>

#include "evaluation/engine_thresholds.hpp"
#include "evaluation/search_view.hpp"

namespace lodopt::evaluation {

// The rate minimising sum max(0, dF_m - lambda dT_m) over lambda >= 0 (see above); 0 without
// moves. Equal-length spans of finite values.
double exchangeRate(std::span<const double> deltaFitness, std::span<const double> deltaMs);

// `choices` is the optimizer's answer at `camera` (as a sweep records it); `settings` the view
// preparation of the search that gave it (fast path, budget). Costs for every object of
// `choices.searched` that this preparation also searches; an object it skips gets zero costs.
ViewLevelCosts measureLevelCosts(const scenes::Scene& scene, const scenes::Camera& camera, const ViewChoices& choices,
                                 renderer::Renderer& renderer, const metrics::MetricParameters& metrics,
                                 const FrameTimeEstimator& estimator, const timemodel::FeatureSet& readFeatures,
                                 const SearchViewSettings& settings);

}  // namespace lodopt::evaluation
