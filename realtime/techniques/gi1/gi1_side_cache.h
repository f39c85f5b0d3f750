#pragma once
// `gi1`'s persistent LRU side cache (Boissé et al. 2022, section 2.1.8): its buffers and its own
// two passes, the binning of the entries into the screen tiles before the reconstruction
// (gi1_side_bin.comp) and the LRU reordering after the blend (gi1_side_order.comp). The
// reconstruction and the blend read and write it through the descriptors it hands out
// (gi1_reconstruct.comp, gi1_blend.comp; gi1_side.glsl lays out its state words).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/timer.h"

namespace giq::realtime {

class Gi1SideCache {
 public:
  // A compute pipeline of techniques/gi1/<name> with these bindings.
  using Compile = std::function<Pipeline(const char* name, std::vector<VkDescriptorType> bindings)>;

  // `entries` 0: off (buffers of a word, bound and never read). `tiles`: the screen tiles;
  // `slots`: the spawn list's slots.
  Gi1SideCache(Context& ctx, const Compile& compile, uint32_t entries, uint64_t tiles,
               uint64_t slots);

  uint32_t entries() const { return entries_; }
  // The first frame: every entry empty, no stamps.
  void clear(VkCommandBuffer cmd);
  // Every frame, before the first pass: the tiles' lists and the claims cleared.
  void begin_frame(VkCommandBuffer cmd);
  // Before the reconstruction: each entry listed by the tile it projects into.
  void bin(VkCommandBuffer cmd, GpuTimer& timer, const Buffer& frame_constants);
  // The reconstruction's bindings: entries, their radiance, this frame's order, the state
  // words and the writes it schedules.
  std::vector<Descriptor> reconstruct_descriptors(int frame) const;
  // The blend's: the scheduled writes, the state words, the entries and their radiance.
  std::vector<Descriptor> blend_descriptors() const;
  // After the blend: the entries used this frame to the front of the next frame's order.
  void reorder(VkCommandBuffer cmd, GpuTimer& timer, const Buffer& frame_constants, int frame);

 private:
  uint32_t entries_ = 0;
  uint64_t stamp_bytes_ = 0;
  Buffer probes_, radiance_, state_, writes_, order_[2], rank_;
  Pipeline bin_, reorder_;
};

}  // namespace giq::realtime
