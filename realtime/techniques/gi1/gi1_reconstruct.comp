#version 460
// `gi1`: each new probe's hemisphere reconstructed from the probes carried over from
// last frame in the 3x3 tiles around it, and its rays guided by it (Boissé et al. 2022,
// section 2.1.3). Every cell of every carried probe within a cell size of the new probe's
// plane is moved to where its hit lies as seen from the new probe (parallax correction: the
// hit is the old probe's position plus the cell's direction times its ray length, which the
// probes keep in w) and added into the new probe's cell in that direction, as an integer in
// units of 1/65535 of the largest value moved (exact in any order, at any brightness, as the
// world cache's sums). The reconstruction is the new probe's history for the blend; a probe
// that gets one is marked as carrying history. With
// `ray_guiding`, the 64 rays pick cells with probability proportional to the reconstructed
// luminance (a prefix sum over the cells; a cell the reconstruction did not reach counts as
// the mean of those it did, so that it is still explored); without, one ray per cell.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/surface.glsl"
#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

#include "passes/receiver.glsl"
#include "techniques/gi1/gi1_common.glsl"
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 0) readonly buffer Spawn { uvec2 spawn[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 1) readonly buffer SpawnList { uint spawn_list[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 2) readonly buffer Counters { GpuGi1Counters counters; };
// Per spawn slot and cell: the reconstructed radiance (rgb) and how many old cells it holds (w).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 3) writeonly buffer Guide { vec4 guide[]; };
// Per spawn slot and ray: the cell it is traced through, and the probability with which that
// cell was picked (float bits).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 4) writeonly buffer RayCells { uvec2 ray_cells[]; };
// Per spawn slot: the new probe, which the blend puts in its tile (the probes stay as they
// are until every new probe has read its neighbours).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 5) writeonly buffer Fresh { GpuGi1Probe fresh[]; };

#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_dispatch.glsl"

shared uint largest;
shared uint sums[GIQ_GI1_CELLS][4];
shared float weights[GIQ_GI1_CELLS];
shared float cdf[GIQ_GI1_CELLS + 1];

// Neighbour k (0 .. 8) of tile t that carries a probe from last frame near the plane of the
// receiver r; GIQ_GI1_NONE if it has none.
uint neighbour(uint t, uint k, Receiver r, float cell) {
  ivec2 u = ivec2(t % gi1.size.z, t / gi1.size.z) + ivec2(int(k % 3u) - 1, int(k / 3u) - 1);
  if (any(lessThan(u, ivec2(0))) || any(greaterThanEqual(u, ivec2(gi1.size.zw)))) return GIQ_GI1_NONE;
  uint i = gi1_tile_index(uvec2(u));
  GpuGi1Probe p = probes[i];
  if (p.info.x == GIQ_GI1_NONE || (p.info.y & GIQ_GI1_REPROJECTED) == 0u) return GIQ_GI1_NONE;
  return abs(dot(p.position.xyz - r.x, r.n)) < cell ? i : GIQ_GI1_NONE;
}

// Where cell c of probe u lands as seen from the receiver: its cell there, or GIQ_GI1_NONE
// when the hit lies behind the receiver's plane; v is the cell's radiance and ray length.
uint moved_cell(uint u, uint c, Receiver r, out vec4 v) {
  GpuGi1Probe p = probes[u];
  v = radiance[u * GIQ_GI1_CELLS + c];
  vec3 dir = to_world(gi1_cell_direction(c, vec2(0.5)), p.normal.xyz);
  vec3 to_hit = p.position.xyz + dir * v.w - r.x;
  if (!(dot(to_hit, r.n) > 0.0)) return GIQ_GI1_NONE;
  return gi1_direction_cell(to_local(normalize(to_hit), r.n));
}

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  uint lane = gl_LocalInvocationIndex, t = spawn_list[g];
  Receiver r = load_receiver(ivec2(gi1_unpack_pixel(spawn[t].x)));
  float cell = gi1_screen_cell(gi1, gi1_view_depth(gi1.camera, r.x));
  if (lane == 0u) largest = 0u;
  sums[lane] = uint[4](0u, 0u, 0u, 0u);
  barrier();
  for (uint k = 0u; k < 9u; ++k) {
    uint u = neighbour(t, k, r, cell);
    vec4 v;
    if (u != GIQ_GI1_NONE && moved_cell(u, lane, r, v) != GIQ_GI1_NONE)
      atomicMax(largest, floatBitsToUint(max(v.r, max(v.g, v.b))));  // >= 0: ordered as its bits
  }
  barrier();
  float scale = uintBitsToFloat(largest);
  for (uint k = 0u; k < 9u; ++k) {
    uint u = neighbour(t, k, r, cell);
    if (u == GIQ_GI1_NONE) continue;
    vec4 v;
    uint c = moved_cell(u, lane, r, v);
    if (c == GIQ_GI1_NONE) continue;
    uvec3 q = scale > 0.0 ? uvec3(round(clamp(v.rgb / scale, 0.0, 1.0) * GIQ_GI1_QUANTUM)) : uvec3(0u);
    atomicAdd(sums[c][0], q.x);
    atomicAdd(sums[c][1], q.y);
    atomicAdd(sums[c][2], q.z);
    atomicAdd(sums[c][3], 1u);
  }
  barrier();
  uint n = sums[lane][3];
  vec3 rec = n > 0u ? vec3(sums[lane][0], sums[lane][1], sums[lane][2]) * (scale / (GIQ_GI1_QUANTUM * float(n)))
                    : vec3(0.0);
  guide[g * GIQ_GI1_CELLS + lane] = vec4(rec, float(n));
  weights[lane] = n > 0u ? luminance(rec) : -1.0;
  barrier();
  if (lane == 0u) {  // in cell order, so that every run sums alike
    float known = 0.0, count = 0.0;
    for (uint c = 0u; c < GIQ_GI1_CELLS; ++c)
      if (weights[c] >= 0.0) {
        known += weights[c];
        count += 1.0;
      }
    float unknown = count > 0.0 ? known / count : 1.0;
    GpuGi1Probe p;
    p.info = uvec4(spawn[t].x, GIQ_GI1_SPAWNED | (count > 0.0 ? GIQ_GI1_REPROJECTED : 0u) |
                                   (probes[t].info.y & GIQ_GI1_PATCHED), GIQ_GI1_NONE, 0u);
    p.position = vec4(r.x, gi1_view_depth(gi1.camera, r.x));
    p.normal = vec4(r.n, cell);
    fresh[g] = p;
    cdf[0] = 0.0;
    for (uint c = 0u; c < GIQ_GI1_CELLS; ++c) cdf[c + 1u] = cdf[c] + (weights[c] >= 0.0 ? weights[c] : unknown);
  }
  barrier();
  uint chosen = lane;
  float probability = 1.0 / float(GIQ_GI1_CELLS);
  if ((gi1.counts.w & GIQ_GI1_RAY_GUIDING) != 0u && cdf[GIQ_GI1_CELLS] > 0.0) {
    Rng rng = rng_init(uvec2(t, lane), gi1.jitter.z, gi1_stream(gi1, 2u));
    float u = rng_next(rng) * cdf[GIQ_GI1_CELLS];
    uint lo = 0u, hi = GIQ_GI1_CELLS - 1u;  // the first cell whose upper bound exceeds u
    while (lo < hi) {
      uint mid = (lo + hi) / 2u;
      if (cdf[mid + 1u] > u) hi = mid; else lo = mid + 1u;
    }
    chosen = lo;
    probability = (cdf[lo + 1u] - cdf[lo]) / cdf[GIQ_GI1_CELLS];
  }
  ray_cells[g * GIQ_GI1_CELLS + lane] = uvec2(chosen, floatBitsToUint(probability));
}
