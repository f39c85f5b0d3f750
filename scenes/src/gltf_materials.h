#pragma once
// glTF materials and the textures they sample, decoded once to linear float RGBA.

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "giq/scenes/material.h"
#include "giq/scenes/texture.h"
#include "gltf_accessors.h"
#include "gltf_document.h"

namespace giq::scenes::gltf {

// Texture coordinates a material's textures read: a TEXCOORD_<set> attribute and a
// KHR_texture_transform. A material has up to two (Material::uv2_slots says which textures
// read the second); they are applied to a primitive's UVs when it is loaded (Mesh::uvs,
// Mesh::uvs2), so every renderer reads transformed sets; an affine map commutes with
// barycentric interpolation, so this is exact.
struct UvMapping {
  int set = 0;                // TEXCOORD_<set>
  glm::dmat3 transform{1.0};  // of (u, v, 1): offset * rotation * scale (KHR_texture_transform)
  std::string field;          // the first textureInfo that set it, for messages ("" = none)
  glm::vec2 apply(glm::vec2 uv) const { return glm::vec2(transform * glm::dvec3(glm::dvec2(uv), 1.0)); }
};

// The textures' images, decoding on worker threads (one per core) while the loader reads the
// geometry. finish() waits, fills the textures' texels and throws the first image's error;
// destroying it unfinished (another error) waits for the workers too.
class TextureDecoding {
 public:
  virtual ~TextureDecoding() = default;
  virtual void finish() = 0;
};

// Fills `materials` (one per glTF material, same order), the textures they use (texels once
// the returned decoding finishes) and each material's UV mappings (`uv`, same order; none,
// one or two each). Header errors (size, format) are thrown here.
std::unique_ptr<TextureDecoding> load_materials(const Context& ctx, const Document& doc, std::vector<Material>& materials,
                                                std::vector<Texture>& textures, std::vector<std::vector<UvMapping>>& uv);

}  // namespace giq::scenes::gltf
