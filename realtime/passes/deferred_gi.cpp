#include "passes/deferred_gi.h"

#include <stdexcept>

namespace giq::realtime {

std::vector<Parameter> DeferredGi::parameters(const FrameNeeds& needs) {
  std::vector<Parameter> p;
  if (!needs.own_direct) p = DirectLightPass::parameters();
  p.push_back(GBufferPass::ray_traced_parameter());
  if (needs.reflective_shadow_maps)
    for (auto& r : ReflectiveShadowMaps::parameters()) p.push_back(std::move(r));
  if (needs.downsample > 0)
    for (auto& u : UpsamplePass::parameters(needs.downsample)) p.push_back(std::move(u));
  return p;
}

DeferredGi::DeferredGi(const TechniqueCreateInfo& ci, const FrameNeeds& needs)
    : width_(ci.width), height_(ci.height), gbuffer_(ci), ci_(ci) {
  if (needs.own_direct)
    own_direct_ = Image(ci.ctx, {width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
  else
    lighting_ = std::make_unique<DirectLightPass>(ci);
  if (needs.motion_vectors) gbuffer_.enable_motion_vectors();
  if (needs.reflective_shadow_maps) rsm_ = std::make_unique<ReflectiveShadowMaps>(ci);
  const ImageDesc full{width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT};
  if (!needs.indirect) {
    indirect_ = Image(ci.ctx, full);  // black, cleared on the first frame
    return;
  }
  composite_ = std::make_unique<CompositePass>(ci.ctx, ci.compiler, width_, height_);
  if (needs.downsample > 0) {
    upsample_ = std::make_unique<UpsamplePass>(ci);
    low_ = Image(ci.ctx, {target_width(), target_height(), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                          VK_IMAGE_USAGE_STORAGE_BIT});
  } else {
    indirect_ = Image(ci.ctx, full);
  }
}

DirectLightPass& DeferredGi::direct_light() {
  if (!lighting_) throw std::logic_error("the technique computes its own direct light (FrameNeeds::own_direct)");
  return *lighting_;
}

ReflectiveShadowMaps& DeferredGi::rsm() {
  if (!rsm_) throw std::logic_error("the frame was created without reflective shadow maps (FrameNeeds)");
  return *rsm_;
}

Image& DeferredGi::add_layer(const std::string& name) {
  Layer l;
  l.name = name;
  l.target = Image(ci_.ctx, {target_width(), target_height(), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                             VK_IMAGE_USAGE_STORAGE_BIT});
  if (upsample_) l.upsample = std::make_unique<UpsamplePass>(ci_);
  layers_.push_back(std::move(l));
  return layers_.back().target;
}

void DeferredGi::render(const FrameInput& in) {
  if (lighting_) lighting_->record_shadows(in);
  if (rsm_) rsm_->record(in);
  gbuffer_.record(in.cmd, in.camera, in.timer);
  if (lighting_) lighting_->record_lighting(in, gbuffer_);
  if (!composite_) {
    if (in.frame == 0) {
      const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
      indirect_.clear(in.cmd, black);
    }
    return;
  }
  if (light_) light_->record(in, *this);
  if (upsample_) {
    upsample_->record(in.cmd, low_, gbuffer_, in.timer);
    for (auto& l : layers_) l.upsample->record(in.cmd, l.target, gbuffer_, in.timer);
  }
  composite_->record(in.cmd, direct(), upsample_ ? upsample_->output() : indirect_, in.timer);
}

std::vector<std::pair<std::string, Image*>> DeferredGi::outputs() {
  Image& indirect = upsample_ ? upsample_->output() : indirect_;
  std::vector<std::pair<std::string, Image*>> o = {
      {"", composite_ ? &composite_->output() : &direct()},
      {"direct", &direct()},
      {"indirect", &indirect}};
  for (auto& l : layers_) o.push_back({l.name, l.upsample ? &l.upsample->output() : &l.target});
  return o;
}

}  // namespace giq::realtime
