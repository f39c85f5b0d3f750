#version 460
// A batch of rays against the scene's BVH: one invocation per ray. Used by tests and tools
// to check the traversal against other ray tracers.
#extension GL_GOOGLE_include_directive : require

#include "bvh.glsl"

layout(local_size_x = 64) in;

struct QueryRay { vec4 org_tmax; vec4 dir_any; };  // w of dir: 1 = any-hit query
struct QueryHit { uint triangle; float t; float u; float v; };

layout(std430, binding = GIQ_SCENE_BINDING_COUNT) readonly buffer Rays { QueryRay rays[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) writeonly buffer Hits { QueryHit hits[]; };
layout(push_constant) uniform Push { uint count; } pc;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  QueryRay r = rays[i];
  RayHit h = trace_ray(r.org_tmax.xyz, r.dir_any.xyz, r.org_tmax.w, r.dir_any.w != 0.0);
  hits[i] = QueryHit(h.triangle, h.t, h.u, h.v);
}
