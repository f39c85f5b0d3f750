// Ray tracing in compute: stack-based traversal of the flattened BVH (src/bvh.cpp) with the
// watertight ray/triangle test of Woop, Benthin and Wald 2013 ("Watertight Ray/Triangle
// Intersection", JCGT 2(1)). Needs scene.glsl. Works on every Vulkan device (no ray queries).
// With GIQ_ALPHA_MASK, hits on the cut-out parts of alpha-masked materials are skipped.
#ifndef GIQ_BVH_GLSL
#define GIQ_BVH_GLSL

#include "scene.glsl"
#include "textures.glsl"

#define GIQ_BVH_STACK 64  // Bvh::kMaxDepth

struct RayHit {
  uint triangle;  // global triangle index; 0xffffffff = miss
  float t;
  float u, v;     // barycentric weights of the second and third vertex
};

// The sheared ray of the watertight test, computed once per ray (paper, Figure 2).
struct ShearedRay {
  vec3 org;
  ivec3 k;  // kx, ky, kz
  vec3 s;   // Sx, Sy, Sz
};

ShearedRay make_sheared(vec3 org, vec3 dir) {
  vec3 ad = abs(dir);
  int kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
  if (dir[kz] < 0.0) { int tmp = kx; kx = ky; ky = tmp; }  // keep the winding
  ShearedRay r;
  r.org = org;
  r.k = ivec3(kx, ky, kz);
  r.s = vec3(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
  return r;
}

// Hit in (0, tmax)? Writes t and the barycentrics. Edges and vertices count as inside, so no
// ray passes between two triangles sharing an edge.
bool intersect_watertight(ShearedRay r, vec3 a, vec3 b, vec3 c, float tmax, out float t, out float u, out float v) {
  vec3 A = a - r.org, B = b - r.org, C = c - r.org;
  float ax = A[r.k.x] - r.s.x * A[r.k.z], ay = A[r.k.y] - r.s.y * A[r.k.z];
  float bx = B[r.k.x] - r.s.x * B[r.k.z], by = B[r.k.y] - r.s.y * B[r.k.z];
  float cx = C[r.k.x] - r.s.x * C[r.k.z], cy = C[r.k.y] - r.s.y * C[r.k.z];
  // precise: the edge functions must not be fused or reordered, or the test loses its
  // watertightness (the paper's argument needs each product rounded on its own).
  precise float U = cx * by - cy * bx;
  precise float V = ax * cy - ay * cx;
  precise float W = bx * ay - by * ax;
  t = 0.0; u = 0.0; v = 0.0;
  if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
  float det = U + V + W;
  if (det == 0.0) return false;
  float T = U * (r.s.z * A[r.k.z]) + V * (r.s.z * B[r.k.z]) + W * (r.s.z * C[r.k.z]);
  if (det > 0.0 ? (T <= 0.0 || T >= tmax * det) : (T >= 0.0 || T <= tmax * det)) return false;
  float inv = 1.0 / det;
  t = T * inv;
  u = V * inv;
  v = W * inv;
  return true;
}

// Slab test; the far distance is widened by 1 + 2 gamma(3) (Ize 2013, "Robust BVH Ray
// Traversal") so a box never rejects a hit that the watertight test would accept.
bool hit_box(vec3 lo, vec3 hi, vec3 org, vec3 inv_dir, float tmax, out float tnear) {
  vec3 t0 = (lo - org) * inv_dir, t1 = (hi - org) * inv_dir;
  vec3 tmin = min(t0, t1), tmx = max(t0, t1);
  tnear = max(max(tmin.x, tmin.y), max(tmin.z, 0.0));
  float tfar = min(min(tmx.x, tmx.y), min(tmx.z, tmax)) * 1.0000004;
  return tnear <= tfar;
}

vec3 safe_inverse(vec3 d) {
  // 1/0 is not guaranteed to be infinity in SPIR-V; a tiny signed value gives the same slabs.
  const float tiny = 1e-30;
  vec3 s = vec3(d.x < 0.0 ? -1.0 : 1.0, d.y < 0.0 ? -1.0 : 1.0, d.z < 0.0 ? -1.0 : 1.0);
  return 1.0 / mix(d, s * tiny, lessThan(abs(d), vec3(tiny)));
}

// any_hit: stop at the first hit (shadow rays); else the closest hit in (0, tmax). camera:
// a camera ray, which passes the backs of single-sided surfaces (glTF 2.0, 3.9.5: back-face
// culling; the reference's EmbreeScene::intersect_camera). skip: triangles [x, x + y) are not
// there (an area light's own mesh, seen from its representative point: passes/rsm_rays.comp).
RayHit trace_ray(vec3 org, vec3 dir, float tmax, bool any_hit, bool camera, uvec2 skip) {
  RayHit hit;
  hit.triangle = 0xffffffffu;
  hit.t = tmax;
  hit.u = 0.0;
  hit.v = 0.0;
  if (bvh_nodes.length() == 0) return hit;
  ShearedRay sr = make_sheared(org, dir);
  vec3 inv_dir = safe_inverse(dir);
  uint stack[GIQ_BVH_STACK];
  int sp = 0;
  uint node = 0u;
  float tn;
  if (!hit_box(bvh_nodes[0].lo, bvh_nodes[0].hi, org, inv_dir, hit.t, tn)) return hit;
  while (true) {
    GpuBvhNode n = bvh_nodes[node];
    if (n.count > 0u) {
      for (uint i = 0u; i < n.count; ++i) {
        uint tri = bvh_prims[n.index + i];
        if (tri - skip.x < skip.y) continue;
        vec3 a, b, c;
        triangle_vertices(tri, a, b, c);
        float t, u, v;
        if (intersect_watertight(sr, a, b, c, hit.t, t, u, v)) {
          if (camera && scene_materials[scene_triangles[tri].v.w].params.w == 0.0 && dot(cross(b - a, c - a), dir) > 0.0) continue;
#ifdef GIQ_ALPHA_MASK
          // A cut-out texel is no surface, for closest and any hits alike (the reference's
          // Embree intersect and occluded filters).
          if (alpha_cut(tri, u, v, alpha_ray_number(org, dir, tri))) continue;
#endif
          hit.triangle = tri;
          hit.t = t;
          hit.u = u;
          hit.v = v;
          if (any_hit) return hit;
        }
      }
    } else {
      // Visit the nearer child first; push the other.
      uint left = node + 1u, right = n.index;
      float tl, tr;
      bool hl = hit_box(bvh_nodes[left].lo, bvh_nodes[left].hi, org, inv_dir, hit.t, tl);
      bool hr = hit_box(bvh_nodes[right].lo, bvh_nodes[right].hi, org, inv_dir, hit.t, tr);
      if (hl && hr) {
        if (tr < tl) { uint tmp = left; left = right; right = tmp; }
        stack[sp++] = right;
        node = left;
        continue;
      }
      if (hl) { node = left; continue; }
      if (hr) { node = right; continue; }
    }
    if (sp == 0) break;
    node = stack[--sp];
  }
  return hit;
}

RayHit trace_ray(vec3 org, vec3 dir, float tmax, bool any_hit, bool camera) {
  return trace_ray(org, dir, tmax, any_hit, camera, uvec2(0u));
}

RayHit trace_ray(vec3 org, vec3 dir, float tmax, bool any_hit) { return trace_ray(org, dir, tmax, any_hit, false); }

bool occluded(vec3 org, vec3 dir, float tmax) { return trace_ray(org, dir, tmax, true).triangle != 0xffffffffu; }

#endif
