#include "reference_frame.h"

#include "scene_setup.h"

namespace giq::cli {

ReferenceFrame reference_frame(const scenes::Scene& scene, const std::string& scene_path, const std::string& view,
                               const std::vector<std::string>& camera, int frame,
                               const reference::RenderSettings& settings) {
  ReferenceFrame r{scene.features.animation ? scene.at_frame(frame) : scene, {}, {}};
  reference::ReferenceMetadata& meta = r.metadata;
  meta.scene = scene_path;
  meta.scene_hash = scene.content_hash;
  meta.frame = frame;
  const scenes::View& v = r.posed.view(!camera.empty() ? kCameraView : view.empty() ? "0" : view);
  meta.camera = v.camera;
  meta.view = v.name;
  for (const std::string& a : camera) {
    if (!meta.camera_given.empty()) meta.camera_given += ' ';
    meta.camera_given += a;
  }
  r.identity = "scene " + scene.content_hash + " view " + meta.view + " camera " + reference::describe_camera(meta.camera) +
               " frame " + std::to_string(frame) + " settings " + reference::settings_json(settings);
  return r;
}

}  // namespace giq::cli
