#pragma once
// A material's BSDF parameters (bsdf.h's BsdfParams) from its glTF values: for one point of a
// textured surface (make_surface), and once per render for every material without textures
// (RenderContext::material_bsdf, which the eight lanes gather).

#include <glm/glm.hpp>

#include <algorithm>

#include "feature_mask.h"
#include "giq/reference/bsdf.h"
#include "giq/scenes/material.h"

namespace giq::reference {

// The BSDF of material m with the values it has at a point (its factors, times its textures
// there when F has them).
template <unsigned F>
BsdfParams bsdf_params(const scenes::Material& m, glm::vec3 base, float metallic, float roughness, float specular,
                       glm::vec3 specular_color) {
  BsdfParams p;
  p.base = base;
  p.metallic = std::clamp(metallic, 0.0f, 1.0f);
  const float r = std::clamp(roughness, 0.0f, 1.0f);
  p.alpha = std::max(r * r, kMinAlpha);
  p.specular_lobe = has(F, kSpecular) && m.has_specular_lobe();
  // KHR_materials_specular: F0 = min(F0(ior = 1.5) * specularColor, 1) * specular, F90 = specular.
  p.f0_dielectric = glm::min(0.04f * specular_color, glm::vec3(1.0f)) * specular;
  p.f90_dielectric = specular;
  return p;
}
// The same for a material without textures.
template <unsigned F>
BsdfParams bsdf_params(const scenes::Material& m) {
  return bsdf_params<F>(m, glm::vec3(m.base_color), m.metallic, m.roughness, m.specular, m.specular_color);
}

}  // namespace giq::reference
