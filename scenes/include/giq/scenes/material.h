#pragma once
// glTF 2.0 metallic-roughness material with the extensions giq understands
// (KHR_materials_emissive_strength, KHR_materials_specular; KHR_materials_ior and
// KHR_materials_unlit are mapped onto these fields when loaded). Texture members index
// Scene::textures; -1 means "no texture". Every texture reads Mesh::uvs.

#include <glm/glm.hpp>
#include <string>

namespace giq::scenes {

enum class AlphaMode { Opaque, Mask };  // BLEND is rejected at load time

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

  bool is_emissive() const { return emissive != glm::vec3(0.0f); }
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
