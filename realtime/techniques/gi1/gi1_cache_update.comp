#version 460
// `gi1`: the probe rays' samples summed into their world-cache cells. Floats added by
// atomics in whatever order the GPU runs them would give different bits from run to run, and
// a fixed scale for integer sums (Capsaicin's 1/1000) cannot hold light that spans 14 orders
// of magnitude; each sample is therefore added as an integer in units of 1/65535 of the
// largest sample its cell received this frame (gi1_trace.comp kept it): exact, in any order,
// at any brightness, to 1/65535 of that largest sample. At most GIQ_GI1_MAX_CELL_SAMPLES
// samples a cell and frame are summed, so the sums cannot overflow.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = 1) readonly buffer Queries { GpuGi1Query queries[]; };
layout(std430, binding = 2) readonly buffer CacheMax { uint cache_max[]; };
// Per finest cell: the fixed-point sums of this frame's samples (rgb) and their count (w).
layout(std430, binding = 3) buffer CacheSums { uvec4 cache_sums[]; };

#include "techniques/gi1/gi1_dispatch.glsl"

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  GpuGi1Query q = queries[g * GIQ_GI1_CELLS + gl_LocalInvocationIndex];
  if (q.cell.x == GIQ_GI1_NONE) return;
  uint cell = q.cell.x * GIQ_GI1_CELLS + q.cell.y;
  if (atomicAdd(cache_sums[cell].w, 1u) >= GIQ_GI1_MAX_CELL_SAMPLES) return;
  float largest = uintBitsToFloat(cache_max[cell]);
  if (!(largest > 0.0)) return;
  uvec3 v = uvec3(round(clamp(q.radiance.rgb / largest, 0.0, 1.0) * GIQ_GI1_QUANTUM));
  atomicAdd(cache_sums[cell].x, v.x);
  atomicAdd(cache_sums[cell].y, v.y);
  atomicAdd(cache_sums[cell].z, v.z);
}
