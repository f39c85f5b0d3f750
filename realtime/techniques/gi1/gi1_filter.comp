#version 460
// `gi1`: the new probes filtered across their neighbours (Boissé et al. 2022, section
// 2.1.6, Algorithm 5), a separable 7x7 sparse blur: along one axis per pass, each cell takes
// the same direction's radiance from the probes found 1 to 3 tiles away on either side (the
// mask's search, gi1_mask.glsl), skipping a probe farther than a cell size from this probe's
// plane, one whose hemisphere does not hold the direction, and one whose hit in that
// direction, seen from this probe, lies more than pi/50 off it (Wright 2021's angle error,
// which keeps small-scale occlusion); the rest weigh by how close their depths are. The
// neighbour's cell is the one its own map has for the direction (the report indexes the same
// cell, which is the same direction only where the normals agree). The first pass reads the
// probes and writes the scratch; the second reads the scratch for this frame's probes and the
// probes for the others (carried probes are not filtered again), writes the probes and
// projects them onto spherical harmonics (the exact integrals of each basis function over
// each cell, gi1_projection.h), for the per-pixel interpolation.
#extension GL_GOOGLE_include_directive : require

#include "shaders/sampling.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) readonly buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = 2) readonly buffer SpawnList { uint spawn_list[]; };
layout(std430, binding = 3) readonly buffer Probes { GpuGi1Probe probes[]; };
layout(std430, binding = 4) readonly buffer Mask { uint probe_mask[]; };
layout(std430, binding = 5) buffer Radiance { vec4 radiance[]; };
layout(std430, binding = 6) buffer Scratch { vec4 scratch[]; };
layout(std430, binding = 7) writeonly buffer Harmonics { vec4 harmonics[]; };
// The integral of each basis function over each cell: [GIQ_GI1_SH][GIQ_GI1_CELLS].
layout(std430, binding = 8) readonly buffer Projection { float projection[]; };

layout(push_constant) uniform Push {
  ivec2 direction;  // (1, 0) or (0, 1)
  uint second;      // 0: probes -> scratch; 1: scratch -> probes, and the projection
  uint radius;      // tiles on either side (3: 7x7; 0: no filter)
} pc;

#include "techniques/gi1/gi1_dispatch.glsl"
#include "techniques/gi1/gi1_probe.glsl"
#include "techniques/gi1/gi1_mask.glsl"

shared vec3 parts[GIQ_GI1_SH][GIQ_GI1_CELLS];

// Cell c of probe t as this pass reads it.
vec4 cell_value(uint t, uint c) {
  bool filtered = pc.second != 0u && (probes[t].info.y & GIQ_GI1_SPAWNED) != 0u;
  return filtered ? scratch[t * GIQ_GI1_CELLS + c] : radiance[t * GIQ_GI1_CELLS + c];
}

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  uint lane = gl_LocalInvocationIndex, t = spawn_list[g];
  GpuGi1Probe p = probes[t];
  vec3 dir = to_world(gi1_cell_direction(lane, vec2(0.5)), p.normal.xyz);
  vec4 own = cell_value(t, lane);
  vec4 sum = own;
  float weight = 1.0, hit = own.w;
  ivec2 tile = ivec2(t % gi1.size.z, t / gi1.size.z);
  for (uint i = 0u; i < 2u * pc.radius; ++i) {
    int step = (int((i & 1u) << 1u) - 1) * int((i >> 1u) + 1u);
    uint u = gi1_find_probe(tile, step * pc.direction);
    if (u == GIQ_GI1_NONE || u == t) continue;
    GpuGi1Probe q = probes[u];
    if (abs(dot(q.position.xyz - p.position.xyz, p.normal.xyz)) > p.normal.w || dot(dir, q.normal.xyz) < 0.0) continue;
    vec4 v = cell_value(u, gi1_direction_cell(to_local(dir, q.normal.xyz)));
    float reach = min(v.w, hit);
    vec3 to_hit = q.position.xyz + dir * reach - p.position.xyz;
    if (dot(dir, to_hit) < cos(PI / 50.0) * length(to_hit)) continue;
    float w = max(0.0, 1.0 - abs(q.position.w - p.position.w) / (2.0 * p.normal.w));
    sum += w * vec4(v.rgb, reach);
    weight += w;
    hit = sum.w / weight;
  }
  vec4 result = sum / weight;
  uint slot = t * GIQ_GI1_CELLS + lane;
  if (pc.second == 0u) {
    scratch[slot] = result;
    return;
  }
  radiance[slot] = result;
  for (uint k = 0u; k < GIQ_GI1_SH; ++k) parts[k][lane] = result.rgb * projection[k * GIQ_GI1_CELLS + lane];
  barrier();
  if (lane < GIQ_GI1_SH) {
    vec3 total = vec3(0.0);
    for (uint c = 0u; c < GIQ_GI1_CELLS; ++c) total += parts[lane][c];
    harmonics[t * GIQ_GI1_SH + lane] = vec4(total, 0.0);
  }
}
