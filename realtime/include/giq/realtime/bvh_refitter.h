#pragma once
// The BVH's bounds refitted on the GPU from the vertices there (shaders/bvh_refit.comp), after
// the deformation pass has moved them: one dispatch per level of the tree, from the deepest
// to the root, each node taking the bounds of its triangles or of its children. The topology
// stays the one built on the CPU (SceneGpu decides when to build anew); the bounds are exact
// for the vertices the GPU renders, which the CPU's posing matches only to float rounding.

#include <cstdint>
#include <utility>
#include <vector>

#include "giq/realtime/bvh.h"
#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"

namespace giq::realtime {

class Context;
class ShaderCompiler;

// The nodes of `bvh` by level, deepest first, and each level's [first, first + count) in that
// list: an interior node's children always lie in the level before it.
std::vector<uint32_t> refit_order(const Bvh& bvh, std::vector<std::pair<uint32_t, uint32_t>>& levels);

class BvhRefitter {
 public:
  BvhRefitter(Context& ctx, ShaderCompiler& compiler);
  // The tree whose bounds record() refits (after each build). With `offset` 1 the tree sits at
  // nodes 1 on, its interior nodes' right children moved along, under a root at node 0 whose
  // other child is another tree (SceneGpu's particles'): that root is refitted last.
  void set_tree(const Bvh& bvh, uint32_t offset = 0);
  // Refits `nodes` (GpuBvhNode) over `vertices` (GpuVertex), `triangles` (GpuTriangle) and
  // `prims`, with a barrier after each level.
  void record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const Buffer& nodes, const Buffer& prims) const;

 private:
  Context* ctx_;
  Pipeline pipeline_;
  Buffer order_;
  std::vector<std::pair<uint32_t, uint32_t>> levels_;
};

}  // namespace giq::realtime
