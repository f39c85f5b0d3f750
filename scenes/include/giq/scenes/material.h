#pragma once
// glTF 2.0 metallic-roughness material with the extensions giq understands
// (KHR_materials_emissive_strength, KHR_materials_specular; KHR_materials_ior and
// KHR_materials_unlit are mapped onto these fields when loaded). Texture members index
// Scene::textures; -1 means "no texture". A texture reads Mesh::uvs, or Mesh::uvs2 where its
// slot's bit is in Material::uv2_slots.

#include <algorithm>
#include <cstdint>
#include <glm/glm.hpp>
#include <string>

namespace giq::scenes {

// glTF 2.0, 3.9.4 "Alpha Coverage". giq renders BLEND as stochastic transparency: a ray meets
// the surface with probability alpha and passes it otherwise, so the reference converges to
// the surface's alpha-weighted average, whatever order the surfaces are in.
enum class AlphaMode { Opaque, Mask, Blend };

// A material's texture slots, as bits of Material::uv2_slots (and of the GPU's GIQ_SLOT_*).
enum TextureSlot : uint32_t {
  kBaseColorSlot = 1,
  kMetallicRoughnessSlot = 2,
  kNormalSlot = 4,
  kEmissiveSlot = 8,
  kSpecularSlot = 16,
  kSpecularColorSlot = 32,
};

struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};  // linear RGBA factor
  int base_color_texture = -1;
  float metallic = 1.0f;  // glTF defaults: a material that says nothing is a rough metal
  float roughness = 1.0f;
  int metallic_roughness_texture = -1;  // G = roughness, B = metallic
  // Emitted radiance = emissive (emissiveFactor x KHR_materials_emissive_strength) x texture.
  glm::vec3 emissive{0.0f};
  int emissive_texture = -1;
  int normal_texture = -1;
  float normal_scale = 1.0f;
  // KHR_materials_specular: scales the dielectric specular layer; 0 = pure Lambert.
  float specular = 1.0f;
  glm::vec3 specular_color{1.0f};
  int specular_texture = -1;        // A channel scales `specular`
  int specular_color_texture = -1;  // RGB scales `specular_color`
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  // The slots whose texture reads the material's second texture-coordinate mapping (a
  // TEXCOORD_n and KHR_texture_transform of their own, baked into Mesh::uvs2).
  uint32_t uv2_slots = 0;

  bool is_emissive() const { return emissive != glm::vec3(0.0f); }
  // How much of a point with this `alpha` (baseColorFactor.a x texture alpha x COLOR_0 alpha)
  // is there: 1 (OPAQUE), 1 or 0 by alphaCutoff (MASK), alpha (BLEND). The GPU's
  // alpha_coverage (realtime/shaders/textures.glsl) says the same.
  float coverage(float alpha) const {
    if (alpha_mode == AlphaMode::Opaque) return 1.0f;
    if (alpha_mode == AlphaMode::Mask) return alpha < alpha_cutoff ? 0.0f : 1.0f;
    return std::clamp(alpha, 0.0f, 1.0f);
  }
  // True when the material has a GGX lobe that can reflect light: metals always, dielectrics
  // unless KHR_materials_specular turns the layer off. Renderers use it to skip GGX entirely.
  bool has_specular_lobe() const {
    if (metallic > 0.0f || metallic_roughness_texture >= 0) return true;
    return specular > 0.0f && specular_color != glm::vec3(0.0f);
  }
  bool has_textures() const {
    return base_color_texture >= 0 || metallic_roughness_texture >= 0 || emissive_texture >= 0 ||
           normal_texture >= 0 || specular_texture >= 0 || specular_color_texture >= 0;
  }
};

}  // namespace giq::scenes
