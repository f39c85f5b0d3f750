#version 460
// `gi1`: the new probes' rays (Boissé et al. 2022, sections 2.1.3 and 2.2). A work group per probe
// on the spawn list, a lane per ray, through a random point of the cell gi1_reconstruct.comp chose
// for it, through the shared compute BVH. A miss sees the environment. At a hit the light leaving
// it towards the probe is sampled (section 2.2.4): diffuse albedo / pi x (the light sources'
// irradiance there: with `light_sampling` sampled through the light grid, the environment among
// them, one shadow ray (section 2.3, gi1_light_sample.glsl), else every light exactly, one BVH
// shadow ray each (passes/hit_irradiance.glsl); plus, with feedback, the indirect
// irradiance this technique found there last frame where the hit was on screen: one more bounce per
// frame, the albedo capped below 1 so that the loop contracts). The hit's own emission is left out:
// the shared direct pass already carries it to the receivers, as `ddgi` does. The sample is filed
// under the hit's world-cache cell (gi1_hash.glsl): the cell's largest sample this frame is kept
// for the update's fixed-point sums, and the first ray to reach a tile this frame lists the tile
// for the update.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/bvh.glsl"
#include "shaders/brdf.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "shaders/lights.glsl"
#include "shaders/octahedron_irradiance.glsl"
#include "shaders/environment.glsl"
#include "shaders/camera.glsl"
#include "passes/direct_light_shared.h"
#include "passes/rsm_albedo.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

#include "passes/receiver.glsl"
#define GIQ_GI1_FRAME_ONLY
#include "techniques/gi1/gi1_common.glsl"
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 0) readonly buffer Spawn { uvec2 spawn[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 1) readonly buffer SpawnList { uint spawn_list[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 2) buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 3) writeonly buffer Queries { GpuGi1Query queries[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 4) coherent buffer CacheHash { uint cache_hash[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 5) coherent buffer CacheStamp { uint cache_stamp[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 6) buffer CacheMax { uint cache_max[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 7) writeonly buffer Touched { uint touched[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 8) readonly buffer AreaLights { GpuAreaLight area_lights[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 9) readonly buffer AreaTriangles { GpuAreaTriangle area_triangles[]; };
// Last frame's indirect irradiance at every pixel (gi1_denoise_temporal.comp): rgb, w the
// surface's view depth (-1: none).
layout(binding = GIQ_GI1_BINDING_COUNT + 10, rgba32f) uniform readonly image2D previous_irradiance;
// Per spawn slot and ray: the cell it is traced through (gi1_reconstruct.comp).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 11) readonly buffer RayCells { uvec2 ray_cells[]; };
// The light grid (gi1_light_grid.comp), read with `light_sampling`.
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 12) readonly buffer LightGrid { uint light_grid[]; };
// The reservoir grid as last frame left it, this frame's claims on its slots, and each ray's
// reservoir for gi1_reservoir_store.comp (gi1_light_sample.glsl).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 13) readonly buffer Reservoirs { GpuGi1Reservoir reservoirs[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 14) buffer ReservoirClaims { uint reservoir_claims[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 15) writeonly buffer ReservoirStash { GpuGi1Reservoir reservoir_stash[]; };

#include "passes/area_light_parts.glsl"
#include "passes/hit_irradiance.glsl"
#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_hash.glsl"
#include "techniques/gi1/gi1_dispatch.glsl"
#include "techniques/gi1/gi1_feedback.glsl"
#include "techniques/gi1/gi1_light.glsl"
#include "techniques/gi1/gi1_reservoir.glsl"
#include "techniques/gi1/gi1_light_sample.glsl"

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  uint lane = gl_LocalInvocationIndex;
  uint t = spawn_list[g];
  uvec2 px = gi1_unpack_pixel(spawn[t].x);
  Receiver r = load_receiver(ivec2(px));
  Rng rng = rng_init(px, gi1.jitter.z * GIQ_GI1_CELLS + lane, gi1_stream(gi1, 1u));
  uint cell = ray_cells[g * GIQ_GI1_CELLS + lane].x;
  vec3 dir = to_world(gi1_cell_direction(cell, vec2(rng_next(rng), rng_next(rng))), r.n);
  RayHit hit = trace_ray(receiver_ray_origin(r, receiver_geometric_normal(r), gi1.camera.position.xyz), dir, 1e30,
                         false);
  GpuGi1Query q;
  q.cell = uvec4(GIQ_GI1_NONE, GIQ_GI1_NONE, 0u, 0u);
  if (hit.triangle == 0xffffffffu) {
    q.radiance = vec4(environment_radiance(gi1.environment, dir), 1.0e30);
    queries[g * GIQ_GI1_CELLS + lane] = q;
    return;
  }
  q.radiance = vec4(0.0, 0.0, 0.0, hit.t);
  HitNormals hn = hit_normals(hit.triangle, hit.u, hit.v, dir);
  if (hn.black) {  // the back of a one-sided surface sends nothing
    queries[g * GIQ_GI1_CELLS + lane] = q;
    return;
  }
  vec3 a, b, c;
  triangle_vertices(hit.triangle, a, b, c);
  vec3 p = a + hit.u * (b - a) + hit.v * (c - a);
  vec3 albedo = diffuse_albedo(hit_material(hit.triangle, hit.u, hit.v, hn.ns));
  float distance_to_eye = camera_orthographic(gi1.camera) ? 0.0 : distance(p, gi1.camera.position.xyz);
  vec3 e = (gi1.counts.w & GIQ_GI1_LIGHT_SAMPLING) != 0u
               ? gi1_sampled_irradiance(p, hn.ng, hn.ns, distance_to_eye, g * GIQ_GI1_CELLS + lane, rng)
               : hit_irradiance(p, hn.ng, hn.ns, gi1.counts.x, gi1.counts.y);
  vec3 sample_ = albedo / PI * e;
  if (gi1_feedback_on()) sample_ += min(albedo, vec3(gi1.params.x)) / PI * feedback_irradiance(p);
  // A non-finite sample would poison the cell for good; it can only come from a degenerate
  // configuration and is dropped.
  if (!all(lessThan(abs(sample_), vec3(3.0e38)))) sample_ = vec3(0.0);
  q.radiance.rgb = sample_;

  Gi1CacheKey key = gi1_cache_key(gi1, p, dir, hit.t, distance_to_eye, (gi1.counts.w & GIQ_GI1_RAY_LENGTH_BIT) != 0u);
  bool first_use;
  uint tile = gi1_cache_insert(gi1, key, gi1.jitter.z, first_use);
  if (tile != GIQ_GI1_NONE) {
    q.cell = uvec4(tile, key.cell, 0u, 0u);
    // Non-negative floats order as their bits do.
    atomicMax(cache_max[tile * GIQ_GI1_CELLS + key.cell], floatBitsToUint(max(sample_.r, max(sample_.g, sample_.b))));
    if (first_use) touched[atomicAdd(counters.tile_groups.w, 1u)] = tile;
  }
  queries[g * GIQ_GI1_CELLS + lane] = q;
}
