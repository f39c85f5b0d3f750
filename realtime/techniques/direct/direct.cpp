// `direct`: the shared G-buffer and direct-lighting passes (passes/direct_light.h), nothing
// else. Outputs: beauty = direct; indirect is black by definition.
#include "techniques/direct/direct.h"

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/timer.h"
#include "passes/direct_light.h"
#include "passes/gbuffer.h"

namespace giq::realtime {
namespace {

class Direct : public Technique {
 public:
  explicit Direct(const TechniqueCreateInfo& ci)
      : gbuffer_(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.features, ci.width, ci.height,
                 GBufferPass::builder(ci.parameters)),
        lighting_(ci),
        indirect_(ci.ctx, {ci.width, ci.height, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                           VK_IMAGE_USAGE_STORAGE_BIT}) {}

  std::vector<std::string> passes() const override { return {"shadow_maps", "gbuffer", "direct_lighting"}; }

  void render(const FrameInput& in) override {
    lighting_.record_shadows(in);
    gbuffer_.record(in.cmd, in.camera, in.timer);
    lighting_.record_lighting(in, gbuffer_);
    if (in.frame == 0) {
      const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      indirect_.clear(in.cmd, black);
    }
  }

  std::vector<std::pair<std::string, Image*>> outputs() override {
    return {{"", &lighting_.output()}, {"direct", &lighting_.output()}, {"indirect", &indirect_}};
  }

 private:
  GBufferPass gbuffer_;
  DirectLightPass lighting_;
  Image indirect_;
};

}  // namespace

TechniqueInfo direct_technique() {
  std::vector<Parameter> parameters = DirectLightPass::parameters();
  parameters.push_back(GBufferPass::ray_traced_parameter());
  return {"direct",
          "direct light only: rasterised G-buffer, shadow maps (cube maps for point/spot and area lights, 3 cascades "
          "for the sun, PCF), exact area-light integration; no indirect light",
          std::move(parameters), [](const TechniqueCreateInfo& ci) { return std::make_unique<Direct>(ci); }};
}

}  // namespace giq::realtime
