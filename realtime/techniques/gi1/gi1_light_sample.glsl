// `gi1`: the light sources' irradiance at a probe ray's hit, sampled (Boissé et al. 2022,
// section 2.3.1): resampled importance sampling (Talbot et al. 2005) with weighted reservoir
// sampling (Chao 1982) over `gi1.lights.y` candidates, each a light drawn uniformly from the
// list of the hit's light-grid cell (gi1_light_grid.comp) and a point on it (a punctual
// light's position, a uniform point of a uniformly chosen triangle of an area light, a
// cosine-distributed direction of the environment). The reservoir keeps one candidate with
// probability proportional to its weight p^ / q, p^ the luminance of its unshadowed
// irradiance and q the density it was drawn with; one shadow ray then tests it, the report's
// single visibility test after resampling. The estimate, f(y) x sum(w) / (M p^(y)), is
// unbiased for the lights the cell lists (the grid leaves out only lights that deposit
// nothing there, and the `light_grid_lights` most important are kept). The report's
// world-space reuse of the reservoirs across frames is not done: each hit draws afresh.
// Needs gi1_light.glsl, shaders/bvh.glsl; the includer binds light_grid[].
#ifndef GIQ_GI1_LIGHT_SAMPLE_GLSL
#define GIQ_GI1_LIGHT_SAMPLE_GLSL

// The grid cell holding p (the nearest one for a point outside the grid).
uint gi1_light_cell(vec3 p) {
  uvec3 n = gi1.grid_cells.xyz;
  ivec3 c = clamp(ivec3(floor((p - gi1.grid.xyz) / gi1.grid.w)), ivec3(0), ivec3(n) - 1);
  return uint(c.x) + n.x * (uint(c.y) + n.y * uint(c.z));
}

struct Gi1LightSample {
  vec3 f;      // unshadowed irradiance contribution at the hit, in the light's own measure
  float pdf;   // the density of the point in that measure (1 for a punctual light)
  vec3 wi;     // towards the light
  float dist;  // to it (1e30: directional light, environment)
};

// A point of light l seen from p (geometric normal ng, shading normal ns); pdf 0 where it
// sends nothing.
Gi1LightSample gi1_sample_light(uint l, vec3 p, vec3 ng, vec3 ns, vec2 u, float u_triangle) {
  Gi1LightSample s;
  s.f = vec3(0.0);
  s.pdf = 0.0;
  if (l < gi1.counts.x) {
    vec3 li = punctual_incident(scene_lights[l], p, s.wi, s.dist);
    s.f = li * max(dot(ns, s.wi), 0.0);
    s.pdf = 1.0;
  } else if (gi1_is_environment(l)) {
    vec3 local = sample_cosine(u);
    s.wi = to_world(local, ns);
    s.dist = 1e30;
    s.f = environment_radiance(gi1.environment, s.wi) * local.z;
    s.pdf = local.z / PI;
  } else {
    GpuAreaLight a = area_lights[l - gi1.counts.x];
    uint k = min(uint(u_triangle * float(a.range.y)), a.range.y - 1u);
    GpuAreaTriangle t = area_triangles[a.range.x + k];
    vec2 b = sample_triangle(u);
    vec3 y = t.a.xyz + b.x * (t.b.xyz - t.a.xyz) + b.y * (t.c.xyz - t.a.xyz);
    vec3 n2 = cross(t.b.xyz - t.a.xyz, t.c.xyz - t.a.xyz);
    float area = 0.5 * length(n2);
    vec3 d = y - p;
    float d2 = dot(d, d);
    if (!(d2 > 0.0) || !(area > 0.0)) return s;
    s.dist = sqrt(d2);
    s.wi = d / s.dist;
    float cos_e = -dot(n2, s.wi) / (2.0 * area);
    if (t.a.w != 0.0) cos_e = abs(cos_e);  // a double-sided emitter
    s.f = t.radiance.rgb * max(dot(ns, s.wi), 0.0) * max(cos_e, 0.0) / d2;
    s.pdf = 1.0 / (float(a.range.y) * area);
  }
  if (dot(ng, s.wi) <= 0.0) s.f = vec3(0.0);  // light from below the surface would leak
  return s;
}

vec3 gi1_sampled_irradiance(vec3 p, vec3 ng, vec3 ns, inout Rng rng) {
  uint base = gi1_light_cell(p) * (gi1.grid_cells.w + 1u), listed = light_grid[base];
  if (listed == 0u) return vec3(0.0);
  uint m = gi1.lights.y;
  float w_sum = 0.0, chosen_target = 0.0;
  Gi1LightSample chosen;
  for (uint i = 0u; i < m; ++i) {
    uint l = light_grid[base + 1u + min(uint(rng_next(rng) * float(listed)), listed - 1u)];
    vec2 u = vec2(rng_next(rng), rng_next(rng));
    Gi1LightSample s = gi1_sample_light(l, p, ng, ns, u, rng_next(rng));
    float target = luminance(s.f);
    float w = s.pdf > 0.0 && target > 0.0 ? target * float(listed) / s.pdf : 0.0;
    w_sum += w;
    float pick = rng_next(rng);
    if (w > 0.0 && pick * w_sum < w) {
      chosen = s;
      chosen_target = target;
    }
  }
  if (!(w_sum > 0.0) || !(w_sum < 3.0e38)) return vec3(0.0);
  vec3 origin = offset_ray(p, ng);
  if (occluded(origin, chosen.wi, chosen.dist < 1e30 ? chosen.dist * (1.0 - 1e-4) : 1e30)) return vec3(0.0);
  return chosen.f * (w_sum / (float(m) * chosen_target));
}

#endif
