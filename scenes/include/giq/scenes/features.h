#pragma once
// What a scene contains, derived from its content. Renderers specialise on it (model only
// what the scene requires) and reject what they do not support at load time.

#include <string>
#include <vector>

namespace giq::scenes {

struct FeatureSet {
  bool directional_lights = false;
  bool point_lights = false;
  bool spot_lights = false;
  bool emissive_meshes = false;
  bool environment = false;      // environment radiance: constant (extras, --env r,g,b) or a map
  bool environment_map = false;  // an equirectangular map (--env FILE): Scene::environment_map
  bool specular = false;     // some material has a GGX lobe (Material::has_specular_lobe)
  bool textures = false;     // some material samples a texture
  bool normal_maps = false;
  bool vertex_colors = false;  // some mesh has COLOR_0
  bool alpha_mask = false;  // some material is MASK or BLEND: renderers test alpha coverage
  bool double_sided = false;  // some material is double-sided
  bool one_sided = false;     // some material is not (its back faces are black)
  bool animation = false;     // the sequence moves something
  bool skinning = false;      // some mesh is skinned (glTF skins): its vertices move with joints
  bool morph_targets = false;  // some mesh blends morph targets
  bool particles = false;      // the scene declares particle emitters (Scene::emitters)

  // Stable lower-case names of the features present, e.g. {"point_lights", "specular"}; used
  // for `giq scene info`, shader #defines (upper-cased, "GIQ_" prefixed) and reports.
  std::vector<std::string> names() const;

  bool operator==(const FeatureSet&) const = default;
};

}  // namespace giq::scenes
