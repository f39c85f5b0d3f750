#include "giq/scenes/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace giq::scenes {

glm::vec2 equirect_uv(glm::vec3 d) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float u = 0.5f + std::atan2(d.x, -d.z) * (0.5f / kPi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * (1.0f / kPi);
  return {u, v};
}

glm::vec3 equirect_direction(glm::vec2 uv) {
  constexpr float kPi = std::numbers::pi_v<float>;
  const float phi = (uv.x - 0.5f) * 2.0f * kPi, theta = uv.y * kPi;
  const float s = std::sin(theta);
  return {s * std::sin(phi), std::cos(theta), -s * std::cos(phi)};
}

}  // namespace giq::scenes
