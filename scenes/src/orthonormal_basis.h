#pragma once
// A tangent frame about a unit vector, for the scene library's own geometry (particles'
// directions, tangents of vertices without UV area or whose tangent vanishes when posed).

#include <cmath>
#include <glm/glm.hpp>

namespace giq::scenes {

// t and b with (t, b, n) orthonormal and right-handed, without a branch on n's direction
// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited", JCGT 6(1), listing 3).
inline void orthonormal_basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z), c = n.x * n.y * a;
  t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
  b = {c, sign + n.y * n.y * a, -n.y};
}

// A unit vector perpendicular to unit n: the tangent of a vertex that has no better one.
inline glm::dvec3 any_perpendicular(const glm::dvec3& n) {
  glm::dvec3 t, b;
  orthonormal_basis(n, t, b);
  return t;
}

}  // namespace giq::scenes
