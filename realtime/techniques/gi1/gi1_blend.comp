#version 460
// `gi1`: the new probes take their rays' radiance (Boissé et al. 2022, section
// 2.1.4). A hit's radiance is its world-cache cell's, at the finest mip level that has
// averaged enough samples (a quarter of a cell's cap), so that a new cell borrows from its
// neighbours; a miss keeps what it saw. Each cell averages the rays traced through it; a cell
// no ray went through (ray guiding skipped it) keeps its reconstruction from last frame's
// probes where it has one, else takes the mean radiance of the hemisphere, the report's
// radiance backup (Figure 7), here estimated from the rays weighted by the inverse of their
// cells' probabilities. Where the probe has a reconstruction from last frame's
// probes (gi1_reconstruct.comp), each cell blends with it by the report's shadow-preserving
// hysteresis (Algorithm 3): a value darker than the history replaces it at once, one more
// than twice as bright is mostly held back (a firefly); parameter `hysteresis` 0 lets the new
// radiance replace the history instead. The new probe then takes its tile.
//
// The side cache (section 2.1.8): where the slot won its claims (gi1_reconstruct.comp), the
// tile's carried probe, which the new probe did not reuse, goes into its entry before the new
// probe replaces it, and the new probe into the entry that matched it.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) readonly buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = 2) readonly buffer SpawnList { uint spawn_list[]; };
layout(std430, binding = 3) buffer Probes { GpuGi1Probe probes[]; };
layout(std430, binding = 4) readonly buffer Queries { GpuGi1Query queries[]; };
layout(std430, binding = 5) readonly buffer CacheCells { vec4 cache_cells[]; };
layout(std430, binding = 6) buffer Radiance { vec4 radiance[]; };
layout(std430, binding = 7) readonly buffer Guide { vec4 guide[]; };
layout(std430, binding = 8) readonly buffer RayCells { uvec2 ray_cells[]; };
layout(std430, binding = 9) readonly buffer Fresh { GpuGi1Probe fresh[]; };
layout(std430, binding = 10) readonly buffer SideWrites { GpuGi1SideWrite side_writes[]; };
layout(std430, binding = 11) readonly buffer SideState { uint side_state[]; };
layout(std430, binding = 12) writeonly buffer SideProbes { GpuGi1Probe side_probes[]; };
layout(std430, binding = 13) writeonly buffer SideRadiance { vec4 side_radiance[]; };

#include "techniques/gi1/gi1_dispatch.glsl"
#include "techniques/gi1/gi1_cache_tile.glsl"
#include "techniques/gi1/gi1_side.glsl"

shared vec4 rays[GIQ_GI1_CELLS];  // rgb radiance, w ray length
shared uint cells[GIQ_GI1_CELLS];
shared float inverse_pdf[GIQ_GI1_CELLS];  // 1 / (64 x the probability of the ray's cell)
shared vec4 traced[GIQ_GI1_CELLS];  // rgb the cell's mean, w its ray length (< 0: no ray)
shared vec4 backup;

// Algorithm 3: the weight of the history.
float hysteresis(vec3 current, vec3 previous) {
  float l1 = dot(current, vec3(1.0 / 3.0)), l2 = dot(previous, vec3(1.0 / 3.0));
  // The report's floor of 1e-4 on the denominator would make the blend depend on the
  // scene's units of radiance; this one only avoids 0 / 0.
  float a = max(l1 - l2 - min(l1, l2), 0.0) / max(max(l1, l2), 1e-30);
  a = clamp(a, 0.0, 0.95);
  return a * a;
}

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  uint lane = gl_LocalInvocationIndex, t = spawn_list[g];
  GpuGi1Query q = queries[g * GIQ_GI1_CELLS + lane];
  vec3 l = q.radiance.rgb;
  if (q.cell.x != GIQ_GI1_NONE) {
    uint first = q.cell.x * GIQ_GI1_TILE_CELLS, finest = q.cell.y;
    float enough = max(1.0, float(gi1.cache.w) / 4.0);
    for (uint level = 0u; level <= 3u; ++level) {
      vec4 v = cache_cells[first + gi1_tile_cell(finest, level)];
      if (v.w > 0.0) l = v.rgb;
      if (v.w >= enough) break;
    }
  }
  rays[lane] = vec4(l, q.radiance.w);
  GpuGi1SideWrite side = GpuGi1SideWrite(GIQ_GI1_NONE, GIQ_GI1_NONE);
  if (gi1.side.x > 0u) side = GpuGi1SideWrite(side_writes[g].evicted, side_writes[g].fresh);
  bool keep_evicted = side.evicted != GIQ_GI1_NONE && side_state[gi1_side_claim(side.evicted)] == 2u * g;
  bool keep_fresh = side.fresh != GIQ_GI1_NONE && side_state[gi1_side_claim(side.fresh)] == 2u * g + 1u;
  if (keep_evicted) {  // before the new probe replaces it
    side_radiance[side.evicted * GIQ_GI1_CELLS + lane] = radiance[t * GIQ_GI1_CELLS + lane];
    if (lane == 0u) side_probes[side.evicted] = probes[t];
  }
  uvec2 ray = ray_cells[g * GIQ_GI1_CELLS + lane];
  cells[lane] = ray.x;
  inverse_pdf[lane] = 1.0 / (float(GIQ_GI1_CELLS) * uintBitsToFloat(ray.y));
  barrier();
  vec4 sum = vec4(0.0);
  float n = 0.0;
  for (uint i = 0u; i < GIQ_GI1_CELLS; ++i)
    if (cells[i] == lane) {
      sum += rays[i];
      n += 1.0;
    }
  traced[lane] = n > 0.0 ? sum / n : vec4(0.0, 0.0, 0.0, -1.0);
  barrier();
  if (lane == 0u) {  // in ray order, so that every run sums alike
    // The mean over the cells, each ray weighted by the inverse of its cell's probability:
    // unbiased however the rays were guided (the plain mean of the traced cells would lean
    // towards the bright cells guiding favours).
    vec4 all_ = vec4(0.0);
    for (uint i = 0u; i < GIQ_GI1_CELLS; ++i) all_ += vec4(rays[i].rgb * inverse_pdf[i], rays[i].w);
    backup = all_ / float(GIQ_GI1_CELLS);
    probes[t] = fresh[g];
  }
  barrier();
  vec4 history = guide[g * GIQ_GI1_CELLS + lane];
  vec4 v;
  if (traced[lane].w >= 0.0) {
    v = traced[lane];
    if (history.w > 0.0) v.rgb = mix(v.rgb, history.rgb, gi1.params.y * hysteresis(v.rgb, history.rgb));
  } else {
    v = history.w > 0.0 ? vec4(history.rgb, backup.w) : backup;
  }
  radiance[t * GIQ_GI1_CELLS + lane] = v;
  if (keep_fresh) {
    side_radiance[side.fresh * GIQ_GI1_CELLS + lane] = v;
    if (lane == 0u) side_probes[side.fresh] = fresh[g];
  }
}
