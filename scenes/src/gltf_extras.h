#pragma once
// The toolkit's data in the glTF root's `extras.giq` (schema in docs/scene-format.md): named
// views, the sequence to play, leak regions, the environment and particle emitters. Keys are checked strictly so
// a typo is an error rather than a silently ignored setting.

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "giq/scenes/scene.h"
#include "gltf_document.h"
#include "scene_source.h"

namespace giq::scenes::gltf {

struct ExtraView {
  std::string name;
  std::string field;  // "extras.giq.views[i]", for messages
  glm::dvec3 eye{0.0}, target{0.0, 0.0, -1.0}, up{0.0, 1.0, 0.0};  // world coordinates
  double yfov_deg = 45.0;
  double ymag = 0.0;  // > 0: orthographic half height (Camera::ymag)
};

struct Extras {
  std::vector<ExtraView> views;
  Sequence sequence;
  std::vector<std::string> leak_regions;
  std::vector<uint32_t> leak_object_ids;
  glm::vec3 environment{0.0f};
  std::vector<AreaShape> area_shapes;  // per glTF mesh: meshes[i].extras.giq.area_light
  // As declared, their node found; the loader completes them (complete_emitter).
  std::vector<Emitter> emitters;
  std::vector<std::string> emitter_fields;  // "extras.giq.emitters[i]", for messages
};

Extras parse_extras(const Document& doc, const SceneSource& src);

}  // namespace giq::scenes::gltf
