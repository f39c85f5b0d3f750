#pragma once
// The CPU octahedral map of unit vectors (Cigolle et al. 2014), written independently of
// shaders/octahedral.glsl: the ddgi tests check the shader against it, the SVGF tests encode
// synthetic normals with it.
#include <cmath>

#include <glm/glm.hpp>

namespace giq::test {

inline glm::vec2 oct_encode(glm::vec3 d) {
  const float l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
  glm::vec2 p(d.x / l1, d.y / l1);
  if (d.z < 0.0f)
    p = glm::vec2((1.0f - std::abs(p.y)) * (p.x >= 0.0f ? 1.0f : -1.0f),
                  (1.0f - std::abs(p.x)) * (p.y >= 0.0f ? 1.0f : -1.0f));
  return p;
}

inline glm::vec3 oct_decode(glm::vec2 e) {
  glm::vec3 v(e.x, e.y, 1.0f - std::abs(e.x) - std::abs(e.y));
  if (v.z < 0.0f) {
    const float x = v.x, y = v.y;
    v.x = (1.0f - std::abs(y)) * (x >= 0.0f ? 1.0f : -1.0f);
    v.y = (1.0f - std::abs(x)) * (y >= 0.0f ? 1.0f : -1.0f);
  }
  return glm::normalize(v);
}

}  // namespace giq::test
