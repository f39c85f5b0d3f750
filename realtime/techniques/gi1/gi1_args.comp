#version 460
// `gi1`: the world-cache update's indirect dispatch, a work group per tile touched this frame.
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 1) in;

layout(std430, binding = 0) buffer Counters { GpuGi1Counters counters; };

#include "techniques/gi1/gi1_dispatch.glsl"

void main() { counters.tile_groups = gi1_groups(counters.tile_groups.w); }
