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

#endif
