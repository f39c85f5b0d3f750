#pragma once
// The shared composite pass of GI techniques: beauty = direct + indirect, per pixel, so that
// the relation the reference keeps exactly (beauty = direct + indirect) holds for every
// technique too, and each technique's indirect layer can be scored on its own.

#include <cstdint>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class ShaderCompiler;

class CompositePass {
 public:
  CompositePass(Context& ctx, ShaderCompiler& compiler, uint32_t width, uint32_t height);
  // Pass name "composite"; direct and indirect are RGBA32F images in GENERAL layout.
  void record(VkCommandBuffer cmd, Image& direct, Image& indirect, GpuTimer& timer);
  Image& output() { return beauty_; }

 private:
  uint32_t width_, height_;
  Image beauty_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
