#version 460
// One level of a BVH refit on the GPU (BvhRefitter): each node of the level gets the bounds
// of its triangles (a leaf) or of its two children (an interior node, whose children are one
// level deeper and were refitted by the previous dispatch). The same bounds as refit_bvh
// (realtime/src/bvh.cpp) computes on the CPU from the same vertices: min and max round nothing.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene_shared.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = 1) readonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = 2) buffer Nodes { GpuBvhNode nodes[]; };
layout(std430, binding = 3) readonly buffer Prims { uint prims[]; };
layout(std430, binding = 4) readonly buffer Order { uint order[]; };  // node indices, deepest level first

layout(push_constant) uniform Push {
  uint first;  // the level's first entry of `order`
  uint count;
} pc;

void main() {
  uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
  if (i >= pc.count) return;
  uint n = order[pc.first + i];
  GpuBvhNode node = nodes[n];
  vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
  if (node.count > 0u) {
    for (uint k = node.index; k < node.index + node.count; ++k) {
      uvec4 t = triangles[prims[k]].v;
      for (int c = 0; c < 3; ++c) {
        vec3 p = vertices[t[c]].position.xyz;
        lo = min(lo, p), hi = max(hi, p);
      }
    }
  } else {
    GpuBvhNode l = nodes[n + 1u], r = nodes[node.index];
    lo = min(l.lo, r.lo), hi = max(l.hi, r.hi);
  }
  nodes[n].lo = lo;
  nodes[n].hi = hi;
}
