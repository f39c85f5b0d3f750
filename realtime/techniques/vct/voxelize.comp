#version 460
// Voxelisation of the scene's triangles into the base level (Afanasev 2021 ch. IV, "voxelization";
// Turánszki 2017, "Voxel-based Global Illumination", part 1). Instead of the geometry-shader
// rasteriser of the sources, a compute pass walks each triangle's footprint on its dominant
// axis plane (Turánszki 2017's axis choice) and keeps every voxel that the triangle overlaps by the
// separating-axis test of Akenine-Moeller 2001 ("Fast 3D Triangle-Box Overlap Testing"):
// coverage is exactly conservative (touching counts), needs no hardware conservative
// rasterisation, and runs the same on lavapipe and on NVIDIA.
// A voxel keeps the smallest index of the triangles overlapping it (imageAtomicMin): the
// result does not depend on the order in which triangles are processed. Alpha-masked and BLEND
// triangles (glTF 3.9.4) are tested at the point of their plane over the voxel's column
// centre (clamped into the triangle): a cut-out there leaves the voxel to other triangles, a
// BLEND surface fills it with probability alpha (a hash of the voxel and the triangle), as
// the G-buffer and the shadow maps cut them out.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene.glsl"
#include "shaders/textures.glsl"
#include "techniques/vct/vct_shared.h"

layout(local_size_x = 64) in;
layout(binding = GIQ_SCENE_BINDING_COUNT + 0, r32ui) uniform uimage3D voxel_ids;
layout(push_constant) uniform Push { VctVoxelizePush pc; };

// Akenine-Moeller's axis tests for one edge e (f = |e|) against the box [-h, h]^3 centred at
// the origin, the triangle's vertices v0, v1, v2 relative to the box centre.
bool separated(vec3 axis, vec3 v0, vec3 v1, vec3 v2, vec3 h) {
  float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
  float r = dot(h, abs(axis));
  return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

bool triangle_box_overlap(vec3 c, vec3 h, vec3 a, vec3 b, vec3 d, vec3 n) {
  vec3 v0 = a - c, v1 = b - c, v2 = d - c;
  // The box's face normals: the triangle's bounds against the box's.
  if (any(greaterThan(min(v0, min(v1, v2)), h)) || any(lessThan(max(v0, max(v1, v2)), -h))) return false;
  // The triangle's plane.
  if (abs(dot(n, v0)) > dot(h, abs(n))) return false;
  // The nine cross products of the box axes with the triangle's edges.
  vec3 e[3] = vec3[3](v1 - v0, v2 - v1, v0 - v2);
  for (int i = 0; i < 3; ++i) {
    if (separated(vec3(0.0, -e[i].z, e[i].y), v0, v1, v2, h)) return false;
    if (separated(vec3(e[i].z, 0.0, -e[i].x), v0, v1, v2, h)) return false;
    if (separated(vec3(-e[i].y, e[i].x, 0.0), v0, v1, v2, h)) return false;
  }
  return true;
}

void main() {
  uint tri = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
  if (tri >= pc.triangle_count) return;
  int res = int(pc.grid.resolution);
  vec3 a, b, c;
  triangle_vertices(tri, a, b, c);
  // Voxel units: voxel (i, j, k) is the box [i, i+1] x [j, j+1] x [k, k+1].
  float inv = 1.0 / pc.grid.origin.w;
  a = (a - pc.grid.origin.xyz) * inv;
  b = (b - pc.grid.origin.xyz) * inv;
  c = (c - pc.grid.origin.xyz) * inv;
  vec3 n = cross(b - a, c - a);
  vec3 an = abs(n);
  if (!(max(an.x, max(an.y, an.z)) > 0.0)) return;  // degenerate: no area, nothing to light
  int w = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  int u = (w + 1) % 3, v = (w + 2) % 3;
  ivec3 lo = clamp(ivec3(floor(min(a, min(b, c)))), ivec3(0), ivec3(res - 1));
  ivec3 hi = clamp(ivec3(floor(max(a, max(b, c)))), ivec3(0), ivec3(res - 1));
  if (any(lessThan(ivec3(floor(max(a, max(b, c)))), ivec3(0))) ||
      any(greaterThanEqual(ivec3(floor(min(a, min(b, c)))), ivec3(res))))
    return;  // outside the cube
  int nu = hi[u] - lo[u] + 1, nv = hi[v] - lo[v] + 1;
  float d = dot(n, a);
  uint stride = gl_WorkGroupSize.x * gl_NumWorkGroups.z;
  for (uint col = gl_LocalInvocationID.x + gl_WorkGroupID.z * gl_WorkGroupSize.x; col < uint(nu * nv); col += stride) {
    int cu = lo[u] + int(col % uint(nu)), cv = lo[v] + int(col / uint(nu));
    // The plane's extent along w over the column's square: at most ~3 voxels, since w is
    // the dominant axis of the normal.
    float w00 = (d - n[u] * float(cu) - n[v] * float(cv)) / n[w];
    float du = -n[u] / n[w], dv = -n[v] / n[w];
    float wmin = w00 + min(du, 0.0) + min(dv, 0.0), wmax = w00 + max(du, 0.0) + max(dv, 0.0);
    int w0 = max(lo[w], int(floor(wmin)) - 1), w1 = min(hi[w], int(floor(wmax)) + 1);
#ifdef GIQ_ALPHA_MASK
    // The plane's point over the column's centre, its barycentrics clamped into the triangle.
    vec3 q;
    q[u] = float(cu) + 0.5;
    q[v] = float(cv) + 0.5;
    q[w] = w00 + 0.5 * du + 0.5 * dv;
    float nn = dot(n, n);
    float b1 = clamp(dot(cross(q - a, c - a), n) / nn, 0.0, 1.0), b2 = clamp(dot(cross(b - a, q - a), n) / nn, 0.0, 1.0);
    if (b1 + b2 > 1.0) {
      float k = 1.0 / (b1 + b2);
      b1 *= k;
      b2 *= k;
    }
#endif
    for (int cw = w0; cw <= w1; ++cw) {
      ivec3 cell;
      cell[u] = cu;
      cell[v] = cv;
      cell[w] = cw;
      if (!triangle_box_overlap(vec3(cell) + 0.5, vec3(0.5), a, b, c, n)) continue;
#ifdef GIQ_ALPHA_MASK
      uvec3 uc = uvec3(cell);
      if (alpha_cut(tri, b1, b2, alpha_hash_number(uc.x ^ pcg_hash(uc.y ^ pcg_hash(uc.z ^ pcg_hash(tri)))))) continue;
#endif
      imageAtomicMin(voxel_ids, cell, tri);
    }
  }
}
