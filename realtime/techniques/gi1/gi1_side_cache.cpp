#include "techniques/gi1/gi1_side_cache.h"

#include <algorithm>

#include "techniques/gi1/gi1_shared.h"

namespace giq::realtime {

Gi1SideCache::Gi1SideCache(Context& ctx, const Compile& compile, uint32_t entries, uint64_t tiles,
                           uint64_t slots)
    : entries_(entries) {
  const VkBufferUsageFlags usage =
      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  auto buffer = [&](uint64_t bytes) { return Buffer(ctx, std::max<uint64_t>(bytes, 16), usage); };
  const uint64_t n = std::max<uint32_t>(entries, 1u);
  probes_ = buffer(n * sizeof(gpu::GpuGi1Probe));
  radiance_ = buffer(n * GIQ_GI1_CELLS * 16);
  // gi1_side.glsl: a stamp per entry, a word per screen tile, a claim per entry.
  state_ = buffer((2 * n + tiles) * 4);
  stamp_bytes_ = n * 4;
  writes_ = buffer(slots * sizeof(gpu::GpuGi1SideWrite));
  std::vector<uint32_t> identity(n);
  for (uint32_t i = 0; i < n; ++i) identity[i] = i;
  for (Buffer& b : order_) b = Buffer::storage(ctx, identity);
  rank_ = Buffer::storage(ctx, identity);
  const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  bin_ = compile("gi1_side_bin.comp", {s, s, s, s});
  reorder_ = compile("gi1_side_order.comp", {s, s, s, s, s});
}

void Gi1SideCache::clear(VkCommandBuffer cmd) {
  vkCmdFillBuffer(cmd, state_.handle(), 0, VK_WHOLE_SIZE, 0);
  vkCmdFillBuffer(cmd, probes_.handle(), 0, VK_WHOLE_SIZE, GIQ_GI1_NONE);  // info.x: empty
}

void Gi1SideCache::begin_frame(VkCommandBuffer cmd) {
  vkCmdFillBuffer(cmd, state_.handle(), stamp_bytes_, VK_WHOLE_SIZE, 0xffffffffu);
}

void Gi1SideCache::bin(VkCommandBuffer cmd, GpuTimer& timer, const Buffer& frame_constants) {
  if (entries_ == 0) return;
  timer.begin(cmd, "gi1_side_bin");
  bin_.bind(cmd);
  bin_.push_descriptors(cmd, {Descriptor::storage(frame_constants), Descriptor::storage(probes_),
                              Descriptor::storage(rank_), Descriptor::storage(state_)});
  vkCmdDispatch(cmd, (entries_ + 63) / 64, 1, 1);
  full_barrier(cmd);
  timer.end(cmd);
}

std::vector<Descriptor> Gi1SideCache::reconstruct_descriptors(int frame) const {
  return {Descriptor::storage(probes_), Descriptor::storage(radiance_),
          Descriptor::storage(order_[frame & 1]), Descriptor::storage(state_),
          Descriptor::storage(writes_)};
}

std::vector<Descriptor> Gi1SideCache::blend_descriptors() const {
  return {Descriptor::storage(writes_), Descriptor::storage(state_), Descriptor::storage(probes_),
          Descriptor::storage(radiance_)};
}

void Gi1SideCache::reorder(VkCommandBuffer cmd, GpuTimer& timer, const Buffer& frame_constants,
                           int frame) {
  if (entries_ == 0) return;
  timer.begin(cmd, "gi1_side_order");
  reorder_.bind(cmd);
  reorder_.push_descriptors(
      cmd, {Descriptor::storage(frame_constants), Descriptor::storage(state_),
            Descriptor::storage(order_[frame & 1]), Descriptor::storage(order_[(frame + 1) & 1]),
            Descriptor::storage(rank_)});
  vkCmdDispatch(cmd, 1, 1, 1);
  full_barrier(cmd);
  timer.end(cmd);
}

}  // namespace giq::realtime
