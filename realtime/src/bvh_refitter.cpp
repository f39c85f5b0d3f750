#include "giq/realtime/bvh_refitter.h"

#include <algorithm>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"

namespace giq::realtime {

std::vector<uint32_t> refit_order(const Bvh& bvh, std::vector<std::pair<uint32_t, uint32_t>>& levels) {
  levels.clear();
  const size_t n = bvh.nodes.size();
  if (n == 0) return {};
  // Depth-first order puts children after their parent, so one forward sweep gives depths.
  std::vector<uint32_t> depth(n, 0);
  uint32_t deepest = 0;
  for (size_t i = 0; i < n; ++i) {
    deepest = std::max(deepest, depth[i]);
    if (bvh.nodes[i].count == 0) depth[i + 1] = depth[bvh.nodes[i].index] = depth[i] + 1;
  }
  // Counting sort by depth, deepest first.
  std::vector<uint32_t> start(deepest + 2, 0);
  for (uint32_t d : depth) ++start[deepest - d + 1];
  for (size_t l = 1; l < start.size(); ++l) start[l] += start[l - 1];
  for (uint32_t l = 0; l <= deepest; ++l) levels.emplace_back(start[l], start[l + 1] - start[l]);
  std::vector<uint32_t> order(n);
  for (size_t i = 0; i < n; ++i) order[start[deepest - depth[i]]++] = uint32_t(i);
  return order;
}

BvhRefitter::BvhRefitter(Context& ctx, ShaderCompiler& compiler)
    : ctx_(&ctx),
      pipeline_(Pipeline::compute(ctx, compiler.compile("shaders/bvh_refit.comp"),
                                  std::vector<VkDescriptorType>(5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), 2 * sizeof(uint32_t))) {}

void BvhRefitter::set_tree(const Bvh& bvh, uint32_t offset) {
  std::vector<uint32_t> order = refit_order(bvh, levels_);
  if (offset > 0) {
    for (uint32_t& n : order) n += offset;
    levels_.emplace_back(uint32_t(order.size()), 1u);
    order.push_back(0u);
  }
  order_ = Buffer::storage(*ctx_, order);
}

void BvhRefitter::record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& triangles, const Buffer& nodes,
                         const Buffer& prims) const {
  if (levels_.empty()) return;
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, {Descriptor::storage(vertices), Descriptor::storage(triangles), Descriptor::storage(nodes),
                                   Descriptor::storage(prims), Descriptor::storage(order_)});
  for (const auto& [first, count] : levels_) {
    const uint32_t push[2] = {first, count};
    pipeline_.push_constants(cmd, push, sizeof(push));
    pipeline_.dispatch_1d(cmd, count);
    full_barrier(cmd);
  }
}

}  // namespace giq::realtime
