#pragma once
// Spawning secondary rays without self-intersection, independent of the scene's scale.
//
// Wächter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing
// Gems (2019), chapter 6, listing 1: the origin is moved along the geometric normal by a fixed
// number of units in the last place (ULPs) of each coordinate, which tracks the floating-point
// error of the hit point at any magnitude. Near zero, where ULPs vanish, the chapter uses a
// fixed absolute offset instead; here that offset and the threshold below which it applies are
// multiplied by the scene's extent, so a millimetre scene and a kilometre scene get the same
// relative offsets (the chapter's constants assume a scene of unit scale).

#include <glm/glm.hpp>

#include <bit>
#include <cmath>
#include <cstdint>

namespace giq::reference {

struct RayOffset {
  static constexpr float kOrigin = 1.0f / 32.0f;         // x scene extent
  static constexpr float kFloatScale = 1.0f / 65536.0f;  // x scene extent
  static constexpr float kIntScale = 256.0f;             // ULPs per unit of normal
};

// p: a point on a surface (computed from barycentrics, so its error is a few ULPs);
// n: the geometric normal on the side the new ray leaves towards; extent: the scene's size.
inline glm::vec3 offset_ray_origin(glm::vec3 p, glm::vec3 n, float extent) {
  glm::vec3 out;
  for (int k = 0; k < 3; ++k) {
    const int32_t of = int32_t(RayOffset::kIntScale * n[k]);
    const int32_t bits = std::bit_cast<int32_t>(p[k]);
    const float p_i = std::bit_cast<float>(bits + (p[k] < 0.0f ? -of : of));
    out[k] = std::abs(p[k]) < RayOffset::kOrigin * extent ? p[k] + RayOffset::kFloatScale * extent * n[k] : p_i;
  }
  return out;
}

}  // namespace giq::reference
