#version 460
// `gi1`: one level of the probe mask (gi1_mask.glsl), from the probes (level 0) or from the
// level above (the first probe of each 2x2 cells, in row order).
#extension GL_GOOGLE_include_directive : require

#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) readonly buffer Probes { GpuGi1Probe probes[]; };
layout(std430, binding = 2) buffer Mask { uint probe_mask[]; };

layout(push_constant) uniform Push { uint level; } pc;

#include "techniques/gi1/gi1_mask.glsl"

void main() {
  uvec2 pos = gl_GlobalInvocationID.xy, size = gi1_mask_size(pc.level);
  if (any(greaterThanEqual(pos, size))) return;
  uint probe = GIQ_GI1_NONE;
  if (pc.level == 0u) {
    uint t = pos.x + pos.y * size.x;
    if (probes[t].info.x != GIQ_GI1_NONE) probe = t;
  } else {
    uvec2 above = gi1_mask_size(pc.level - 1u);
    uint first = gi1_mask_offset(pc.level - 1u);
    for (uint j = 0u; j < 4u && probe == GIQ_GI1_NONE; ++j) {
      uvec2 q = pos * 2u + uvec2(j & 1u, j >> 1u);
      if (all(lessThan(q, above))) probe = probe_mask[first + q.x + q.y * above.x];
    }
  }
  probe_mask[gi1_mask_offset(pc.level) + pos.x + pos.y * size.x] = probe;
}
