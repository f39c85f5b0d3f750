#pragma once
// Skins and morph targets read from the document (glTF 2.0 spec, 3.7.2.2 "Morph Targets" and
// 3.7.3 "Skins") and checked against each other: what placement.h evaluates at any instant.

#include <tiny_gltf.h>

#include <string>

#include "gltf_accessors.h"
#include "scene_source.h"

namespace giq::scenes::gltf {

// The morph targets and JOINTS_k/WEIGHTS_k sets of a primitive of `n` vertices into `out`.
// Each vertex's weights are divided by their sum, which the spec requires to be 1 and
// quantised or hand-edited files miss; a vertex whose weights are all zero is given to its
// first joint. Both are reported as warnings when they change anything beyond quantisation.
void load_deformation(const Context& ctx, const tinygltf::Primitive& p, const std::string& w, bool quantized, size_t n, DeformationRest& out);

// src.skins from the document's skins, and every node's skin and morph weights checked
// against its mesh: a skinned node's primitives carry joints within its skin, and no
// instancing; weights have one entry per target; a mesh's primitives agree on their targets.
void load_skins(const Context& ctx, SceneSource& src);

}  // namespace giq::scenes::gltf
