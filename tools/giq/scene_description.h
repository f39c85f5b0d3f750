#pragma once
// What `giq scene info --json` prints and giq.Scene(...).info holds: a scene's features,
// counts, bounds, lights, views, sequence and leak regions, and what the loader dropped.

#include <nlohmann/json.hpp>

#include "giq/scenes/scene.h"

namespace giq::cli {

nlohmann::json describe_scene(const scenes::Scene& scene);

}  // namespace giq::cli
