// Shared by `lodopt tune` and `lodopt schedule`: camera paths from the scene or a file, option
// parsing for the scheduler, and cameras as JSON.
//
// A camera path file is JSON:
//   {"name": "walk", "frames_per_second": 30,
//    "frames": [{"position": [x, y, z], "target": [x, y, z],
//                "up": [0, 1, 0], "fov_y_degrees": 45, "near": 0.1, "far": 1000}, ...]}
// ("up", "fov_y_degrees", "near" and "far" optional, with the defaults shown).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "statistics.hpp"
#include "scenes/scene.hpp"
#include "scheduler/scheduler.hpp"

namespace lodopt::cli {

// A path of `scene` by name, or a camera path file (see above). Throws UsageError naming the
// file and the element, or listing the scene's paths.
scenes::CameraPath loadCameraPath(const scenes::Scene& scene, const std::string& nameOrFile);
// The scene's first path; throws UsageError when it has none.
scenes::CameraPath defaultCameraPath(const scenes::Scene& scene);

// "bounds" | "exact"; throws UsageError.
scheduler::FeatureMode parseFeatureMode(const std::string& text);
// "flat" | "tiles"; throws UsageError.
scheduler::Organisation parseOrganisation(const std::string& text);
// "D1,K1,D2,K2,NEAR" into switch-control parameters; throws UsageError.
void parseSwitchControl(const std::string& text, scheduler::SwitchControlParameters& parameters);
// "hysteresis" | "vmi20"; throws UsageError.
scheduler::SwitchRule parseSwitchRule(const std::string& text);
// A coefficients file; throws UsageError with the file's message.
scheduler::SchedulerCoefficients loadCoefficientsOrThrow(const std::string& path);

// Camera as JSON (position, target, up, fov, near, far) for reports and checkpoints.
nlohmann::json cameraToJson(const scenes::Camera& camera);
// Throws UsageError naming `where` when a field is missing or mistyped.
scenes::Camera cameraFromJson(const nlohmann::json& json, const std::string& where);


}  // namespace lodopt::cli
