#pragma once
// One frame of a reference render as `giq reference` and giq.reference() set it up: the scene
// posed at the frame, the view or --camera it is seen through, the metadata its EXR records
// and the identity a checkpoint of it must match. Both render it the same way, so the same
// settings give the same bits from either.

#include <string>
#include <vector>

#include "giq/reference/reference_exr.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"

namespace giq::cli {

struct ReferenceFrame {
  scenes::Scene posed;
  reference::ReferenceMetadata metadata;
  std::string identity;
};

// scene: as SceneSetup::load returned it (with the --camera view when `camera` is given);
// scene_path: as the user gave it; view: a name or index, "" for the first view.
ReferenceFrame reference_frame(const scenes::Scene& scene, const std::string& scene_path, const std::string& view,
                               const std::vector<std::string>& camera, int frame,
                               const reference::RenderSettings& settings);

}  // namespace giq::cli
