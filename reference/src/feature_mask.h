#pragma once
// The compile-time feature mask the integrator is specialised on. A bit that is clear removes
// the corresponding code from the instantiation (if constexpr), so an all-diffuse, untextured
// scene lit by one area light runs no GGX, texture or punctual-light code at all.

#include "giq/scenes/features.h"

namespace giq::reference {

enum FeatureBit : unsigned {
  kSpecular = 1u << 0,     // some material has a GGX lobe
  kTextures = 1u << 1,     // some material samples a texture (normal maps included), a mesh has vertex colours, or the environment is a map
  kPunctual = 1u << 2,     // directional, point or spot lights
  kEmissive = 1u << 3,     // emissive triangles
  kEnvironment = 1u << 4,  // environment light, constant or a map
  kFeatureCount = 5,
};

constexpr bool has(unsigned mask, unsigned bit) { return (mask & bit) != 0; }

inline unsigned feature_mask(const scenes::FeatureSet& f) {
  unsigned m = 0;
  if (f.specular) m |= kSpecular;
  // An environment map is a texture lookup per escaped ray, which the lanes do not do.
  if (f.textures || f.normal_maps || f.vertex_colors || f.environment_map) m |= kTextures;
  if (f.directional_lights || f.point_lights || f.spot_lights) m |= kPunctual;
  if (f.emissive_meshes) m |= kEmissive;
  if (f.environment) m |= kEnvironment;
  return m;
}

}  // namespace giq::reference
