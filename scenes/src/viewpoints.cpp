#include "scenes/viewpoints.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/gtc/constants.hpp>

namespace lodopt::scenes {

namespace {

template <typename T>
T parseNumber(std::string_view text, const char* what, std::string_view whole) {
    T value{};
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, value);
    if (text.empty() || error != std::errc() || stop != end) {
        throw std::invalid_argument("grid '" + std::string(whole) + "': " + what + " '" + std::string(text) +
                                    "' is not a number (expected CxRxD@H or CxRxD@H/P, e.g. 10x10x8@2)");
    }
    return value;
}

}  // namespace

CameraGrid parseCameraGrid(std::string_view text) {
    const std::size_t at = text.find('@');
    if (at == std::string_view::npos) {
        throw std::invalid_argument("grid '" + std::string(text) +
                                    "': no '@HEIGHT' (expected CxRxD@H or CxRxD@H/P, e.g. 10x10x8@2)");
    }
    const std::string_view counts = text.substr(0, at);
    std::string_view placement = text.substr(at + 1);
    CameraGrid grid;
    int* fields[3] = {&grid.columns, &grid.rows, &grid.directions};
    const char* names[3] = {"columns", "rows", "directions"};
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
        const std::size_t cross = counts.find('x', start);
        if ((k < 2) != (cross != std::string_view::npos)) {
            throw std::invalid_argument("grid '" + std::string(text) +
                                        "': expected three counts CxRxD before '@' (e.g. 10x10x8@2)");
        }
        const std::string_view part = counts.substr(start, k < 2 ? cross - start : std::string_view::npos);
        *fields[k] = parseNumber<int>(part, names[k], text);
        if (*fields[k] < 1) {
            throw std::invalid_argument("grid '" + std::string(text) + "': " + names[k] + " must be >= 1");
        }
        start = cross + 1;
    }
    const std::size_t slash = placement.find('/');
    grid.height = parseNumber<float>(placement.substr(0, slash), "height", text);
    if (slash != std::string_view::npos) grid.pitchDegrees = parseNumber<float>(placement.substr(slash + 1), "pitch", text);
    if (!std::isfinite(grid.height)) throw std::invalid_argument("grid '" + std::string(text) + "': height must be finite");
    if (!(grid.pitchDegrees > -90.0f && grid.pitchDegrees < 90.0f)) {
        throw std::invalid_argument("grid '" + std::string(text) + "': pitch must be in (-90, 90) degrees");
    }
    return grid;
}

Bounds sceneBounds(const Scene& scene) {
    Bounds all;
    all.min = glm::vec3(std::numeric_limits<float>::max());
    all.max = glm::vec3(-std::numeric_limits<float>::max());
    for (const Object& object : scene.objects) {
        if (object.levels.empty()) continue;
        const Bounds bounds = worldBounds(object, 0);
        if (bounds.empty()) continue;
        all.min = glm::min(all.min, bounds.min);
        all.max = glm::max(all.max, bounds.max);
    }
    if (all.empty()) return Bounds{glm::vec3(0.0f), glm::vec3(-1.0f), glm::vec3(0.0f), 0.0f};
    all.sphereCenter = 0.5f * (all.min + all.max);
    all.sphereRadius = 0.5f * glm::length(all.max - all.min);
    return all;
}

std::vector<Camera> gridCameras(const Scene& scene, const CameraGrid& grid) {
    if (grid.columns < 1 || grid.rows < 1 || grid.directions < 1) {
        throw SceneError("camera grid: columns, rows and directions must be >= 1");
    }
    if (!std::isfinite(grid.height) || !(grid.pitchDegrees > -90.0f && grid.pitchDegrees < 90.0f) ||
        !(grid.fovYDegrees > 0.0f && grid.fovYDegrees < 180.0f)) {
        throw SceneError("camera grid: height must be finite, pitch in (-90, 90), fov in (0, 180)");
    }
    const Bounds bounds = sceneBounds(scene);
    if (!grid.box && bounds.empty()) {
        throw SceneError("camera grid: scene '" + scene.name + "' has no geometry to place a grid over; give a box");
    }
    const GroundBox box = grid.box ? *grid.box : GroundBox{bounds.min.x, bounds.min.z, bounds.max.x, bounds.max.z};
    if (!(box.maxX >= box.minX && box.maxZ >= box.minZ) || !std::isfinite(box.minX + box.maxX + box.minZ + box.maxZ)) {
        throw SceneError("camera grid: box must have min <= max on x and z, finite");
    }
    const float ground = bounds.empty() ? 0.0f : bounds.min.y;
    const float extent = bounds.empty() ? 1.0f : glm::length(bounds.max - bounds.min);
    const float pitch = glm::radians(grid.pitchDegrees);
    std::vector<Camera> cameras;
    cameras.reserve(std::size_t(grid.columns) * std::size_t(grid.rows) * std::size_t(grid.directions));
    for (int row = 0; row < grid.rows; ++row) {
        for (int column = 0; column < grid.columns; ++column) {
            const float x = box.minX + (box.maxX - box.minX) * (float(column) + 0.5f) / float(grid.columns);
            const float z = box.minZ + (box.maxZ - box.minZ) * (float(row) + 0.5f) / float(grid.rows);
            for (int direction = 0; direction < grid.directions; ++direction) {
                const float yaw = glm::two_pi<float>() * float(direction) / float(grid.directions);
                Camera camera;
                camera.name = "grid_" + std::to_string(row) + "_" + std::to_string(column) + "_" +
                              std::to_string(direction);
                camera.position = glm::vec3(x, ground + grid.height, z);
                const glm::vec3 look(std::cos(pitch) * std::cos(yaw), std::sin(pitch), std::cos(pitch) * std::sin(yaw));
                camera.target = camera.position + look;
                camera.fovYDegrees = grid.fovYDegrees;
                // Far enough to see across the whole scene from any grid position.
                camera.farPlane = std::max(1000.0f, 4.0f * (extent + std::abs(grid.height)));
                cameras.push_back(camera);
            }
        }
    }
    return cameras;
}

double screenSize(const Bounds& bounds, const Camera& camera) {
    if (bounds.empty()) return 0.0;
    const double distance = std::max(double(glm::length(bounds.sphereCenter - camera.position)), 1e-6);
    const double tanHalfFov = std::tan(glm::radians(double(camera.fovYDegrees)) / 2.0);
    return 2.0 * double(bounds.sphereRadius) / (2.0 * distance * tanHalfFov);
}

}  // namespace lodopt::scenes
