// `gi1`'s lights as one list (section 2.3): index l < P a punctual light (scene_lights), then
// the frame's area lights (emissive meshes: area_lights, area_triangles), then, where the scene
// has one, the environment; P = gi1.counts.x, and gi1.lights.x counts them all. The light grid
// (gi1_light_grid.comp) ranks them per cell, the hits sample them (gi1_light_sample.glsl).
// Needs shaders/scene.glsl, lights.glsl, environment.glsl, sampling.glsl and
// passes/area_light_parts.glsl; the includer binds area_lights[] and area_triangles[].
#ifndef GIQ_GI1_LIGHT_GLSL
#define GIQ_GI1_LIGHT_GLSL

bool gi1_is_environment(uint l) { return l >= gi1.counts.x + gi1.counts.y; }

// The environment's mean radiance, from six directions (a constant environment exactly).
vec3 gi1_environment_mean() {
  vec3 sum = vec3(0.0);
  for (uint a = 0u; a < 6u; ++a) {
    vec3 d = vec3(0.0);
    d[a % 3u] = a < 3u ? 1.0 : -1.0;
    sum += environment_radiance(gi1.environment, d);
  }
  return sum / 6.0;
}

// How much light l deposits at point c, as luminance (the grid's importance, section 2.3.2):
// a spot counts as a point light (its cone may cross a cell between its corners), an area
// light as its triangles' power towards c with the inverse-square law, no closer than
// `near` (a corner on the light), the environment as pi times its mean radiance.
float gi1_light_importance(uint l, vec3 c, float near) {
  if (l < gi1.counts.x) {
    GpuLight s = scene_lights[l];
    if (int(s.position.w) == GIQ_LIGHT_DIRECTIONAL) return luminance(s.radiant.rgb);
    vec3 d = s.position.xyz - c;
    float d2 = max(dot(d, d), near * near);
    return luminance(s.radiant.rgb) * range_window(sqrt(d2), s.direction.w) / d2;
  }
  if (gi1_is_environment(l)) return PI * luminance(gi1_environment_mean());
  GpuAreaLight a = area_lights[l - gi1.counts.x];
  float sum = 0.0;
  for (uint k = 0u; k < a.range.y; ++k) {
    GpuAreaTriangle t = area_triangle(a, k);
    vec3 n2 = cross(t.b.xyz - t.a.xyz, t.c.xyz - t.a.xyz);  // twice the area along the normal
    vec3 to = c - (t.a.xyz + t.b.xyz + t.c.xyz) / 3.0;
    float d2 = max(dot(to, to), near * near);
    float cos_area = dot(n2, to) / sqrt(d2);  // cos x twice the area
    if (t.a.w != 0.0) cos_area = abs(cos_area);
    sum += luminance(t.radiance.rgb) * 0.5 * max(cos_area, 0.0) / d2;
  }
  return sum;
}

#endif
