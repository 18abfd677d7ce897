// The CLI's way to a time model: a device profile from `lodopt calibrate` (--profile), or the
// default profile shipped for the built-in scenes, and a model chosen by name (--model).
#pragma once

#include <memory>
#include <ostream>
#include <string>

#include "evaluation/time_cost.hpp"
#include "renderer/renderer.hpp"
#include "timemodel/time_model.hpp"

namespace lodopt::cli {

struct TimeEstimator {
    std::string name;                             // "linear (shipped default profile)"
    std::shared_ptr<timemodel::TimeModel> model;  // fitted
    evaluation::FrameTimeEstimator estimate;      // calls model->estimateMs
};

// Loads `profilePath` (empty = the profile shipped for `sceneName`, or for the default scene)
// and picks `modelName` (empty = the profile's default model). Warns on `warnings` when the
// profile was made on another renderer, frame clock, render size or machine (`timedOn`: the
// renderer the command draws with; null skips the renderer's checks). Throws UsageError for an
// unreadable profile or an unknown model.
TimeEstimator loadTimeEstimator(const std::string& profilePath, const std::string& modelName,
                                const std::string& sceneName, const renderer::RenderSettings& settings,
                                const renderer::Renderer* timedOn, std::ostream& warnings);


}  // namespace lodopt::cli
