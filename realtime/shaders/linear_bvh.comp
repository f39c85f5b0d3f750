#version 460
// A BVH built on the GPU every frame (LinearBvh) over leaves of `per_leaf` consecutive
// triangles, for geometry whose triangles fly too far for a refit: the particles. Karras 2012
// ("Maximizing Parallelism in the Construction of BVHs, Octrees, and k-d Trees", HPG): leaves
// sorted by the Morton code of their centres (bitonic sort, as Turánszki 2017 sorts particles),
// every interior node found from the sorted keys alone, bounds bottom-up with one atomic
// visit count per node. The result is then written in the depth-first
// layout of shaders/bvh.glsl (left child next, right child at `index`), so the one traversal
// every technique uses walks it unchanged: a node covering sorted leaves [first, last] after L
// left turns from the root sits at 2 first + L (the nodes before it in depth-first order are
// its ancestors and, for each right turn, the left sibling's whole subtree).
//
// One file, one pass per GIQ_LBVH_PASS (LinearBvh::record runs them in this order):
//   1 leaves: each leaf's box, the box of the centres (atomics), the prims of the leaves;
//   2 codes: the keys (Morton code, leaf), padded to a power of two;
//   3 sort: one bitonic merge step (k, j) over all keys, for j >= kLocal;
//   7 sort in shared memory: blocks of kLocal keys, every step with j < kLocal of stage k (or,
//     with k = 0, of every stage up to kLocal: each block sorted);
//   4 hierarchy: interior node i's children and range, each child's parent;
//   5 bounds: leaf to root, a node's box made by the second of its children to arrive;
//   6 flatten: every node to its depth-first place; the root above (node 0) gets the union
//     of the tree beside it (node 1) and this one.
//
// With GIQ_LBVH_LIGHTS the tree is a light tree over the particles, of its own (node 0 its
// root, no prims: a leaf's index is its leaf's first triangle less first_triangle): the keys
// put each stage of life first (its material less stage_material, in the top 8 bits, over
// 24 bits of Morton code), so that each stage's particles are exactly one subtree (a binary
// radix tree has a node for every shared prefix), whose root's place goes to
// stage_roots[stage]; and every node gets its particles' centroid and count in `clusters`.
#extension GL_GOOGLE_include_directive : require

#include "shaders/scene_shared.h"

layout(local_size_x = GIQ_LBVH_GROUP) in;  // LinearBvh's group(pass)

layout(std430, binding = 0) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = 1) readonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = 2) buffer Nodes { GpuBvhNode nodes[]; };
layout(std430, binding = 3) buffer Prims { uint prims[]; };
layout(std430, binding = 4) buffer Keys { uvec2 keys[]; };  // (Morton code, leaf), sorted by pass 3
struct LeafBox {
  vec4 lo, hi;
};
layout(std430, binding = 5) buffer Leaves { LeafBox leaves[]; };  // by leaf, unsorted
// Interior node i of Karras's layout: links x left child, y right child (kLeaf | sorted leaf
// for a leaf); range x first and y last sorted leaf; its box.
struct Inner {
  uvec4 links;
  uvec4 range;
  vec4 lo, hi;
  vec4 centre;  // xyz: the centroid of its leaves' centres (pass 5)
};
layout(std430, binding = 6) coherent buffer Inners { Inner inner[]; };
// Parents (kNone for the root): sorted leaf k's at k, interior node i's at count + i.
layout(std430, binding = 7) buffer Parents { uint parents[]; };
// The centres' box as order-preserving uint bits (pass 1): lo xyz, hi xyz.
layout(std430, binding = 8) buffer Centres { uint centre_box[6]; };
// Children of interior node i that have their box (pass 5; zeroed before it).
layout(std430, binding = 9) buffer Visits { uint visits[]; };
#ifdef GIQ_LBVH_LIGHTS
// By depth-first place: xyz the centroid of the node's leaves' centres, w their count.
layout(std430, binding = 10) writeonly buffer Clusters { vec4 clusters[]; };
layout(std430, binding = 11) writeonly buffer StageRoots { uint stage_roots[]; };  // kNone: no particle
#endif

layout(push_constant) uniform Push {
  uint first_triangle;  // of leaf 0
  uint count;           // leaves
  uint per_leaf;        // triangles per leaf
  uint node_base;       // where the tree's root goes in `nodes`
  uint prim_base;       // where leaf 0's triangles go in `prims`
  uint padded;          // keys, a power of two >= count
  uint k, j;            // the bitonic step (pass 3)
  uint stage_material;  // GIQ_LBVH_LIGHTS: the material of stage 0
} pc;

const uint kLeaf = 0x80000000u;
const uint kLocal = 2u * GIQ_LBVH_GROUP;  // keys a workgroup of pass 7 sorts
#if GIQ_LBVH_PASS == 7
shared uvec2 block[kLocal];
#endif
const uint kNone = 0xffffffffu;

uint thread_index() { return (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x; }

// Floats as uints in the same order, for atomicMin and atomicMax.
uint ordered(float f) {
  uint u = floatBitsToUint(f);
  return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}
float unordered(uint u) { return uintBitsToFloat((u & 0x80000000u) != 0u ? u & 0x7fffffffu : ~u); }

// 10 bits spread to every third bit (Karras 2012's 30-bit Morton codes).
uint spread(uint x) {
  x = (x * 0x00010001u) & 0xff0000ffu;
  x = (x * 0x00000101u) & 0x0f00f00fu;
  x = (x * 0x00000011u) & 0xc30c30c3u;
  x = (x * 0x00000005u) & 0x49249249u;
  return x;
}

// Karras's delta: the length of the common prefix of keys a and b (the leaf index breaks ties
// between equal codes), -1 outside the keys.
int delta(int a, int b) {
  if (b < 0 || b >= int(pc.count)) return -1;
  uvec2 x = keys[a] ^ keys[b];
  return x.x != 0u ? 31 - findMSB(x.x) : 32 + 31 - findMSB(x.y);
}

bool left_child(uint parent, uint child) { return inner[parent].links.x == child; }

void main() {
  uint i = thread_index();
#if GIQ_LBVH_PASS == 1
  if (i >= pc.count) return;
  vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
  for (uint t = 0u; t < pc.per_leaf; ++t) {
    uint tri = pc.first_triangle + i * pc.per_leaf + t;
    uvec4 v = triangles[tri].v;
    for (int c = 0; c < 3; ++c) {
      vec3 p = vertices[v[c]].position.xyz;
      lo = min(lo, p), hi = max(hi, p);
    }
#ifndef GIQ_LBVH_LIGHTS
    prims[pc.prim_base + i * pc.per_leaf + t] = tri;
#endif
  }
  leaves[i].lo = vec4(lo, 0.0);
  leaves[i].hi = vec4(hi, 0.0);
  vec3 c = 0.5 * (lo + hi);
  for (int a = 0; a < 3; ++a) {
    atomicMin(centre_box[a], ordered(c[a]));
    atomicMax(centre_box[3 + a], ordered(c[a]));
  }
#elif GIQ_LBVH_PASS == 2
  if (i >= pc.padded) return;
  if (i >= pc.count) {
    keys[i] = uvec2(kNone);  // after every leaf
    return;
  }
  vec3 lo = vec3(unordered(centre_box[0]), unordered(centre_box[1]), unordered(centre_box[2]));
  vec3 hi = vec3(unordered(centre_box[3]), unordered(centre_box[4]), unordered(centre_box[5]));
  vec3 c = 0.5 * (leaves[i].lo.xyz + leaves[i].hi.xyz);
  vec3 extent = hi - lo;
  vec3 q = clamp((c - lo) / max(extent, vec3(1e-30)), 0.0, 1.0) * 1023.0;
  uvec3 b = uvec3(q);
  uint code = spread(b.x) << 2 | spread(b.y) << 1 | spread(b.z);
#ifdef GIQ_LBVH_LIGHTS
  uint stage = min(triangles[pc.first_triangle + i * pc.per_leaf].v.w - pc.stage_material, 255u);
  code = stage << 24 | code >> 6;
#endif
  keys[i] = uvec2(code, i);
#elif GIQ_LBVH_PASS == 3
  // Batcher's bitonic sort, one compare-exchange per pair: the partner is i ^ j, and the
  // direction alternates with bit k of i.
  uint partner = i ^ pc.j;
  if (i >= pc.padded || partner <= i) return;
  uvec2 a = keys[i], b = keys[partner];
  bool greater = a.x != b.x ? a.x > b.x : a.y > b.y;
  bool ascending = (i & pc.k) == 0u;
  if (greater == ascending) {
    keys[i] = b;
    keys[partner] = a;
  }
#elif GIQ_LBVH_PASS == 7
  // The same compare-exchanges as pass 3, kLocal keys to a workgroup (two per invocation),
  // with a barrier between steps instead of a dispatch.
  uint base = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kLocal, t = gl_LocalInvocationID.x;
  uint n = min(pc.padded, kLocal);
  for (uint e = t; e < n; e += GIQ_LBVH_GROUP) block[e] = keys[base + e];
  uint k_first = pc.k == 0u ? 2u : pc.k, k_last = pc.k == 0u ? n : pc.k;
  for (uint k = k_first; k <= k_last; k *= 2u)
    for (uint j = min(k / 2u, kLocal / 2u); j > 0u; j /= 2u) {
      barrier();
      if (t < n / 2u) {
        uint a_index = 2u * j * (t / j) + t % j;  // the pair's lower element
        uvec2 a = block[a_index], b = block[a_index + j];
        bool greater = a.x != b.x ? a.x > b.x : a.y > b.y;
        if (greater == (((base + a_index) & k) == 0u)) {
          block[a_index] = b;
          block[a_index + j] = a;
        }
      }
    }
  barrier();
  for (uint e = t; e < n; e += GIQ_LBVH_GROUP) keys[base + e] = block[e];
#elif GIQ_LBVH_PASS == 4
  if (i + 1u >= pc.count) return;  // count - 1 interior nodes
  int n = int(i);
  // Karras 2012's construction: the direction of the node's range, its other end, then the
  // split.
  int d = delta(n, n + 1) > delta(n, n - 1) ? 1 : -1;
  int delta_min = delta(n, n - d);
  int lmax = 2;
  while (delta(n, n + lmax * d) > delta_min) lmax *= 2;
  int l = 0;
  for (int t = lmax / 2; t >= 1; t /= 2)
    if (delta(n, n + (l + t) * d) > delta_min) l += t;
  int other = n + l * d;
  int delta_node = delta(n, other);
  int s = 0;
  int t = l;
  do {
    t = (t + 1) / 2;
    if (delta(n, n + (s + t) * d) > delta_node) s += t;
  } while (t > 1);
  int split = n + s * d + min(d, 0);
  uint first = uint(min(n, other)), last = uint(max(n, other));
  uint left = first == uint(split) ? kLeaf | uint(split) : uint(split);
  uint right = last == uint(split + 1) ? kLeaf | uint(split + 1) : uint(split + 1);
  inner[i].links = uvec4(left, right, 0u, 0u);
  inner[i].range = uvec4(first, last, 0u, 0u);
  if (i == 0u) parents[pc.count] = kNone;
  parents[(left & kLeaf) != 0u ? left & ~kLeaf : pc.count + left] = i;
  parents[(right & kLeaf) != 0u ? right & ~kLeaf : pc.count + right] = i;
#elif GIQ_LBVH_PASS == 5
  if (i >= pc.count || pc.count < 2u) return;
  uint node = parents[i];
  while (node != kNone) {
    // The first child to arrive stops; the second sees both children's boxes written.
    memoryBarrierBuffer();
    if (atomicAdd(visits[node], 1u) == 0u) return;
    memoryBarrierBuffer();
    vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
    // The centroid as the children's, weighted by their leaves: a mean of means, never a sum
    // of a million coordinates.
    vec3 centre[2];
    float weight[2];
    for (int c = 0; c < 2; ++c) {
      uint child = inner[node].links[c];
      if ((child & kLeaf) != 0u) {
        LeafBox b = leaves[keys[child & ~kLeaf].y];
        lo = min(lo, b.lo.xyz), hi = max(hi, b.hi.xyz);
        centre[c] = 0.5 * (b.lo.xyz + b.hi.xyz);
        weight[c] = 1.0;
      } else {
        lo = min(lo, inner[child].lo.xyz), hi = max(hi, inner[child].hi.xyz);
        centre[c] = inner[child].centre.xyz;
        weight[c] = float(inner[child].range.y - inner[child].range.x + 1u);
      }
    }
    inner[node].lo = vec4(lo, 0.0);
    inner[node].hi = vec4(hi, 0.0);
    inner[node].centre = vec4(centre[0] + (centre[1] - centre[0]) * (weight[1] / (weight[0] + weight[1])), 0.0);
    node = parents[pc.count + node];
  }
#elif GIQ_LBVH_PASS == 6
  // Nodes 0 .. count - 2 are interior, then the leaves; no leaves: an empty leaf of one prim
  // (the first triangle again, which no ray can find closer than itself) so the layout holds.
  if (pc.count == 0u) {
#ifdef GIQ_LBVH_LIGHTS
    return;  // no stage has a root
#endif
    if (i > 0u) return;
    nodes[pc.node_base].lo = vec3(uintBitsToFloat(0x7f800000u));
    nodes[pc.node_base].hi = -vec3(uintBitsToFloat(0x7f800000u));
    nodes[pc.node_base].index = pc.prim_base;
    nodes[pc.node_base].count = 1u;
    prims[pc.prim_base] = 0u;
    nodes[0].lo = nodes[1].lo;
    nodes[0].hi = nodes[1].hi;
    return;
  }
  uint interior = pc.count - 1u;
  if (i >= interior + pc.count) return;
  bool leaf = i >= interior;
  uint id = leaf ? kLeaf | (i - interior) : i;
  uint first = leaf ? i - interior : inner[i].range.x;
  uint turns = 0u;
  for (uint child = id, parent = pc.count > 1u ? parents[leaf ? i - interior : pc.count + i] : kNone; parent != kNone;
       child = parent, parent = parents[pc.count + parent])
    turns += left_child(parent, child) ? 1u : 0u;
  uint place = pc.node_base + 2u * first + turns;
  GpuBvhNode node;
  if (leaf) {
    uint leaf_index = keys[i - interior].y;
    node.lo = leaves[leaf_index].lo.xyz;
    node.hi = leaves[leaf_index].hi.xyz;
    node.index = pc.prim_base + leaf_index * pc.per_leaf;
    node.count = pc.per_leaf;
  } else {
    // The right child covers [split + 1, last] with the same left turns as this node.
    uint right = inner[i].links.y;
    uint right_first = (right & kLeaf) != 0u ? right & ~kLeaf : inner[right].range.x;
    node.lo = inner[i].lo.xyz;
    node.hi = inner[i].hi.xyz;
    node.index = pc.node_base + 2u * right_first + turns;
    node.count = 0u;
  }
  nodes[place] = node;
#ifdef GIQ_LBVH_LIGHTS
  uint last = leaf ? first : inner[i].range.y;
  vec3 centre = leaf ? 0.5 * (node.lo + node.hi) : inner[i].centre.xyz;
  clusters[place] = vec4(centre, float(last - first + 1u));
  // The root of its stage's subtree: its leaves are of one stage, its parent's of two.
  uint parent = pc.count > 1u ? parents[leaf ? first : pc.count + i] : kNone;
  uint stage = keys[first].x >> 24;
  if (stage == keys[last].x >> 24 &&
      (parent == kNone || keys[inner[parent].range.x].x >> 24 != keys[inner[parent].range.y].x >> 24))
    stage_roots[stage] = place;
#else
  if (place == pc.node_base) {
    nodes[0].lo = min(nodes[1].lo, node.lo);
    nodes[0].hi = max(nodes[1].hi, node.hi);
  }
#endif
#endif
}
