#pragma once
// KHR_lights_punctual lights, posed in the scene's local frame, and the falloff formulas
// both renderers must share.
//
// Units: giq renders in radiometric units with the glTF numbers taken as they are. A point
// or spot light of intensity I and colour c has radiant intensity I*c (per steradian); a
// directional light of intensity E gives irradiance E*c on a surface facing it; an emissive
// surface emits radiance emissiveFactor x emissive_strength. No lumen/watt conversion is
// applied anywhere, so the reference and every real-time technique agree by construction.

#include <glm/glm.hpp>
#include <string>

namespace giq::scenes {

enum class LightType { Directional, Point, Spot };

struct Light {
  std::string name;
  LightType type = LightType::Point;
  int node = -1;  // glTF node the light is attached to
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;  // 0 = infinite (glTF: undefined range)
  float inner_cone = 0.0f;                // radians, spot only
  float outer_cone = 0.785398163397448f;  // radians (pi/4, the glTF default), spot only
  glm::vec3 position{0.0f};               // local frame; unused for directional lights
  glm::vec3 direction{0.0f, 0.0f, -1.0f}; // unit, the way the light travels (node's -Z)

  glm::vec3 radiant() const { return color * intensity; }
  // Emitted power, luminance-weighted (pbrt-v4's Light::Phi): 4 pi I for a point light, the
  // solid angle of the cone half-way between inner and outer times I for a spot, and for a
  // directional light its irradiance over a disc of `scene_radius` (the scene's cross-section).
  double power(double scene_radius) const;
};

// Rec. 709 luminance of a linear RGB colour: the weight light powers are compared by.
double luminance(glm::vec3 rgb);

// KHR_lights_punctual, "Range Property": the recommended smooth window,
// clamp(1 - (d / range)^4, 0, 1), multiplied onto the inverse-square law. 1 when range is 0.
float range_window(float distance, float range);

// KHR_lights_punctual, "Spot": angular attenuation from the cosine between the spot axis and
// the direction from the light to the point: a clamped linear ramp between cos(outer) and
// cos(inner), squared.
float spot_attenuation(float cos_angle, float inner_cone, float outer_cone);

}  // namespace giq::scenes
