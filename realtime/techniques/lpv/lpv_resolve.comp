#version 460
// LPV: the fixed-point injection sums (lpv_inject.comp) as float SH, the first volume to
// propagate and the start of the accumulated volume.
#extension GL_GOOGLE_include_directive : require

#include "techniques/lpv/lpv_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Inject { int inject[]; };
layout(std430, binding = 1) writeonly buffer Current { vec4 current[]; };
layout(std430, binding = 2) writeonly buffer Accumulated { vec4 accumulated[]; };

layout(push_constant) uniform Push { LpvGrid grid; };

void main() {
  uint i = gl_GlobalInvocationID.x;  // one SH vector (cell x 3 + channel)
  uint n = grid.resolution * grid.resolution * grid.resolution * 3u;
  if (i >= n) return;
  float inv = grid.injection_scale > 0.0 ? 1.0 / grid.injection_scale : 0.0;
  vec4 v = vec4(inject[4u * i], inject[4u * i + 1u], inject[4u * i + 2u], inject[4u * i + 3u]) * inv;
  current[i] = v;
  accumulated[i] = v;
}
