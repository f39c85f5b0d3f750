#pragma once
// The shared "shade at 1/k resolution, bring it back" pass of screen-space GI techniques
// (Afanasev 2021 §II.2.2.1 and §IV: RSM and VCT compute their indirect light at 1/k of the
// screen's resolution and restore it with UpsampleBlurCS). The thesis upsamples bilinearly
// and blurs 9×9 with no regard for edges, which smears indirect light across depth and normal
// discontinuities (the "glow" around objects). Here both steps are edge-aware, guided by the
// full-resolution G-buffer:
//   upsample: joint bilateral upsampling (Kopf et al. 2007, "Joint Bilateral Upsampling"):
//     the 2×2 nearest low-resolution samples, bilinear weights times a geometric weight that
//     vanishes across a normal crease or off the receiver's tangent plane; a pixel that no
//     neighbour resembles takes the most similar sample of its 4×4 neighbourhood.
//   blur: the thesis's 9-tap binomial Gaussian (1 8 28 56 70 56 28 8 1)/256, separable, with
//     the same geometric weight (a cross-bilateral filter).
// Low-resolution pixel (x, y) stands for full-resolution pixel
// (min(k*x + k/2, width-1), min(k*y + k/2, height-1)): techniques shade that G-buffer texel.

#include <cstdint>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"

namespace giq::realtime {

class Context;
class GBufferPass;
class GpuTimer;
class ShaderCompiler;

class UpsamplePass {
 public:
  // "downsample" (k, integer 1..8, default default_k) and "blur" (0/1, default 1).
  static std::vector<Parameter> parameters(int default_k);

  UpsamplePass(Context& ctx, ShaderCompiler& compiler, uint32_t width, uint32_t height, uint32_t k, bool blur);
  // At the technique's resolution, with its "downsample" and "blur" parameters.
  explicit UpsamplePass(const TechniqueCreateInfo& ci);

  uint32_t factor() const { return k_; }
  uint32_t low_width() const { return (width_ + k_ - 1) / k_; }
  uint32_t low_height() const { return (height_ + k_ - 1) / k_; }

  // `low`: RGBA32F, low_width() x low_height(), GENERAL. Records "upsample" and, with blur on,
  // "blur". With k = 1 and blur off it is a copy.
  void record(VkCommandBuffer cmd, Image& low, GBufferPass& gbuffer, GpuTimer& timer);
  Image& output() { return output_; }  // RGBA32F, width x height, GENERAL after record()

 private:
  void dispatch(VkCommandBuffer cmd, GBufferPass& gbuffer, Image& src, Image& dst, uint32_t mode);

  uint32_t width_, height_, k_;
  bool blur_;
  Image output_, scratch_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
