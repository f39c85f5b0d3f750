// `rsm`: the shared direct-lighting pass, the shared reflective shadow maps (passes/rsm.h) and
// a gather of N VPL samples per pixel (rsm_gather.comp); beauty = direct + indirect.
#include "techniques/rsm/rsm.h"

#include <cmath>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/composite.h"
#include "passes/direct_light.h"
#include "passes/gbuffer.h"
#include "passes/rsm.h"
#include "passes/upsample.h"
#include "techniques/rsm/rsm_shared.h"

namespace giq::realtime {
namespace {

// The thesis draws (xi1, xi2) uniformly at random once for all pixels (seed 000, appendix:
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

class Rsm : public Technique {
 public:
  explicit Rsm(const TechniqueCreateInfo& ci)
      : scene_gpu_(ci.scene_gpu),
        width_(ci.width),
        height_(ci.height),
        gbuffer_(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.features, ci.width, ci.height,
                 GBufferPass::builder(ci.parameters)),
        lighting_(ci),
        rsm_(ci),
        composite_(ci.ctx, ci.compiler, ci.width, ci.height),
        samples_(uint32_t(ci.parameters.get_int("samples"))),
        r_max_(float(ci.parameters.get("r_max"))),
        upsample_(ci.ctx, ci.compiler, ci.width, ci.height,
                  uint32_t(ci.parameters.get_int("downsample")),
                  ci.parameters.get_int("blur") != 0),
        blur_(ci.parameters.get_int("blur") != 0),
        low_(ci.ctx, {upsample_.low_width(), upsample_.low_height(), 1,
                      VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT}) {
    sample_buffer_ = Buffer::storage(ci.ctx, polar_samples(samples_, r_max_));
    auto bindings = SceneGpu::binding_types();
    bindings.insert(bindings.end(),
                    {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                     VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                     VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                     VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                     VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
    gather_ = Pipeline::compute(
        ci.ctx,
        ci.compiler.compile("techniques/rsm/rsm_gather.comp", feature_defines(ci.scene.features)),
        bindings, sizeof(gpu::RsmGatherPush));
  }

  std::vector<std::string> passes() const override {
    std::vector<std::string> p = {"shadow_maps",     "rsm",        "gbuffer",
                                  "direct_lighting", "rsm_gather", "upsample"};
    if (blur_) p.push_back("blur");
    p.push_back("composite");
    return p;
  }

  void render(const FrameInput& in) override {
    lighting_.record_shadows(in);
    rsm_.record(in);
    gbuffer_.record(in.cmd, in.camera, in.timer);
    lighting_.record_lighting(in, gbuffer_);

    in.timer.begin(in.cmd, "rsm_gather");
    low_.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
    gather_.bind(in.cmd);
    auto d = scene_gpu_.descriptors();
    d.push_back(Descriptor::storage_image(gbuffer_.position()));
    d.push_back(Descriptor::storage_image(gbuffer_.normal()));
    d.push_back(Descriptor::storage_image(gbuffer_.ids()));
    d.push_back(Descriptor::storage_image(rsm_.surface()));
    d.push_back(Descriptor::storage_image(rsm_.flux()));
    d.push_back(Descriptor::storage(rsm_.layer_buffer()));
    d.push_back(Descriptor::storage(rsm_.emitter_buffer()));
    d.push_back(Descriptor::storage(sample_buffer_));
    d.push_back(Descriptor::storage_image(low_));
    gather_.push_descriptors(in.cmd, d);
    // Seed 000, 2.2.1: the gather runs at 1/k resolution, O(width/k height/k N).
    gpu::RsmGatherPush pc{
        glm::uvec4(width_, height_, upsample_.low_width(), upsample_.low_height()),
        glm::vec4(r_max_, float(samples_), float(upsample_.factor()), float(rsm_.emitter_count()))};
    gather_.push_constants(in.cmd, pc);
    gather_.dispatch_2d(in.cmd, upsample_.low_width(), upsample_.low_height());
    full_barrier(in.cmd);
    in.timer.end(in.cmd);

    upsample_.record(in.cmd, low_, gbuffer_, in.timer);
    composite_.record(in.cmd, lighting_.output(), upsample_.output(), in.timer);
  }

  std::vector<std::pair<std::string, Image*>> outputs() override {
    return {{"", &composite_.output()},
            {"direct", &lighting_.output()},
            {"indirect", &upsample_.output()}};
  }

 private:
  const SceneGpu& scene_gpu_;
  uint32_t width_, height_;
  GBufferPass gbuffer_;
  DirectLightPass lighting_;
  ReflectiveShadowMaps rsm_;
  CompositePass composite_;
  uint32_t samples_;
  float r_max_;
  UpsamplePass upsample_;
  bool blur_;
  Image low_;
  Buffer sample_buffer_;
  Pipeline gather_;
};

}  // namespace

TechniqueInfo rsm_technique() {
  std::vector<Parameter> parameters = DirectLightPass::parameters();
  parameters.push_back(GBufferPass::ray_traced_parameter());
  for (auto& p : ReflectiveShadowMaps::parameters()) parameters.push_back(p);
  parameters.push_back({"samples", 512, 1, 4096, true, "VPL samples per pixel (seed 000: 512)"});
  parameters.push_back(
      {"r_max", 0.75, 0.001, 1, false,
       "sampling radius: a fraction of a directional light's window; for cube maps, of the "
       "half-angle pi (1 = the whole sphere around the light)"});
  for (auto& p : UpsamplePass::parameters(3)) parameters.push_back(p);  // seed 000, 2.2.1: k = 3
  return {"rsm",
          "Reflective Shadow Maps (seed 000 ch. II): one diffuse bounce from the VPLs of each "
          "light's RSM "
          "(ortho window for the sun, cube faces for point/spot/area lights), N polar samples per "
          "pixel",
          std::move(parameters),
          [](const TechniqueCreateInfo& ci) { return std::make_unique<Rsm>(ci); }};
}

}  // namespace giq::realtime
