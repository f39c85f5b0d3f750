#pragma once
// Where a node puts one primitive's vertices at one instant: morph targets blended in the
// mesh's frame (glTF 2.0 spec, 3.7.2.2 "Morph Targets"), then either skinned by the joints'
// matrices (3.7.3 "Skins") or moved by the node's world transform.

#include <glm/glm.hpp>
#include <vector>

#include "scene_source.h"

namespace giq::scenes {

struct PlacedVertices {
  std::vector<glm::dvec3> positions;  // world
  std::vector<glm::dvec3> normals;    // world, not normalised (zero where collapsed); empty when the primitive has none
  std::vector<glm::dvec4> tangents;   // world xyz, not normalised; w the bitangent's sign in the world's handedness
  // The placement mirrors the primitive (negative determinant), so that its winding is
  // reversed: for a skin, where most of the vertices are mirrored.
  bool mirrored = false;
  // A deforming primitive's matrices (Deformation::joints before taking them relative to the
  // origin): its skin's joint matrices, or its one transform; empty for a rigid primitive.
  std::vector<glm::dmat4> matrices;
  bool skinned = false;  // by its node's skin
};

// Primitive `p` of node `node` (which holds its mesh) at the instant of `nodes`. `M` is the
// node's world transform times its instance's (EXT_mesh_gpu_instancing); a skinned node ignores
// it, as glTF 2.0 spec, 3.7.3.3 requires ("the transform of the skinned mesh node MUST be
// ignored"). `positions_only`: normals and tangents are left empty (bounds need no more).
PlacedVertices place(const SceneSource& src, const PrimitiveSource& p, const NodePose& nodes, int node, const glm::dmat4& M,
                     bool positions_only = false);

}  // namespace giq::scenes
