#pragma once
// A BVH built on the GPU every frame over leaves of consecutive triangles (shaders/
// linear_bvh.comp: Karras 2012's parallel construction over Morton-sorted leaves), for the
// particles, whose triangles fly metres between frames: a refit would keep a tree chosen for
// where they were, and a CPU build would need the CPU to know where they are. The tree is
// written into the scene's node and prim buffers in the depth-first layout of
// shaders/bvh.glsl, as the right child of a root at node 0 whose left child, at node 1, is the
// tree the CPU built over the other triangles; every traversal then sees one tree.

#include <cstdint>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class ShaderCompiler;

class LinearBvh {
 public:
  // Room for `max_leaves` leaves of `per_leaf` triangles each.
  LinearBvh(Context& ctx, ShaderCompiler& compiler, uint32_t max_leaves, uint32_t per_leaf);

  // Nodes and prims the tree takes in the scene's buffers (at least one each: with no leaf the
  // tree is an empty-boxed leaf).
  static uint32_t node_count(uint32_t max_leaves) { return max_leaves > 0 ? 2 * max_leaves - 1 : 1; }
  uint32_t node_count() const { return node_count(max_leaves_); }
  uint32_t prim_count() const { return max_leaves_ > 0 ? max_leaves_ * per_leaf_ : 1; }

  // Builds the tree over `leaves` leaves, leaf j being triangles first_triangle + per_leaf j
  // onwards (GpuTriangle over GpuVertex), at nodes [node_base, node_base + 2 leaves - 1) and
  // prims [prim_base, ...), and sets node 0's bounds to cover node 1's and the new root's.
  // Barriers between the passes and after the last; timed when given a timer, as "particle bvh
  // keys", "particle bvh sort" and "particle bvh nodes" (the last alone without leaves).
  void record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const Buffer& nodes, const Buffer& prims,
              uint32_t first_triangle, uint32_t leaves, uint32_t node_base, uint32_t prim_base, GpuTimer* timer = nullptr) const;

 private:
  Context* ctx_;
  uint32_t max_leaves_, per_leaf_;
  Pipeline passes_[7];
  Buffer keys_, leaves_, inner_, parents_, centres_, visits_;
};

}  // namespace giq::realtime
