#include "scenes/engine_lod.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>

namespace lodopt::scenes {

namespace {

double largestExtent(const Bounds& bounds) {
    const glm::vec3 size = bounds.max - bounds.min;
    return double(std::max({size.x, size.y, size.z}));
}

}  // namespace

double unrealScreenSize(double screenSize) { return screenSize; }

double unityRelativeHeight(double screenSize, const Bounds& bounds) {
    if (!(bounds.sphereRadius > 0.0f)) return screenSize;
    return screenSize * largestExtent(bounds) / (2.0 * double(bounds.sphereRadius));
}

double screenSizeFromUnityRelativeHeight(double relativeHeight, const Bounds& bounds) {
    const double extent = largestExtent(bounds);
    if (!(extent > 0.0)) return relativeHeight;
    return relativeHeight * 2.0 * double(bounds.sphereRadius) / extent;
}

double switchDistance(double screenSize, const Bounds& bounds, double fovYDegrees) {
    const double tanHalfFov = std::tan(glm::radians(fovYDegrees) / 2.0);
    return double(bounds.sphereRadius) / (screenSize * tanHalfFov);
}

double babylonScreenCoverage(double screenSize, double aspect) {
    return glm::pi<double>() * screenSize * screenSize / (4.0 * aspect);
}

}  // namespace lodopt::scenes
