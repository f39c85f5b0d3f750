// `rsm`: Reflective Shadow Maps (Afanasev 2021, ch. II; Dachsbacher and Stamminger 2005): a
// gather of N VPL samples per pixel (rsm_gather.comp) from the frame's reflective shadow maps
// (passes/rsm.h), at 1/k resolution.
#include <cmath>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/deferred_gi.h"
#include "techniques/rsm/rsm_shared.h"

namespace giq::realtime {
namespace {

// The thesis draws (xi1, xi2) uniformly at random once for all pixels (Afanasev 2021, appendix:
// the constant buffer `xi`); a Hammersley set has the same distribution with less clumping:
// xi1 = (i + 1/2) / N stratified, xi2 the base-2 radical inverse of i. Stored per sample:
// (xi1, sin 2 pi xi2, cos 2 pi xi2, cos(pi r_max xi1)), the last for cube maps' cones, so the
// gather evaluates no trigonometric function.
std::vector<glm::vec4> polar_samples(uint32_t n, float r_max) {
  std::vector<glm::vec4> xi(n);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    const double xi1 = (i + 0.5) / n, xi2 = double(bits) * 2.3283064365386963e-10;
    xi[i] = glm::vec4(float(xi1), float(std::sin(2.0 * M_PI * xi2)),
                      float(std::cos(2.0 * M_PI * xi2)), float(std::cos(M_PI * r_max * xi1)));
  }
  return xi;
}

class Rsm : public IndirectLight {
 public:
  Rsm(const TechniqueCreateInfo& ci, DeferredGi& /*frame*/)
      : samples_(uint32_t(ci.parameters.get_int("samples"))), r_max_(float(ci.parameters.get("r_max"))) {
    sample_buffer_ = Buffer::storage(ci.ctx, polar_samples(samples_, r_max_));
    auto bindings = GBufferPass::receiver_bindings();
    bindings.insert(bindings.end(),
                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    gather_ = Pipeline::compute(
        ci.ctx, ci.compiler.compile("techniques/rsm/rsm_gather.comp", feature_defines(ci.scene.features)),
        bindings, sizeof(gpu::RsmGatherPush));
  }

  void record(const FrameInput& in, DeferredGi& frame) override {
    ReflectiveShadowMaps& rsm = frame.rsm();
    Image& target = frame.indirect_target();
    in.timer.begin(in.cmd, "rsm_gather");
    target.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
    gather_.bind(in.cmd);
    auto d = frame.gbuffer().receiver_descriptors();
    d.push_back(Descriptor::storage_image(rsm.surface()));
    d.push_back(Descriptor::storage_image(rsm.flux()));
    d.push_back(Descriptor::storage(rsm.layer_buffer()));
    d.push_back(Descriptor::storage(rsm.emitter_buffer()));
    d.push_back(Descriptor::storage(sample_buffer_));
    d.push_back(Descriptor::storage_image(target));
    gather_.push_descriptors(in.cmd, d);
    // Afanasev 2021, II.2.2.1: the gather runs at 1/k resolution, O(width/k height/k N).
    gpu::RsmGatherPush pc{};
    pc.size = glm::uvec2(frame.width(), frame.height());
    pc.low_size = glm::uvec2(frame.target_width(), frame.target_height());
    pc.r_max = r_max_;
    pc.samples = samples_;
    pc.factor = frame.factor();
    pc.emitter_count = rsm.emitter_count();
    gather_.push_constants(in.cmd, pc);
    gather_.dispatch_2d(in.cmd, frame.target_width(), frame.target_height());
    full_barrier(in.cmd);
    in.timer.end(in.cmd);
  }

 private:
  uint32_t samples_;
  float r_max_;
  Buffer sample_buffer_;
  Pipeline gather_;
};

}  // namespace

TechniqueInfo rsm_technique() {
  FrameNeeds needs;
  needs.reflective_shadow_maps = true;
  needs.downsample = 3;  // Afanasev 2021, II.2.2.1: k = 3
  return deferred_technique<Rsm>(
      "rsm",
      "Reflective Shadow Maps (Afanasev 2021 ch. II): one diffuse bounce from the VPLs of each light's RSM (ortho "
      "window for the sun, cube faces for point/spot/area lights), N polar samples per pixel",
      needs,
      {{"samples", 512, 1, 4096, true, "VPL samples per pixel (Afanasev 2021: 512)"},
       {"r_max", 0.75, 0.001, 1, false,
        "sampling radius: a fraction of a directional light's window; for cube maps, of the half-angle pi (1 = the "
        "whole sphere around the light)"}},
      {"samples", {16, 32, 64, 128, 256, 512, 1024}});
}

}  // namespace giq::realtime
