#pragma once
// How a skinned or morphing mesh is made from its rest pose at one instant (glTF 2.0 spec,
// 3.7.2.2 "Morph Targets" and 3.7.3 "Skins"), for renderers that deform vertices themselves:
// the real-time module does it in a compute pass (realtime/shaders/deform.comp). Mesh::positions,
// normals and tangents hold the same vertices posed on the CPU in double precision
// (scenes/src/placement.cpp), which the reference renders; a renderer deforming in float
// agrees with them to float rounding.
//
// Vertex i of the Mesh is rest vertex i, except where the rest pose has no normals: then the
// Mesh has flat normals and its vertex 3k + c is corner c of rest triangle k (corners 1 and 2
// swapped where `mirrored`), with that triangle's face normal. A deforming Mesh keeps all its
// vertices in every pose; its triangles are the rest triangles (mirrored likewise) less those
// that collapse at this instant.

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace giq::scenes {

// One morph target's displacements: each list empty or one per rest vertex; TANGENT displaces
// xyz only.
struct MorphTarget {
  std::vector<glm::vec3> positions, normals, tangents;
};

// What does not change with time, shared by every pose of a scene.
struct DeformationRest {
  std::vector<glm::vec3> positions;   // the primitive's own frame
  std::vector<glm::vec3> normals;     // empty: flat normals
  std::vector<glm::vec4> tangents;    // empty when absent
  std::vector<glm::uvec3> triangles;  // before mirroring and collapse
  std::vector<MorphTarget> targets;
  // JOINTS_k and WEIGHTS_k, one entry per set k, one element per vertex: four indices into
  // Deformation::joints and their weights, which sum to 1 over all sets.
  std::vector<std::vector<glm::uvec4>> joints;
  std::vector<std::vector<glm::vec4>> weights;
  bool has_joints() const { return !joints.empty(); }
};

// The instant's part.
struct Deformation {
  std::shared_ptr<const DeformationRest> rest;
  // Skinned (the node has a skin): joint j's matrix, its node's world transform times its
  // inverse bind matrix. Otherwise one matrix, the node's world transform (joints in the rest
  // pose are then unused, glTF 2.0 spec, 3.7.3). Both are taken relative to
  // Scene::origin in double precision before rounding, so that geometry far from the world
  // origin keeps float precision. A vertex moves by the weighted sum of its joints' matrices.
  std::vector<glm::mat4> joints;
  bool skinned = false;
  std::vector<float> weights;  // morph target weights, one per target
  // The matrices mirror most vertices (negative determinant): the winding is reversed.
  bool mirrored = false;
};

}  // namespace giq::scenes
