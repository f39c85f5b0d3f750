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
//
// The side cache (section 2.1.8): the entries the 3x3 tiles list (gi1_side_bin.comp) that lie
// on the new probe's plane with its normal (as reprojection asks) count in the reconstruction
// as the carried probes do. Then the slot schedules the blend's writes into it: where the
// tile's carried probe is not reused (the new probe is on another surface: evicted, as with
// thin geometry, Figure 11), the carried probe goes into the entry that matches it among
// those listed, else into a new entry at the back of the LRU order (the slot's own: the
// g-th from the back); the entry that matched the new probe best takes the new probe, so that
// the cache follows changing light. Each write claims its entry with an atomic minimum of
// its key (2g, 2g + 1): the lowest claim wins on every run, where the report's compare-and-
// swap lets timing choose. Every entry used is stamped as used this frame (most recently
// used: gi1_side_order.comp).
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
// The side cache (gi1_side_bin.comp, gi1_side_order.comp, gi1_blend.comp).
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 6) readonly buffer SideProbes { GpuGi1Probe side_probes[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 7) readonly buffer SideRadiance { vec4 side_radiance[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 8) readonly buffer SideOrder { uint side_order[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 9) buffer SideState { uint side_state[]; };
layout(std430, binding = GIQ_GI1_BINDING_COUNT + 10) writeonly buffer SideWrites { GpuGi1SideWrite side_writes[]; };

#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_dispatch.glsl"
#include "techniques/gi1/gi1_side.glsl"

shared uint largest;
shared uint sums[GIQ_GI1_CELLS][4];
shared float weights[GIQ_GI1_CELLS];
shared float cdf[GIQ_GI1_CELLS + 1];
shared uint listed[9];  // the side-cache entry each of the 3x3 tiles lists, or GIQ_GI1_NONE
shared uint side[9];    // those of them on the new probe's plane, or GIQ_GI1_NONE

// Tile k (0 .. 8) of the 3x3 around tile t, or GIQ_GI1_NONE off the screen.
uint around(uint t, uint k) {
  ivec2 u = ivec2(t % gi1.size.z, t / gi1.size.z) + ivec2(int(k % 3u) - 1, int(k / 3u) - 1);
  if (any(lessThan(u, ivec2(0))) || any(greaterThanEqual(u, ivec2(gi1.size.zw)))) return GIQ_GI1_NONE;
  return gi1_tile_index(uvec2(u));
}

// Neighbour k (0 .. 8) of tile t that carries a probe from last frame near the plane of the
// receiver r; GIQ_GI1_NONE if it has none.
uint neighbour(uint t, uint k, Receiver r, float cell) {
  uint i = around(t, k);
  if (i == GIQ_GI1_NONE) return GIQ_GI1_NONE;
  GpuGi1Probe p = probes[i];
  if (p.info.x == GIQ_GI1_NONE || (p.info.y & GIQ_GI1_REPROJECTED) == 0u) return GIQ_GI1_NONE;
  return abs(dot(p.position.xyz - r.x, r.n)) < cell ? i : GIQ_GI1_NONE;
}

// Whether probe (or entry) p lies within `cell` of the plane through x with normal n, facing
// as n does: the reprojection's test (Algorithm 1).
bool on_plane(GpuGi1Probe p, vec3 x, vec3 n, float cell) {
  return abs(dot(p.position.xyz - x, n)) < cell && dot(p.normal.xyz, n) > 0.95;
}

// Source k of the reconstruction: the carried probes of the 3x3 tiles (k < 9), then the
// side-cache entries they list (k >= 9). For this lane's cell c of it: where the cell lands
// as seen from the receiver, or GIQ_GI1_NONE (no such source, or the hit lies behind the
// receiver's plane); v is the cell's radiance and ray length.
uint moved_cell(uint t, uint k, uint c, Receiver r, float cell, out vec4 v) {
  v = vec4(0.0);
  GpuGi1Probe p;
  if (k < 9u) {
    uint u = neighbour(t, k, r, cell);
    if (u == GIQ_GI1_NONE) return GIQ_GI1_NONE;
    p = probes[u];
    v = radiance[u * GIQ_GI1_CELLS + c];
  } else {
    uint e = side[k - 9u];
    if (e == GIQ_GI1_NONE) return GIQ_GI1_NONE;
    p = side_probes[e];
    v = side_radiance[e * GIQ_GI1_CELLS + c];
  }
  vec3 dir = to_world(gi1_cell_direction(c, vec2(0.5)), p.normal.xyz);
  vec3 to_hit = p.position.xyz + dir * v.w - r.x;
  if (!(dot(to_hit, r.n) > 0.0)) return GIQ_GI1_NONE;
  return gi1_direction_cell(to_local(normalize(to_hit), r.n));
}

// The side cache's writes for slot g (tile t, new probe at receiver r), as described above.
void schedule_side_writes(uint g, uint t, Receiver r, float cell) {
  GpuGi1SideWrite w = GpuGi1SideWrite(GIQ_GI1_NONE, GIQ_GI1_NONE);
  GpuGi1Probe carried = probes[t];
  bool has_carried = carried.info.x != GIQ_GI1_NONE && (carried.info.y & GIQ_GI1_REPROJECTED) != 0u;
  if (has_carried && neighbour(t, 4u, r, cell) == GIQ_GI1_NONE) {  // evicted
    float nearest = 1e38;
    for (uint k = 0u; k < 9u; ++k) {
      uint e = listed[k];
      if (e == GIQ_GI1_NONE || !on_plane(side_probes[e], carried.position.xyz, carried.normal.xyz, carried.normal.w))
        continue;
      float d = distance(side_probes[e].position.xyz, carried.position.xyz);
      if (d < nearest) nearest = d, w.evicted = e;
    }
    if (w.evicted == GIQ_GI1_NONE && g < gi1.side.x) w.evicted = side_order[gi1.side.x - 1u - g];
  }
  float nearest = 1e38;
  for (uint k = 0u; k < 9u; ++k) {
    uint e = side[k];
    if (e == GIQ_GI1_NONE) continue;
    side_state[gi1_side_stamp(e)] = gi1.side.y;
    float d = distance(side_probes[e].position.xyz, r.x);
    if (d < nearest && e != w.evicted) nearest = d, w.fresh = e;
  }
  if (w.evicted != GIQ_GI1_NONE) {
    side_state[gi1_side_stamp(w.evicted)] = gi1.side.y;
    atomicMin(side_state[gi1_side_claim(w.evicted)], 2u * g);
  }
  if (w.fresh != GIQ_GI1_NONE) atomicMin(side_state[gi1_side_claim(w.fresh)], 2u * g + 1u);
  side_writes[g] = w;
}

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  uint lane = gl_LocalInvocationIndex, t = spawn_list[g];
  Receiver r = load_receiver(ivec2(gi1_unpack_pixel(spawn[t].x)));
  float cell = gi1_screen_cell(gi1, gi1_view_depth(gi1.camera, r.x));
  if (lane == 0u) largest = 0u;
  sums[lane] = uint[4](0u, 0u, 0u, 0u);
  if (lane < 9u) {
    uint i = gi1.side.x > 0u ? around(t, lane) : GIQ_GI1_NONE;
    uint rank = i != GIQ_GI1_NONE ? side_state[gi1_side_tile(i)] : 0xffffffffu;
    listed[lane] = rank != 0xffffffffu ? side_order[rank] : GIQ_GI1_NONE;
    side[lane] = listed[lane] != GIQ_GI1_NONE && on_plane(side_probes[listed[lane]], r.x, r.n, cell) ? listed[lane]
                                                                                                     : GIQ_GI1_NONE;
  }
  barrier();
  const uint sources = gi1.side.x > 0u ? 18u : 9u;
  for (uint k = 0u; k < sources; ++k) {
    vec4 v;
    if (moved_cell(t, k, lane, r, cell, v) != GIQ_GI1_NONE)
      atomicMax(largest, floatBitsToUint(max(v.r, max(v.g, v.b))));  // >= 0: ordered as its bits
  }
  barrier();
  float scale = uintBitsToFloat(largest);
  for (uint k = 0u; k < sources; ++k) {
    vec4 v;
    uint c = moved_cell(t, k, lane, r, cell, v);
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
    if (gi1.side.x > 0u) schedule_side_writes(g, t, r, cell);
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
