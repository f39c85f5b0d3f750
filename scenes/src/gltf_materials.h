#pragma once
// glTF materials and the textures they sample, decoded once to linear float RGBA.

#include <vector>

#include "giq/scenes/material.h"
#include "giq/scenes/texture.h"
#include "gltf_accessors.h"
#include "gltf_document.h"

namespace giq::scenes::gltf {

// Fills `materials` (one per glTF material, same order) and the textures they use.
void load_materials(const Context& ctx, const Document& doc, std::vector<Material>& materials, std::vector<Texture>& textures);

}  // namespace giq::scenes::gltf
