// `gi1`: the light sources' irradiance at a probe ray's hit, sampled (Boissé et al. 2022,
// section 2.3.1): resampled importance sampling (Talbot et al. 2005) with weighted reservoir
// sampling (Chao 1982) over `gi1.lights.y` candidates, each a light drawn uniformly from the
// list of the hit's light-grid cell (gi1_light_grid.comp) and a point on it (a punctual
// light's position, a uniform point of a uniformly chosen triangle of an area light, a
// cosine-distributed direction of the environment). The reservoir keeps one candidate with
// probability proportional to its weight p^ / q, p^ the luminance of its unshadowed
// irradiance and q the density it was drawn with. Without reuse the estimate,
// f(y) x sum(w) / (M p^(y)), is unbiased for the lights the cell lists (the grid leaves out
// only lights that deposit nothing there, and keeps the `light_grid_lights` most important).
//
// World-space reuse (the report's single temporal pass): the reservoir last frame left in the
// hit's cell of the reservoir grid (gi1_reservoir.glsl) joins, where its surface faced the
// same way (normals within 25 degrees, the report's bilateral test), its sample re-evaluated
// here and weighted by its W and its M (capped at `gi1.lights.z`). The combined reservoir is
// what this hit stores for the next frame; which of the hits in a cell stores it is the lowest
// ray index (an atomic minimum, gi1_reservoir_store.comp), the same on every run. Visibility
// enters only at the end, one shadow ray for the chosen sample: as the report says, the
// reuse then darkens where a light is hidden from part of a cell.
// Needs gi1_light.glsl, gi1_reservoir.glsl, shaders/bvh.glsl; the includer binds light_grid[],
// reservoirs[] (last frame's), reservoir_claims[] and reservoir_stash[].
#ifndef GIQ_GI1_LIGHT_SAMPLE_GLSL
#define GIQ_GI1_LIGHT_SAMPLE_GLSL

// The grid cell holding p (the nearest one for a point outside the grid).
uint gi1_light_cell(vec3 p) {
  uvec3 n = gi1.grid_cells.xyz;
  ivec3 c = clamp(ivec3(floor((p - gi1.grid.xyz) / gi1.grid.w)), ivec3(0), ivec3(n) - 1);
  return uint(c.x) + n.x * (uint(c.y) + n.y * uint(c.z));
}

struct Gi1LightSample {
  uint light, triangle;  // the light, and for an area light the triangle the point is on (in it)
  vec3 y;                // the point on an area light, or the environment's direction
  vec3 f;                // unshadowed irradiance contribution at the hit, in the light's measure
  float pdf;             // the density of the point in that measure (1 for a punctual light)
  vec3 wi;               // towards the light
  float dist;            // to it (1e30: directional light, environment)
};

// What light l's point y (on its triangle k for an area light; the direction for the
// environment; ignored for a punctual light) sends to p (geometric normal ng, shading normal
// ns), unshadowed.
Gi1LightSample gi1_light_at(uint l, uint k, vec3 y, vec3 p, vec3 ng, vec3 ns) {
  Gi1LightSample s;
  s.light = l;
  s.triangle = k;
  s.y = y;
  s.f = vec3(0.0);
  s.pdf = 0.0;
  s.wi = vec3(0.0, 0.0, 1.0);
  s.dist = 1e30;
  if (l < gi1.counts.x) {
    vec3 li = punctual_incident(scene_lights[l], p, s.wi, s.dist);
    s.f = li * max(dot(ns, s.wi), 0.0);
  } else if (gi1_is_environment(l)) {
    s.wi = y;
    s.f = environment_radiance(gi1.environment, y) * max(dot(ns, y), 0.0);
  } else {
    GpuAreaLight a = area_lights[l - gi1.counts.x];
    // A reservoir's triangle from the last frame may be past a stage of particles that has
    // fewer now.
    if (k >= a.range.y) return s;
    GpuAreaTriangle t = area_triangle(a, k);
    vec3 n2 = cross(t.b.xyz - t.a.xyz, t.c.xyz - t.a.xyz);
    vec3 d = y - p;
    float d2 = dot(d, d), len2 = length(n2);
    if (!(d2 > 0.0) || !(len2 > 0.0)) return s;
    s.dist = sqrt(d2);
    s.wi = d / s.dist;
    float cos_e = -dot(n2, s.wi) / len2;
    if (t.a.w != 0.0) cos_e = abs(cos_e);  // a double-sided emitter
    s.f = t.radiance.rgb * max(dot(ns, s.wi), 0.0) * max(cos_e, 0.0) / d2;
  }
  if (dot(ng, s.wi) <= 0.0) s.f = vec3(0.0);  // light from below the surface would leak
  return s;
}

// A point of light l drawn for p, with its density; pdf 0 where it sends nothing.
Gi1LightSample gi1_sample_light(uint l, vec3 p, vec3 ng, vec3 ns, vec2 u, float u_triangle) {
  if (l < gi1.counts.x) {
    Gi1LightSample s = gi1_light_at(l, 0u, vec3(0.0), p, ng, ns);
    s.pdf = 1.0;
    return s;
  }
  if (gi1_is_environment(l)) {
    vec3 local = sample_cosine(u);
    Gi1LightSample s = gi1_light_at(l, 0u, to_world(local, ns), p, ng, ns);
    s.pdf = local.z / PI;
    return s;
  }
  GpuAreaLight a = area_lights[l - gi1.counts.x];
  uint k = min(uint(u_triangle * float(a.range.y)), a.range.y - 1u);
  GpuAreaTriangle t = area_triangle(a, k);
  vec2 b = sample_triangle(u);
  vec3 y = t.a.xyz + b.x * (t.b.xyz - t.a.xyz) + b.y * (t.c.xyz - t.a.xyz);
  Gi1LightSample s = gi1_light_at(l, k, y, p, ng, ns);
  float area = 0.5 * length(cross(t.b.xyz - t.a.xyz, t.c.xyz - t.a.xyz));
  s.pdf = area > 0.0 ? 1.0 / (float(a.range.y) * area) : 0.0;
  return s;
}

// The irradiance at hit p (seen at `view_depth` along the view) of ray `ray` (its index in the
// stash), through a reservoir, shadowed.
vec3 gi1_sampled_irradiance(vec3 p, vec3 ng, vec3 ns, float view_depth, uint ray, inout Rng rng) {
  uint base = gi1_light_cell(p) * (gi1.grid_cells.w + 1u), listed = light_grid[base];
  uint m = gi1.lights.y, total_m = 0u;
  float w_sum = 0.0, chosen_target = 0.0;
  Gi1LightSample chosen;
  if (listed > 0u) {
    total_m = m;
    for (uint i = 0u; i < m; ++i) {
      uint l = light_grid[base + 1u + min(uint(rng_next(rng) * float(listed)), listed - 1u)];
      vec2 u = vec2(rng_next(rng), rng_next(rng));
      Gi1LightSample s = gi1_sample_light(l, p, ng, ns, u, rng_next(rng));
      float target = luminance(s.f);
      float w = s.pdf > 0.0 && target > 0.0 ? target * float(listed) / s.pdf : 0.0;
      w_sum += w;
      if (w > 0.0 && rng_next(rng) * w_sum < w) chosen = s, chosen_target = target;
    }
  }
  uint fingerprint;
  uint slot = gi1_reservoir_slot(p, view_depth, fingerprint);
  if (gi1.lights.z > 0u) {
    GpuGi1Reservoir r = reservoirs[slot];
    if (r.info.x == fingerprint && r.info.w > 0u && dot(r.weight.yzw, ns) > 0.9063) {  // cos 25 degrees
      Gi1LightSample s = gi1_light_at(r.info.y, r.info.z, r.point.xyz, p, ng, ns);
      uint mr = min(r.info.w, gi1.lights.z);
      float target = luminance(s.f);
      float w = target * r.weight.x * float(mr);
      total_m += mr;
      w_sum += w;
      if (w > 0.0 && rng_next(rng) * w_sum < w) chosen = s, chosen_target = target;
    }
  }
  bool found = w_sum > 0.0 && w_sum < 3.0e38 && chosen_target > 0.0;
  float weight = found ? w_sum / (float(total_m) * chosen_target) : 0.0;
  // This hit's reservoir, for the next frame: the claim decides which hit of the cell stores.
  GpuGi1Reservoir keep;
  keep.point = vec4(found ? chosen.y : vec3(0.0), uintBitsToFloat(slot));
  keep.info = uvec4(fingerprint, found ? chosen.light : 0u, found ? chosen.triangle : 0u, found ? total_m : 0u);
  keep.weight = vec4(weight, ns);
  reservoir_stash[ray] = keep;
  atomicMin(reservoir_claims[slot], ray);
  if (!found) return vec3(0.0);
  vec3 origin = offset_ray(p, ng);
  if (occluded(origin, chosen.wi, chosen.dist < 1e30 ? chosen.dist * (1.0 - 1e-4) : 1e30)) return vec3(0.0);
  return chosen.f * weight;
}

#endif
