#include "giq/realtime/linear_bvh.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <stdexcept>
#include <string>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"

namespace giq::realtime {

namespace {

// shaders/linear_bvh.comp's bindings: the scene's tree's, and a light tree's two more.
constexpr uint32_t kBindings = 10, kLightBindings = 12;

// shaders/linear_bvh.comp's push constants.
struct Push {
  uint32_t first_triangle, count, per_leaf, node_base, prim_base, padded, k, j, stage_material;
};

// Invocations per workgroup. Pass 5 (bounds, leaf to root) runs one per workgroup: where a
// workgroup's invocations run as the lanes of one SIMD loop (lavapipe), two lanes reaching a
// node in different iterations were both seen to get 0 back from its visit count, and the
// node's box was never made. Across workgroups the atomics hold on every device.
// Pass 7 sorts blocks of twice its group's keys in shared memory.
constexpr uint32_t group(int pass) { return pass == 5 ? 1 : pass == 7 ? 512 : 64; }
constexpr uint32_t kLocal = 2 * group(7);  // the shader's kLocal
constexpr int kPasses = 7;

// std430 sizes of the shader's LeafBox and Inner.
constexpr uint64_t kLeafBoxBytes = 32, kInnerBytes = 80;

}  // namespace

LinearBvh::LinearBvh(Context& ctx, ShaderCompiler& compiler, uint32_t max_leaves, uint32_t per_leaf, bool lights,
                     const LinearBvh* scratch_of)
    : max_leaves_(max_leaves), per_leaf_(per_leaf), lights_(lights) {
  const std::vector<VkDescriptorType> bindings(lights ? kLightBindings : kBindings, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  for (int p = 0; p < kPasses; ++p) {
    std::vector<ShaderDefine> defines = {{"GIQ_LBVH_PASS", std::to_string(p + 1)}, {"GIQ_LBVH_GROUP", std::to_string(group(p + 1))}};
    if (lights) defines.push_back({"GIQ_LBVH_LIGHTS", "1"});
    passes_[p] = Pipeline::compute(ctx, compiler.compile("shaders/linear_bvh.comp", defines), bindings, sizeof(Push));
  }
  if (scratch_of) {
    if (scratch_of->max_leaves_ < max_leaves) throw std::logic_error("LinearBvh: shared scratch for fewer leaves");
    scratch_ = scratch_of->scratch_;
    return;
  }
  const uint64_t n = std::max<uint32_t>(max_leaves, 1);
  constexpr VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  scratch_ = std::make_shared<const Scratch>(Scratch{
      Buffer(ctx, std::bit_ceil(n) * 2 * sizeof(uint32_t), usage), Buffer(ctx, n * kLeafBoxBytes, usage),
      Buffer(ctx, n * kInnerBytes, usage), Buffer(ctx, 2 * n * sizeof(uint32_t), usage),
      Buffer(ctx, 6 * sizeof(uint32_t), usage), Buffer(ctx, n * sizeof(uint32_t), usage)});
}

LinearBvh::LightTree LinearBvh::make_light_tree(Context& ctx) const {
  const uint64_t nodes = std::max<uint64_t>(2 * uint64_t(max_leaves_), 2) - 1;
  constexpr VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  return {Buffer(ctx, nodes * sizeof(BvhNode), usage), Buffer(ctx, nodes * 4 * sizeof(float), usage),
          Buffer(ctx, kLightStages * sizeof(uint32_t), usage)};
}

void LinearBvh::place_beside(std::vector<BvhNode>& nodes, std::vector<uint32_t>& prims) {
  const glm::vec3 inf(std::numeric_limits<float>::infinity());
  const uint32_t room_nodes = max_leaves_ > 0 ? 2 * max_leaves_ - 1 : 1, room_prims = max_leaves_ > 0 ? max_leaves_ * per_leaf_ : 1;
  const uint32_t spare_prim = uint32_t(prims.size()) + room_prims;
  const BvhNode empty{inf, spare_prim, -inf, 1};
  std::vector<BvhNode> other = nodes.empty() ? std::vector<BvhNode>{empty} : std::move(nodes);
  for (BvhNode& n : other)
    if (n.count == 0) ++n.index;
  node_base_ = 1 + uint32_t(other.size());
  prim_base_ = uint32_t(prims.size());
  nodes.assign(1, BvhNode{other[0].lo, node_base_, other[0].hi, 0});
  nodes.insert(nodes.end(), other.begin(), other.end());
  nodes.resize(node_base_ + room_nodes, empty);
  prims.resize(spare_prim + 1, 0u);
}

void LinearBvh::record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const Buffer& nodes,
                       const Buffer& prims, uint32_t first_triangle, uint32_t leaves, GpuTimer* timer) const {
  build(cmd, {Descriptor::storage(vertices), Descriptor::storage(triangles), Descriptor::storage(nodes), Descriptor::storage(prims)},
        first_triangle, leaves, 0, timer);
}

void LinearBvh::record_lights(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const LightTree& tree,
                              uint32_t first_triangle, uint32_t leaves, uint32_t stage_material) const {
  vkCmdFillBuffer(cmd, tree.stage_roots.handle(), 0, VK_WHOLE_SIZE, 0xffffffffu);
  full_barrier(cmd);
  // No prims: the shader writes none, so the roots' buffer stands in at binding 3.
  build(cmd, {Descriptor::storage(vertices), Descriptor::storage(triangles), Descriptor::storage(tree.nodes),
              Descriptor::storage(tree.stage_roots)},
        first_triangle, leaves, stage_material, nullptr, {Descriptor::storage(tree.clusters), Descriptor::storage(tree.stage_roots)});
}

void LinearBvh::build(VkCommandBuffer cmd, std::vector<Descriptor> d, uint32_t first_triangle, uint32_t leaves,
                      uint32_t stage_material, GpuTimer* timer, const std::vector<Descriptor>& light_outputs) const {
  leaves = std::min(leaves, max_leaves_);
  const Scratch& s = *scratch_;
  d.insert(d.end(), {Descriptor::storage(s.keys), Descriptor::storage(s.leaves), Descriptor::storage(s.inner),
                     Descriptor::storage(s.parents), Descriptor::storage(s.centres), Descriptor::storage(s.visits)});
  d.insert(d.end(), light_outputs.begin(), light_outputs.end());
  const uint32_t node_base = lights_ ? 0 : node_base_, prim_base = lights_ ? 0 : prim_base_;
  Push push{first_triangle, leaves, per_leaf_, node_base, prim_base, std::bit_ceil(std::max(leaves, 1u)), 0, 0, stage_material};
  auto run = [&](int pass, uint64_t threads) {
    passes_[pass - 1].bind(cmd);
    passes_[pass - 1].push_descriptors(cmd, d);
    passes_[pass - 1].push_constants(cmd, push);
    passes_[pass - 1].dispatch_1d(cmd, threads, group(pass));
    full_barrier(cmd);
  };
  if (leaves > 0) {
    if (timer) timer->begin(cmd, "particle bvh keys");
    // The centres' box starts empty: lo at the largest ordered value, hi at the smallest.
    vkCmdFillBuffer(cmd, s.centres.handle(), 0, 3 * sizeof(uint32_t), 0xffffffffu);
    vkCmdFillBuffer(cmd, s.centres.handle(), 3 * sizeof(uint32_t), 3 * sizeof(uint32_t), 0u);
    full_barrier(cmd);
    run(1, leaves);
    run(2, push.padded);
    // Bitonic sort: the steps over blocks that fit a workgroup in shared memory (pass 7), the
    // longer ones a dispatch each (pass 3).
    if (timer) timer->end(cmd), timer->begin(cmd, "particle bvh sort");
    const uint64_t local_threads = std::max<uint32_t>(push.padded, 2) / 2;
    run(7, local_threads);
    for (uint32_t k = 2 * kLocal; k <= push.padded; k *= 2) {
      push.k = k;
      for (uint32_t j = k / 2; j >= kLocal; j /= 2) {
        push.j = j;
        run(3, push.padded);
      }
      run(7, local_threads);
    }
    if (timer) timer->end(cmd), timer->begin(cmd, "particle bvh nodes");
    run(4, leaves - 1);
    vkCmdFillBuffer(cmd, s.visits.handle(), 0, uint64_t(leaves) * sizeof(uint32_t), 0u);
    full_barrier(cmd);
    run(5, leaves);
  } else if (timer) {
    timer->begin(cmd, "particle bvh nodes");
  }
  run(6, leaves > 0 ? 2 * uint64_t(leaves) - 1 : 1);
  if (timer) timer->end(cmd);
}

}  // namespace giq::realtime
