#pragma once
// The reference EXR of a finished render: the film's layers (Film::to_image) plus the header
// metadata that makes the file traceable (ARCHITECTURE.md, "Reference EXR").
//
// Header keys (all strings): giq.version, giq.scene, giq.scene_hash, giq.view, giq.camera,
// giq.frame, giq.spp, giq.seed, giq.settings (JSON), giq.nonfinite_samples and, when recorded,
// giq.render_time (seconds). The render time is the one value that differs between two runs
// of the same render, so it is written only on request: by default two renders with the same
// settings, on any thread count, resumed or not, are byte-identical files.

#include <cstdint>
#include <string>

#include "giq/image/image.h"
#include "giq/reference/film.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/camera.h"

namespace giq::reference {

struct ReferenceMetadata {
  std::string scene;       // the scene's path ("" for a scene built in code)
  std::string scene_hash;  // Scene::content_hash
  std::string view;        // view name, or "cli" for --camera
  scenes::Camera camera;   // in the scene's local frame
  // The camera as the command line gave it (`giq reference --camera`: world coordinates, an
  // engine's frame and units), recorded as "giq.camera_given"; "" for a view of the scene.
  std::string camera_given;
  int frame = 0;
  double render_seconds = -1.0;  // < 0: not recorded
};

// The settings that determine the image (not the thread count, which never changes it), as
// compact JSON with a stable key order.
std::string settings_json(const RenderSettings& settings);

// A one-line description of a camera: position, forward, up, vertical fov in degrees.
std::string describe_camera(const scenes::Camera& camera);

image::Image reference_image(const Film& film, const RenderSettings& settings, const ReferenceMetadata& meta);

}  // namespace giq::reference
