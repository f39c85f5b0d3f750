// Punctual lights (KHR_lights_punctual) as giq::scenes defines them (scenes/src/light.cpp):
// inverse-square law times the recommended range window, spot cone falloff as a squared
// linear ramp in cos(angle). Needs scene.glsl.
#ifndef GIQ_LIGHTS_GLSL
#define GIQ_LIGHTS_GLSL

// scenes::range_window: clamp(1 - (d / range)^4, 0, 1); 1 when range is 0.
float range_window(float d, float range) {
  if (!(range > 0.0)) return 1.0;
  float r = d / range;
  float r2 = r * r;
  return clamp(1.0 - r2 * r2, 0.0, 1.0);
}

// scenes::spot_attenuation with scale and offset precomputed on the CPU (GpuLight::cone).
float spot_attenuation(GpuLight l, float cos_angle) {
  float a = clamp(cos_angle * l.cone.x + l.cone.y, 0.0, 1.0);
  return a * a;
}

// Direction from p towards the light (wi), the distance to it (infinity for directional
// lights) and the radiance-like factor: irradiance on a surface facing the light.
vec3 punctual_incident(GpuLight l, vec3 p, out vec3 wi, out float dist) {
  int type = int(l.position.w);
  if (type == GIQ_LIGHT_DIRECTIONAL) {
    wi = -l.direction.xyz;
    dist = 1e30;
    return l.radiant.rgb;
  }
  vec3 d = l.position.xyz - p;
  float d2 = dot(d, d);
  dist = sqrt(d2);
  wi = d / dist;
  if (!(d2 > 0.0)) return vec3(0.0);
  float f = range_window(dist, l.direction.w) / d2;
  if (type == GIQ_LIGHT_SPOT) f *= spot_attenuation(l, dot(l.direction.xyz, -wi));
  return l.radiant.rgb * f;
}

#endif
