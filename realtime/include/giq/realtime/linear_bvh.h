#pragma once
// A BVH built on the GPU every frame over leaves of consecutive triangles (shaders/
// linear_bvh.comp: Karras 2012's parallel construction over Morton-sorted leaves), for the
// particles, whose triangles fly metres between frames: a refit would keep a tree chosen for
// where they were, and a CPU build would need the CPU to know where they are. The tree is
// written into the scene's node and prim buffers in the depth-first layout of
// shaders/bvh.glsl, as the right child of a root at node 0 whose left child, at node 1, is the
// tree the CPU built over the other triangles; every traversal then sees one tree.

#include <cstdint>
#include <memory>
#include <vector>

#include "giq/realtime/bvh.h"
#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class ShaderCompiler;

class LinearBvh {
 public:
  // Room for `max_leaves` leaves of `per_leaf` triangles each; `lights`: the light tree's
  // builder (record_lights), not the scene's. With `scratch_of` (a builder of as many leaves)
  // the two share their working buffers (about 130 bytes a leaf): their builds must not
  // overlap, as one after the other in a command buffer do not (each ends with a barrier).
  LinearBvh(Context& ctx, ShaderCompiler& compiler, uint32_t max_leaves, uint32_t per_leaf, bool lights = false,
            const LinearBvh* scratch_of = nullptr);

  // Makes `nodes` and `prims` (a tree in shaders/bvh.glsl's layout, possibly empty) the
  // arrays both trees live in: a root at node 0 over that tree, moved to node 1 on (its right
  // children moved along), and room for this tree after it, where record() builds. Either
  // tree without triangles is a one-prim leaf with an empty box; the prim is triangle 0, which
  // no ray finds closer than itself.
  void place_beside(std::vector<BvhNode>& nodes, std::vector<uint32_t>& prims);

  // Builds the tree over `leaves` leaves, leaf j being triangles first_triangle + per_leaf j
  // onwards (GpuTriangle over GpuVertex), in the room place_beside() made, and sets node 0's
  // bounds to cover node 1's and the new root's. Barriers between the passes and after the
  // last; timed when given a timer, as "particle bvh keys", "particle bvh sort" and "particle
  // bvh nodes" (the last alone without leaves).
  void record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const Buffer& nodes, const Buffer& prims,
              uint32_t first_triangle, uint32_t leaves, GpuTimer* timer = nullptr) const;

  // A light tree over the particles (GIQ_LBVH_LIGHTS in shaders/linear_bvh.comp): one
  // subtree per stage of life, each stage's root at stage_roots[its material - stage_material]
  // (0xffffffff for a stage without particles; at most kLightStages stages), and each node's
  // particles' centroid and count, by node, in `clusters` (vec4). Nodes in shaders/bvh.glsl's
  // layout from node 0, a leaf's index its particle's first triangle less first_triangle.
  static constexpr uint32_t kLightStages = 256;
  struct LightTree {
    Buffer nodes;        // 2 max_leaves - 1 GpuBvhNode
    Buffer clusters;     // 2 max_leaves - 1 vec4
    Buffer stage_roots;  // kLightStages uint
  };
  LightTree make_light_tree(Context& ctx) const;
  // Builds `tree` over the same leaves as record() (vertices, triangles, first_triangle,
  // leaves), with barriers between the passes and after the last.
  void record_lights(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const LightTree& tree,
                     uint32_t first_triangle, uint32_t leaves, uint32_t stage_material) const;

 private:
  // record()'s passes over descriptors 0..3 (vertices, triangles, nodes, prims), then the
  // light tree's outputs with lights_.
  void build(VkCommandBuffer cmd, std::vector<Descriptor> d, uint32_t first_triangle, uint32_t leaves,
             uint32_t stage_material, GpuTimer* timer, const std::vector<Descriptor>& light_outputs = {}) const;

  uint32_t max_leaves_, per_leaf_;
  bool lights_;
  uint32_t node_base_ = 0, prim_base_ = 0;  // where place_beside() left room
  Pipeline passes_[7];
  struct Scratch {
    Buffer keys, leaves, inner, parents, centres, visits;
  };
  std::shared_ptr<const Scratch> scratch_;
};

}  // namespace giq::realtime
