// Importance of an object for the real-time scheduler, and the distance thresholds that give
// its initial level (Dong, Liu, Xia, Fan & Zhang 2015, "A time-critical adaptive approach for
// visualizing natural scenes on different devices", PLoS ONE 10(2), eq. 4 and eqs. 11-12).
//
// Published form (DONG15 eq. 11):  I = B / (α1 (1 + tan θ) d + α2 · 100 / s)
//   d  distance from the eye to the object's centre (world units; DONG15: metres),
//   θ  angle between the view direction and the direction to the object, [0, π/2),
//   s  projected area. DONG15's is the tree crown's projected area (m², a property of the
//      object and the direction, not of the distance); ours is the orthographic silhouette of
//      the object's level-0 bounding box seen along the eye ray, world units²,
//   B  the same denominator for a benchmark object (eq. 12), which therefore has I = 1.
// Defaults α1 = 0.6, α2 = 0.4. DONG15's Table 4 (benchmark d = 15, θ = 0°, s = 6) is
// reproduced by tests/scheduler/importance_test.cpp: the published two decimals are the
// formula's values truncated, not rounded (0.698 is printed 0.69, 1.356 is printed 1.35).
//
// Extended form (ours, so that tuning may choose more features behind the same interface):
//   D = α1 (1 + tan θ) d + α2 · 100 / s + α3 · 10⁴ / p + α4 · c,   I = w · B / D
//   p  projected pixels of the level-0 bounding box on screen (CITY17's #pixels), floored at
//      one pixel; 10⁴ / p = 100 / (p / 100), p counted in hundreds of pixels as the
//      optimizer's projectedArea hint,
//   c  distance of the projected centre from the screen centre in half-diagonals (0 at the
//      centre, 1 at a corner, larger off screen),
//   w  a per-object weight > 0 (1 by default).
// With α3 = α4 = 0 and w = 1 it is the published form.
//
// The optimizer's `importance` baseline (optimizer/heuristics.hpp, importanceDenominator and
// importance) implements the same eq. 11 over its plain-number hints; the scheduler may not
// depend on the optimizer, so the formula lives here again. Both give the same value for the
// same (d, θ, s, α1, α2): tests/scheduler/importance_test.cpp pins the published values.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "scenes/scene.hpp"

namespace lodopt::scheduler {

// What the importance formula sees of one object from one camera.
struct ObjectView {
    double distance = 0.0;          // d >= 0, world units
    double viewAngleRadians = 0.0;  // θ in [0, π/2)
    double projectedArea = 1.0;     // s > 0, world units²
    double projectedPixels = 1.0;   // p >= 0, pixels (floored at 1 by the formula)
    double centerOffset = 0.0;      // c >= 0, half-diagonals from the screen centre
};

struct ImportanceCoefficients {
    double alpha1 = 0.6;  // >= 0, finite: distance term (DONG15 default)
    double alpha2 = 0.4;  // >= 0, finite: projected-area term (DONG15 default)
    double alpha3 = 0.0;  // >= 0, finite: projected-pixels term (extended form)
    double alpha4 = 0.0;  // >= 0, finite: screen-centre term (extended form)
    bool extended() const { return alpha3 != 0.0 || alpha4 != 0.0; }
};

// Throws std::invalid_argument naming the first coefficient that is negative or not finite,
// or when all four are 0.
void validateCoefficients(const ImportanceCoefficients& coefficients);

// The four terms of the denominator without their α (distance, area, pixels, centre).
struct ImportanceTerms {
    double distance = 0.0;  // (1 + tan θ) d
    double area = 0.0;      // 100 / s
    double pixels = 0.0;    // 10⁴ / max(p, 1)
    double center = 0.0;    // c
};
ImportanceTerms importanceTerms(const ObjectView& view);

// D = Σ α_k · term_k, >= 0. `view` as documented on ObjectView (caller's duty).
double importanceDenominator(const ObjectView& view, const ImportanceCoefficients& coefficients);

// I = weight · B / D (DONG15 eq. 11) with B = `benchmarkDenominator` > 0; a zero denominator
// (an object at the eye with only the distance term) is infinitely important.
double importance(const ObjectView& view, double benchmarkDenominator, const ImportanceCoefficients& coefficients,
                  double weight = 1.0);
// The same with B computed from a benchmark object (eq. 12).
double importance(const ObjectView& view, const ObjectView& benchmark, const ImportanceCoefficients& coefficients,
                  double weight = 1.0);

// How an object is seen: its centre and extent (world space) against a camera and a viewport.
// Objects are static, so the scheduler precomputes these per object once.
struct ObjectShape {
    glm::vec3 center{0.0f};  // bounding-sphere centre, world space
    float radius = 0.0f;     // bounding-sphere radius, world units (of every level)
    // Level-0 bounding box: its object-space bounds and the object's transform.
    scenes::Bounds box;
    glm::mat4 transform{1.0f};
};
// The level-0 shape of `object` (sphere over every level's world bounds).
ObjectShape objectShape(const scenes::Object& object);

// Orthographic area of an oriented box seen along `direction` (unit length, world space):
// |v·(e2×e3)| + |v·(e3×e1)| + |v·(e1×e2)| for the box's world edge vectors e1, e2, e3.
double silhouetteArea(const scenes::Bounds& box, const glm::mat4& transform, glm::vec3 direction);

// d, θ, s, p and c of `shape` from `camera`. `viewProjection` = projection · view of the
// camera at `width` x `height` pixels (both > 0).
ObjectView observe(const ObjectShape& shape, const scenes::Camera& camera, const glm::mat4& viewProjection, int width,
                   int height);
// The same with p already known (`projectedPixels` >= 0, e.g. from the scheduler's own box
// projection), so the box is projected once per frame.
ObjectView observe(const ObjectShape& shape, const scenes::Camera& camera, const glm::mat4& viewProjection,
                   double projectedPixels);

// DONG15 eq. 4: level k when t_k <= x < t_{k+1} (t_0 = 0), clamped to the coarsest level.
// `thresholds` ascending, > 0 (validated by validateThresholds); `levelCount` >= 1.
int distanceLevel(double x, const std::vector<double>& thresholds, int levelCount);

// The thresholds of the initial levels. Relative (the default): x = d / r, the distance in
// bounding-sphere radii, so one set of thresholds serves objects of every size; absolute:
// x = d in world units, as DONG15 prints them.
struct DistanceThresholds {
    std::vector<double> values = {4.0, 8.0, 16.0, 32.0, 64.0, 128.0, 256.0};  // ascending, > 0
    bool relativeToRadius = true;
    // t_k = first · ratio^(k-1), k = 1..count: the family tuning searches.
    static DistanceThresholds geometric(double first, double ratio, int count);
};
// Throws std::invalid_argument unless the values are finite, > 0 and strictly ascending.
void validateThresholds(const DistanceThresholds& thresholds);

}  // namespace lodopt::scheduler
