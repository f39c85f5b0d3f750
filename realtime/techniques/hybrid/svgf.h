#pragma once
// The spatiotemporal variance-guided filter (SVGF: Schied et al. 2017, "Spatiotemporal
// Variance-Guided Filtering: Real-Time Reconstruction for Path-Traced Global Illumination",
// HPG), for two signals at once (direct and indirect light, filtered separately as Kim-Chan
// 2022, section 2.2, does). Per frame, each pass timed under its name:
//   svgf_reproject   demodulate by albedo, reproject the history with the G-buffer's motion
//                    vectors, exponential moving averages of colour and luminance moments
//                    (svgf_reproject.comp)
//   svgf_variance    a 7x7 spatial variance where the history is under 4 frames
//                    (svgf_variance.comp)
//   svgf_atrous_<i>  the i-th a-trous iteration, step 2^i; the output of iteration
//                    `feedback_tap` is next frame's history (svgf_atrous.comp)
//   svgf_modulate    remodulate, add the unfiltered light (svgf_modulate.comp)
// NVIDIA Falcor's SVGFPass is the public implementation whose behaviour and defaults this
// follows; docs/techniques/hybrid.md maps the paper's equations to the shaders.

#include <array>
#include <cstdint>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "giq/scenes/camera.h"

namespace giq::realtime {

class Context;
class GBufferPass;
class GpuTimer;
class ShaderCompiler;

struct SvgfSettings {
  int iterations = 4;      // a-trous iterations (0: temporal accumulation only)
  int feedback_tap = 1;    // the iteration whose output is the history (-1: the unfiltered mean)
  float phi_colour = 10.0f;
  float phi_normal = 128.0f;
  float alpha_colour = 0.05f;
  float alpha_moments = 0.2f;
  int history_cap = 32;    // frames
};

class Svgf {
 public:
  // iterations, feedback_tap, phi_colour, phi_normal, alpha_colour, alpha_moments,
  // history_cap, with Falcor's defaults, for a technique to list among its own.
  static std::vector<Parameter> parameters();
  static SvgfSettings settings(const ParameterValues& values);

  Svgf(Context& ctx, ShaderCompiler& compiler, uint32_t width, uint32_t height, const SvgfSettings& settings);

  // Images the filter reads and writes, RGBA32F at its size, in GENERAL layout.
  struct Frame {
    Image& direct;      // in: raw direct light, `unfiltered` included
    Image& indirect;    // in: raw indirect light
    Image& unfiltered;  // in: light that needs no filtering (emission, background)
    Image& albedo;      // in: what the light is demodulated by; 0 where nothing is filtered
    Image& out_direct;  // out: filtered direct light plus `unfiltered`
    Image& out_indirect;
    Image& out_history; // out: R = frames in the history
  };
  // `restart`: drop the history (the first frame). The G-buffer's motion vectors must be on.
  void record(VkCommandBuffer cmd, const Frame& frame, GBufferPass& gbuffer, const scenes::Camera& camera,
              bool restart, GpuTimer& timer);

  // One a-trous iteration alone, for tests: colour (rgb) and variance (alpha) of each signal
  // from `in` to `out` over a surface image as svgf_shared.h describes it.
  void record_atrous(VkCommandBuffer cmd, Image& surface, Image& in_direct, Image& in_indirect, Image& out_direct,
                     Image& out_indirect, int step);

 private:
  void atrous(VkCommandBuffer cmd, Image& surface, Image& in_direct, Image& in_indirect, Image& out_direct,
              Image& out_indirect, int step, bool feedback);
  std::vector<Image*> images();

  uint32_t width_, height_;
  SvgfSettings settings_;
  // Two of each kept from frame to frame: this frame's writes one, reads the other.
  std::array<Image, 2> surface_, object_, moments_, length_;
  Image history_direct_, history_indirect_;  // the feedback tap's output
  Image integrated_direct_, integrated_indirect_;
  std::array<Image, 2> ping_direct_, ping_indirect_;
  int current_ = 0;
  bool has_previous_ = false;
  scenes::Camera previous_;
  Pipeline reproject_, variance_, atrous_, modulate_;
};

}  // namespace giq::realtime
