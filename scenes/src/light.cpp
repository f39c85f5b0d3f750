#include "giq/scenes/light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace giq::scenes {

double luminance(glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

double Light::power(double scene_radius) const {
  const double y = luminance(radiant());
  switch (type) {
    case LightType::Point: return 4.0 * std::numbers::pi * y;
    case LightType::Spot:
      return 2.0 * std::numbers::pi * (1.0 - std::cos(0.5 * (double(inner_cone) + double(outer_cone)))) * y;
    case LightType::Directional: return std::numbers::pi * (scene_radius * scene_radius) * y;
  }
  return 0.0;
}

float range_window(float distance, float range) {
  // KHR_lights_punctual, "Range Property", recommended implementation:
  //   clamp(1.0 - pow(current_distance / range, 4), 0, 1) / pow(current_distance, 2)
  // The inverse-square factor is left to the caller.
  if (!(range > 0.0f)) return 1.0f;
  const float r = distance / range;
  const float r2 = r * r;
  return std::clamp(1.0f - r2 * r2, 0.0f, 1.0f);
}

float spot_attenuation(float cos_angle, float inner_cone, float outer_cone) {
  // KHR_lights_punctual, "Inner and Outer Cone Angles", recommended implementation:
  //   lightAngleScale = 1.0f / max(0.001f, cos(innerConeAngle) - cos(outerConeAngle));
  //   lightAngleOffset = -cos(outerConeAngle) * lightAngleScale;
  //   angularAttenuation = saturate(cd * lightAngleScale + lightAngleOffset);
  //   angularAttenuation *= angularAttenuation;
  const float cos_outer = std::cos(outer_cone);
  const float scale = 1.0f / std::max(0.001f, std::cos(inner_cone) - cos_outer);
  const float offset = -cos_outer * scale;
  const float a = std::clamp(cos_angle * scale + offset, 0.0f, 1.0f);
  return a * a;
}

}  // namespace giq::scenes
