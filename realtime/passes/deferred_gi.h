#pragma once
// The deferred frame every screen-space GI technique is recorded inside: a technique is only
// its indirect light. The frame owns the shared steps and declares their parameters once:
//   shadow_maps      shadow maps of every light (passes/shadow_maps.h)
//   rsm              reflective shadow maps, for techniques that ask (passes/rsm.h)
//   gbuffer          rasterised or ray-traced (passes/gbuffer.h), motion vectors on request
//   direct_lighting  the direct light every technique shares (passes/direct_light.h), or
//                    none for a technique that computes its own (FrameNeeds::own_direct)
//   ...              the technique's own passes (IndirectLight::record)
//   upsample, blur   for techniques that shade at 1/k resolution (passes/upsample.h), for the
//                    indirect light and each extra layer
//   composite        beauty = direct + indirect (passes/composite.h)
// in that order, each timed under its name. Outputs: "" (beauty), "direct", "indirect", then
// the technique's extra layers. A technique that adds no light (`direct`) gets beauty =
// direct and a black indirect layer, without a composite.
//
// Falcor's render passes declare their inputs and outputs (`reflect()`) and a graph wires them;
// a deferred GI frame has one fixed shape, so a technique declares only which optional steps
// it uses (FrameNeeds) and reads what the frame made through its accessors.

#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "passes/composite.h"
#include "passes/direct_light.h"
#include "passes/gbuffer.h"
#include "passes/rsm.h"
#include "passes/upsample.h"

namespace giq::realtime {

// The optional steps of the frame a technique uses.
struct FrameNeeds {
  bool indirect = true;                 // false: the technique adds no light (`direct`)
  bool reflective_shadow_maps = false;  // the "rsm" step and its parameters
  bool motion_vectors = false;          // the G-buffer's motion vectors, every frame
  // The technique writes the direct light too (into DeferredGi::direct_target(), at full
  // resolution), so the frame records neither shadow maps nor the shared direct light and
  // declares none of their parameters: for techniques whose direct light is part of what
  // they estimate and denoise (`hybrid`).
  bool own_direct = false;
  // 0: the indirect light is shaded at full resolution. k >= 1: at 1/k resolution per axis,
  // brought back by the edge-aware upsample; declares "downsample" (default k) and "blur".
  int downsample = 0;
};

class DeferredGi;

// A GI technique's own work: recorded once per frame after the direct light, it writes the
// indirect radiance into frame.indirect_target() and its extra layers, each pass between
// in.timer.begin() and in.timer.end().
class IndirectLight {
 public:
  virtual ~IndirectLight() = default;
  virtual void record(const FrameInput& in, DeferredGi& frame) = 0;
};

class DeferredGi final : public Technique {
 public:
  // The shared steps' parameters for these needs: the G-buffer builder, the direct light's,
  // the reflective shadow maps' and the upsample's.
  static std::vector<Parameter> parameters(const FrameNeeds& needs);

  DeferredGi(const TechniqueCreateInfo& ci, const FrameNeeds& needs);
  // The technique, created after the frame so that it can size its resources from it.
  void set_light(std::unique_ptr<IndirectLight> light) { light_ = std::move(light); }

  void render(const FrameInput& in) override;
  std::vector<std::pair<std::string, Image*>> outputs() override;

  // What the shared steps made this frame, for the technique's passes.
  GBufferPass& gbuffer() { return gbuffer_; }
  DirectLightPass& direct_light();  // not with FrameNeeds::own_direct
  ReflectiveShadowMaps& rsm();  // only with FrameNeeds::reflective_shadow_maps

  uint32_t width() const { return width_; }  // full resolution
  uint32_t height() const { return height_; }
  // The resolution the technique shades at: full, or 1/k with FrameNeeds::downsample.
  uint32_t factor() const { return upsample_ ? upsample_->factor() : 1u; }
  uint32_t target_width() const { return upsample_ ? upsample_->low_width() : width_; }
  uint32_t target_height() const { return upsample_ ? upsample_->low_height() : height_; }
  // RGBA32F at the target resolution; the technique moves it to GENERAL and writes it.
  Image& indirect_target() { return upsample_ ? low_ : indirect_; }
  // RGBA32F at full resolution, with FrameNeeds::own_direct: the technique moves it to
  // GENERAL and writes it.
  Image& direct_target() { return own_direct_; }
  // An extra output layer, written like the indirect target and upsampled like it; call
  // from the technique's constructor.
  Image& add_layer(const std::string& name);

 private:
  struct Layer {
    std::string name;
    Image target;
    std::unique_ptr<UpsamplePass> upsample;
  };

  Image& direct() { return lighting_ ? lighting_->output() : own_direct_; }

  uint32_t width_, height_;
  GBufferPass gbuffer_;
  std::unique_ptr<DirectLightPass> lighting_;
  std::unique_ptr<ReflectiveShadowMaps> rsm_;
  std::unique_ptr<UpsamplePass> upsample_;
  std::unique_ptr<CompositePass> composite_;
  Image low_, indirect_, own_direct_;
  std::deque<Layer> layers_;  // a deque: add_layer()'s references stay valid
  std::unique_ptr<IndirectLight> light_;
  const TechniqueCreateInfo ci_;  // for add_layer's upsample passes
};

// The registry entry of a deferred GI technique T, constructed as T(ci, frame): its own
// parameters first, then the frame's. T = void: the frame alone (`direct`).
template <class T>
TechniqueInfo deferred_technique(std::string name, std::string description, const FrameNeeds& needs,
                                 std::vector<Parameter> own, QualityKnob quality) {
  for (auto& p : DeferredGi::parameters(needs)) own.push_back(std::move(p));
  return {std::move(name), std::move(description), std::move(own), std::move(quality),
          [needs](const TechniqueCreateInfo& ci) {
            auto frame = std::make_unique<DeferredGi>(ci, needs);
            if constexpr (!std::is_void_v<T>) frame->set_light(std::make_unique<T>(ci, *frame));
            return std::unique_ptr<Technique>(std::move(frame));
          }};
}

}  // namespace giq::realtime
