#version 460
// `gi1`: the side cache's lookup structure (Boissé et al. 2022, section 2.1.8). The side cache
// keeps probes the screen cache evicted, with their positions and normals, for any number of
// frames; each frame every entry is projected into this frame's view and the tile it lands
// in lists it, as tiled deferred shading lists lights (Andersson 2011). A tile keeps one
// entry, the most recently used (lowest rank in the LRU order): an atomic minimum, the same
// on every run, where the report's list of entries per tile is filled in timing order.
#extension GL_GOOGLE_include_directive : require

#include "shaders/camera.glsl"
#include "techniques/gi1/gi1_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Frame { GpuGi1Frame gi1; };
layout(std430, binding = 1) readonly buffer SideProbes { GpuGi1Probe side_probes[]; };
layout(std430, binding = 2) readonly buffer SideRank { uint side_rank[]; };
layout(std430, binding = 3) buffer SideState { uint side_state[]; };

#include "techniques/gi1/gi1_side.glsl"

void main() {
  uint e = gl_GlobalInvocationID.x;
  if (e >= gi1.side.x || side_probes[e].info.x == GIQ_GI1_NONE) return;
  vec3 q = camera_project(gi1.camera, side_probes[e].position.xyz, vec2(gi1.size.xy));
  if (!(q.z > 0.0) || any(lessThan(q.xy, vec2(0.0))) || any(greaterThanEqual(q.xy, vec2(gi1.size.xy)))) return;
  uvec2 tile = uvec2(q.xy) / GIQ_GI1_PROBE;
  atomicMin(side_state[gi1_side_tile(tile.x + tile.y * gi1.size.z)], side_rank[e]);
}
