// Morph targets and skins (glTF 2.0 spec, 3.7.2.2 and 3.7.3), evaluated on the CPU in double
// precision: the reference poses every frame from here, and the real-time module uploads the
// same vertices.

#include "placement.h"

#include <glm/matrix.hpp>

namespace giq::scenes {
namespace {

// The cofactor matrix of L: det(L) L^-T, defined even for a singular L. Normals transform by
// it; its sign is fixed by the caller so that they keep facing outwards.
glm::dmat3 cofactor(const glm::dmat3& L) { return glm::dmat3(glm::cross(L[1], L[2]), glm::cross(L[2], L[0]), glm::cross(L[0], L[1])); }

}  // namespace

PlacedVertices place(const SceneSource& src, const PrimitiveSource& p, const NodePose& nodes, int node, const glm::dmat4& M,
                     bool positions_only) {
  const size_t n = p.positions.size();
  static const DeformationRest kRigid;
  const DeformationRest& d = p.deformation ? *p.deformation : kRigid;
  // Morph targets: the weighted sum of the targets' displacements, in the mesh's frame (only
  // for a primitive that has them: a rigid one is read as it is).
  std::vector<glm::dvec3> pos, nrm, tan;
  if (!d.targets.empty()) {
    pos.assign(p.positions.begin(), p.positions.end());
    nrm.assign(p.normals.begin(), p.normals.end());
    tan.resize(p.tangents.size());
    for (size_t i = 0; i < tan.size(); ++i) tan[i] = glm::dvec3(p.tangents[i]);
    const std::vector<double>& weights = nodes.weights[size_t(node)];
    for (size_t k = 0; k < d.targets.size() && k < weights.size(); ++k) {
      const double w = weights[k];
      if (w == 0.0) continue;
      const MorphTarget& t = d.targets[k];
      for (size_t i = 0; i < t.positions.size(); ++i) pos[i] += w * glm::dvec3(t.positions[i]);
      for (size_t i = 0; i < t.normals.size() && i < nrm.size(); ++i) nrm[i] += w * glm::dvec3(t.normals[i]);
      for (size_t i = 0; i < t.tangents.size() && i < tan.size(); ++i) tan[i] += w * glm::dvec3(t.tangents[i]);
    }
  }
  const bool morphed = !d.targets.empty();
  const auto position = [&](size_t i) { return morphed ? pos[i] : glm::dvec3(p.positions[i]); };
  const auto normal = [&](size_t i) { return morphed ? nrm[i] : glm::dvec3(p.normals[i]); };
  const auto tangent = [&](size_t i) { return morphed ? tan[i] : glm::dvec3(p.tangents[i]); };

  PlacedVertices out;
  out.positions.resize(n);
  out.normals.resize(positions_only ? 0 : p.normals.size());
  out.tangents.resize(positions_only ? 0 : p.tangents.size());
  const int skin = src.nodes[size_t(node)].skin;
  if (skin < 0 || !d.has_joints()) {
    const glm::dmat3 L(M), cof = cofactor(L);
    const double sign = glm::determinant(L) < 0.0 ? -1.0 : 1.0;
    out.mirrored = sign < 0.0;
    if (p.deformation) out.matrices.assign(1, M);
    for (size_t i = 0; i < n; ++i) out.positions[i] = glm::dvec3(M * glm::dvec4(position(i), 1.0));
    for (size_t i = 0; i < out.normals.size(); ++i) out.normals[i] = sign * (cof * normal(i));
    for (size_t i = 0; i < out.tangents.size(); ++i) out.tangents[i] = glm::dvec4(L * tangent(i), p.tangents[i].w < 0.0f ? -sign : sign);
    return out;
  }

  // Skinning: each vertex moves by the weighted sum of its joints' matrices, joint j's being
  // its node's world transform times its inverse bind matrix (3.7.3.1 "Joint Hierarchy").
  const SkinSource& s = src.skins[size_t(skin)];
  std::vector<glm::dmat4> joint(s.joints.size());
  for (size_t j = 0; j < joint.size(); ++j) joint[j] = nodes.world[size_t(s.joints[j])] * s.inverse_bind[j];
  int mirrored = 0;
  for (size_t i = 0; i < n; ++i) {
    glm::dmat4 S(0.0);
    for (size_t set = 0; set < d.joints.size(); ++set) {
      const glm::uvec4 j = d.joints[set][i];
      const glm::vec4 w = d.weights[set][i];
      for (int c = 0; c < 4; ++c)
        if (w[c] != 0.0f) S += double(w[c]) * joint[j[c]];
    }
    const glm::dmat3 L(S);
    const double sign = glm::determinant(L) < 0.0 ? -1.0 : 1.0;
    mirrored += sign < 0.0 ? 1 : -1;
    out.positions[i] = glm::dvec3(S * glm::dvec4(position(i), 1.0));
    if (i < out.normals.size()) out.normals[i] = sign * (cofactor(L) * normal(i));
    if (i < out.tangents.size()) out.tangents[i] = glm::dvec4(L * tangent(i), p.tangents[i].w < 0.0f ? -sign : sign);
  }
  out.mirrored = mirrored > 0;
  out.matrices = std::move(joint);
  out.skinned = true;
  return out;
}

}  // namespace giq::scenes
