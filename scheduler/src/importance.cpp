// Importance (Dong et al. 2015, eqs. 11-12, and our extended form) and the distance
// thresholds of the initial levels (eq. 4). See scheduler/importance.hpp.
#include "scheduler/importance.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "timemodel/features.hpp"

namespace lodopt::scheduler {

namespace {

// θ stays below π/2 so tan θ is finite; objects further off axis are behind the eye and culled.
constexpr double kMaxViewAngle = 1.5;

void checkCoefficient(double value, const char* name) {
    if (!std::isfinite(value) || value < 0.0) {
        throw std::invalid_argument(std::string("importance: ") + name + " = " + std::to_string(value) +
                                    ", must be finite and >= 0");
    }
}

}  // namespace

void validateCoefficients(const ImportanceCoefficients& c) {
    checkCoefficient(c.alpha1, "alpha1");
    checkCoefficient(c.alpha2, "alpha2");
    checkCoefficient(c.alpha3, "alpha3");
    checkCoefficient(c.alpha4, "alpha4");
    if (c.alpha1 + c.alpha2 + c.alpha3 + c.alpha4 <= 0.0) {
        throw std::invalid_argument("importance: alpha1..alpha4 are all 0");
    }
}

ImportanceTerms importanceTerms(const ObjectView& view) {
    assert(view.distance >= 0.0 && view.projectedArea > 0.0);
    ImportanceTerms terms;
    terms.distance = (1.0 + std::tan(view.viewAngleRadians)) * view.distance;
    terms.area = 100.0 / view.projectedArea;
    terms.pixels = 1e4 / std::max(view.projectedPixels, 1.0);
    terms.center = view.centerOffset;
    return terms;
}

double importanceDenominator(const ObjectView& view, const ImportanceCoefficients& c) {
    const ImportanceTerms terms = importanceTerms(view);
    // Terms with a zero α are skipped, so the published form never reads p or c.
    double d = c.alpha1 * terms.distance + c.alpha2 * terms.area;
    if (c.alpha3 != 0.0) d += c.alpha3 * terms.pixels;
    if (c.alpha4 != 0.0) d += c.alpha4 * terms.center;
    return d;
}

double importance(const ObjectView& view, double benchmarkDenominator, const ImportanceCoefficients& c, double weight) {
    assert(benchmarkDenominator > 0.0 && weight > 0.0);
    const double d = importanceDenominator(view, c);
    return d > 0.0 ? weight * benchmarkDenominator / d : std::numeric_limits<double>::infinity();
}

double importance(const ObjectView& view, const ObjectView& benchmark, const ImportanceCoefficients& c, double weight) {
    return importance(view, importanceDenominator(benchmark, c), c, weight);
}

ObjectShape objectShape(const scenes::Object& object) {
    ObjectShape shape;
    shape.transform = object.transform;
    shape.box = object.levels.empty() ? scenes::Bounds{} : object.levels[0].stats.bounds;
    // One sphere around every level's world box, so culling never drops a coarse level that
    // reaches further than level 0 (a billboard wider than its tree).
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    bool any = false;
    for (int level = 0; level < int(object.levels.size()); ++level) {
        const scenes::Bounds b = scenes::worldBounds(object, level);
        if (b.empty()) continue;
        low = glm::min(low, b.min);
        high = glm::max(high, b.max);
        any = true;
    }
    if (!any) {
        shape.center = glm::vec3(object.transform[3]);
        shape.radius = 0.0f;
        return shape;
    }
    shape.center = 0.5f * (low + high);
    shape.radius = 0.5f * glm::length(high - low);
    return shape;
}

double silhouetteArea(const scenes::Bounds& box, const glm::mat4& transform, glm::vec3 direction) {
    if (box.empty()) return 0.0;
    const glm::vec3 size = box.max - box.min;
    const glm::vec3 e1 = glm::vec3(transform[0]) * size.x;
    const glm::vec3 e2 = glm::vec3(transform[1]) * size.y;
    const glm::vec3 e3 = glm::vec3(transform[2]) * size.z;
    return std::abs(double(glm::dot(direction, glm::cross(e2, e3)))) +
           std::abs(double(glm::dot(direction, glm::cross(e3, e1)))) +
           std::abs(double(glm::dot(direction, glm::cross(e1, e2))));
}

ObjectView observe(const ObjectShape& shape, const scenes::Camera& camera, const glm::mat4& viewProjection, int width,
                   int height) {
    assert(width > 0 && height > 0);
    return observe(shape, camera, viewProjection,
                   timemodel::projectedPixels(shape.box, viewProjection * shape.transform, width, height));
}

ObjectView observe(const ObjectShape& shape, const scenes::Camera& camera, const glm::mat4& viewProjection,
                   double projectedPixels) {
    ObjectView view;
    const glm::vec3 viewDirection = glm::normalize(camera.target - camera.position);
    const glm::vec3 toObject = shape.center - camera.position;
    const float length = glm::length(toObject);
    view.distance = double(length);
    const glm::vec3 ray = length > 0.0f ? toObject / length : viewDirection;
    const double cosine = std::clamp(double(glm::dot(ray, viewDirection)), -1.0, 1.0);
    view.viewAngleRadians = std::min(std::acos(cosine), kMaxViewAngle);
    // A flat or empty box has no area; a floor keeps 100 / s finite (such an object is
    // simply unimportant, as DONG15's formula makes a tiny crown).
    view.projectedArea = std::max(silhouetteArea(shape.box, shape.transform, ray), 1e-6);
    view.projectedPixels = projectedPixels;
    const glm::vec4 clip = viewProjection * glm::vec4(shape.center, 1.0f);
    if (clip.w > 0.0f) {
        view.centerOffset = std::hypot(double(clip.x / clip.w), double(clip.y / clip.w)) / std::sqrt(2.0);
    } else {
        view.centerOffset = 2.0;  // behind the eye: further than any on-screen point
    }
    return view;
}

int distanceLevel(double x, const std::vector<double>& thresholds, int levelCount) {
    assert(levelCount >= 1);
    // Level k when t_k <= x < t_{k+1}: the number of thresholds at or below x.
    const int level = int(std::upper_bound(thresholds.begin(), thresholds.end(), x) - thresholds.begin());
    return std::min(level, levelCount - 1);
}

DistanceThresholds DistanceThresholds::geometric(double first, double ratio, int count) {
    assert(first > 0.0 && ratio > 1.0 && count >= 0);
    DistanceThresholds result;
    result.values.clear();
    double value = first;
    for (int k = 0; k < count; ++k, value *= ratio) result.values.push_back(value);
    return result;
}

void validateThresholds(const DistanceThresholds& thresholds) {
    const std::vector<double>& t = thresholds.values;
    for (std::size_t k = 0; k < t.size(); ++k) {
        if (!std::isfinite(t[k]) || t[k] <= 0.0 || (k > 0 && t[k] <= t[k - 1])) {
            throw std::invalid_argument("distance thresholds[" + std::to_string(k) + "] = " + std::to_string(t[k]) +
                                        ": thresholds must be finite, > 0 and strictly ascending");
        }
    }
}

}  // namespace lodopt::scheduler
