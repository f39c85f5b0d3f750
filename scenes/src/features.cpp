#include "giq/scenes/features.h"

namespace giq::scenes {

std::vector<std::string> FeatureSet::names() const {
  // Order is fixed (declaration order) so the list, the shader #defines derived from it and
  // reports are stable from run to run.
  const std::pair<bool, const char*> all[] = {
      {directional_lights, "directional_lights"},
      {point_lights, "point_lights"},
      {spot_lights, "spot_lights"},
      {emissive_meshes, "emissive_meshes"},
      {environment, "environment"},
      {environment_map, "environment_map"},
      {specular, "specular"},
      {textures, "textures"},
      {normal_maps, "normal_maps"},
      {vertex_colors, "vertex_colors"},
      {alpha_mask, "alpha_mask"},
      {double_sided, "double_sided"},
      {one_sided, "one_sided"},
      {animation, "animation"},
      {skinning, "skinning"},
      {morph_targets, "morph_targets"},
      {particles, "particles"},
  };
  std::vector<std::string> out;
  for (const auto& [present, name] : all)
    if (present) out.emplace_back(name);
  return out;
}

}  // namespace giq::scenes
