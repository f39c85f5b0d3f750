#pragma once
// Lambert (1760): the irradiance at q (normal n) from a convex polygon of unit radiance wholly
// above q's horizon, E = 1/2 sum_i theta_i n.unit(v_i x v_i+1) (Arvo 1995, eq. 7), in double
// precision: the closed form the direct pass's area lights and glowing particles are held to.
// Each edge's angle is atan2(|a x b|, a.b), which stays accurate for the small, distant faces of
// particles, where acos(a.b) would lose it.
#include <glm/glm.hpp>

#include <cmath>
#include <vector>

namespace giq::test {

inline const glm::dvec3 kUp(0.0, 1.0, 0.0);

inline double polygon_irradiance(glm::dvec3 q, glm::dvec3 n, const std::vector<glm::dvec3>& polygon) {
  double e = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3 a = glm::normalize(polygon[i] - q), b = glm::normalize(polygon[(i + 1) % polygon.size()] - q);
    const glm::dvec3 c = glm::cross(a, b);
    const double l = glm::length(c);
    if (l > 0.0) e += std::atan2(l, glm::dot(a, b)) * glm::dot(n, c) / l;
  }
  return 0.5 * std::abs(e);
}

}  // namespace giq::test
