#version 460
// `gi1`: the reservoir grid's writes (Boissé et al. 2022, section 2.3.1). Each probe ray whose
// hit sampled the lights left its reservoir in the stash and claimed its cell's slot with its
// index (gi1_light_sample.glsl); the lowest index of a slot stores, so the grid is the same on
// every run, and a slot no hit claimed keeps what it held. After the trace, which reads the
// grid as the last frame left it.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Counters { GpuGi1Counters counters; };
layout(std430, binding = 1) readonly buffer ReservoirStash { GpuGi1Reservoir reservoir_stash[]; };
layout(std430, binding = 2) readonly buffer ReservoirClaims { uint reservoir_claims[]; };
layout(std430, binding = 3) writeonly buffer Reservoirs { GpuGi1Reservoir reservoirs[]; };

#include "techniques/gi1/gi1_dispatch.glsl"

void main() {
  uint g = gi1_group();
  if (g >= counters.probe_groups.w) return;
  uint ray = g * GIQ_GI1_CELLS + gl_LocalInvocationIndex;
  GpuGi1Reservoir r = reservoir_stash[ray];
  uint slot = floatBitsToUint(r.point.w);
  if (reservoir_claims[slot] == ray) reservoirs[slot] = r;
}
