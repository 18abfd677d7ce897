// Test fixtures for the scheduler: scenes made of MeshBuilder primitives and synthetic time
// models whose coefficients are set by hand.
//
//   grid scene (top view, nx x nz objects, `spacing` apart, centred on the origin):
//       z ^   o  o  o  o
//         |   o  o  o  o       each object: level 0 an ellipsoid 24x12 (528 triangles),
//         |   o  o  o  o       level 1 an ellipsoid 10x5 (90), level 2 a box (12)
//         +-------------> x
#pragma once

#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <string>
#include <vector>

#include "scenes/mesh_builder.hpp"
#include "scenes/scene.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::scheduler::testing {

inline scenes::Object makeBlob(const std::string& name, glm::vec3 position, float radius) {
    scenes::Object object;
    object.name = name;
    object.transform = glm::translate(glm::mat4(1.0f), position);
    const glm::vec3 radii(radius, radius * 1.5f, radius);
    const glm::vec3 center(0.0f, radius * 1.5f, 0.0f);
    for (int level = 0; level < 3; ++level) {
        scenes::MeshBuilder builder;
        if (level == 0) builder.addEllipsoid(center, radii, 24, 12);
        if (level == 1) builder.addEllipsoid(center, radii, 10, 5);
        if (level == 2) builder.addBox(center, radii);
        scenes::Level l;
        l.meshes.push_back(builder.finish());
        object.levels.push_back(std::move(l));
    }
    return object;
}

inline scenes::Scene makeGridScene(int nx, int nz, float spacing, float radius = 1.0f) {
    scenes::Scene scene;
    scene.name = "grid";
    for (int i = 0; i < nx; ++i) {
        for (int k = 0; k < nz; ++k) {
            const glm::vec3 position((float(i) - 0.5f * float(nx - 1)) * spacing, 0.0f,
                                     (float(k) - 0.5f * float(nz - 1)) * spacing);
            scene.objects.push_back(makeBlob("blob_" + std::to_string(i) + "_" + std::to_string(k), position, radius));
        }
    }
    scenes::updateStatistics(scene);
    scenes::Camera camera;
    camera.name = "overview";
    camera.position = glm::vec3(0.0f, 0.4f * spacing * float(nx), 0.6f * spacing * float(nz));
    camera.target = glm::vec3(0.0f);
    camera.farPlane = 10000.0f;
    scene.views.push_back(camera);
    return scene;
}

// A camera at `position` looking at `target`.
inline scenes::Camera lookAt(glm::vec3 position, glm::vec3 target, float fov = 60.0f) {
    scenes::Camera camera;
    camera.position = position;
    camera.target = target;
    camera.fovYDegrees = fov;
    camera.nearPlane = 0.1f;
    camera.farPlane = 10000.0f;
    return camera;
}

// T = interceptMs + msPerTriangle · triangles: a model the test can predict by hand (the
// triangle count is exact in every feature mode).
inline std::unique_ptr<timemodel::TimeModel> triangleModel(double interceptMs, double msPerTriangle) {
    auto model = timemodel::makeTimeModel("linear");
    std::vector<double> coefficients(model->coefficientNames().size(), 0.0);
    coefficients[0] = interceptMs;
    coefficients[std::size_t(timemodel::Feature::kTriangles) + 1] = msPerTriangle;
    model->setCoefficients(coefficients);
    return model;
}

}  // namespace lodopt::scheduler::testing
