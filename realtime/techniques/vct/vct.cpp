// `vct`: the shared G-buffer, shadow-map and direct-lighting passes, then voxel cone tracing
// for the indirect light (seed 000 ch. IV; seed 001, "Voxel-based Global Illumination"):
//   voxelize     the scene's triangles into the base level (voxelize.comp)
//   voxel_light  albedo x shadowed direct light per marked voxel (voxel_light.comp)
//   voxel_mips   six anisotropic mip chains (voxel_mip.comp), optionally blended over time
//   cone_trace   diffuse cones + one specular cone per pixel at 1/k resolution (cone_trace.comp)
//   upsample, blur (passes/upsample.h), composite.
// Everything is re-voxelised every frame, so moving lights and geometry need no bookkeeping
// beyond the temporal blend's reset.
#include "techniques/vct/vct.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include "giq/base/error.h"
#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/composite.h"
#include "passes/direct_light.h"
#include "passes/gbuffer.h"
#include "passes/upsample.h"
#include "techniques/vct/vct_shared.h"
#include "techniques/vct/volume.h"
#include "techniques/vct/voxel_scale.h"

namespace giq::realtime {
namespace {

constexpr uint32_t kMaxGroupsX = 65535;     // minimum maxComputeWorkGroupCount[0]
constexpr uint32_t kCoarsestChainSize = 4;  // seed 000 ch. V: chains stop at 4^3

uint32_t voxel_resolution(const ParameterValues& p) {
  const int r = p.get_int("voxel_resolution");
  if (r < 8 || (r & (r - 1)) != 0)
    throw InputError(
        "", "--param",
        "voxel_resolution=" + std::to_string(r) + ": expected a power of two from 8 to 512");
  return uint32_t(r);
}

uint32_t chain_levels(uint32_t resolution) {
  uint32_t levels = 1;
  for (uint32_t s = resolution / 2; s > kCoarsestChainSize; s /= 2) ++levels;
  return levels;
}

class Vct : public Technique {
 public:
  explicit Vct(const TechniqueCreateInfo& ci)
      : scene_gpu_(ci.scene_gpu),
        width_(ci.width),
        height_(ci.height),
        gbuffer_(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.features, ci.width, ci.height,
                 GBufferPass::builder(ci.parameters)),
        lighting_(ci),
        upsample_(ci.ctx, ci.compiler, ci.width, ci.height,
                  uint32_t(ci.parameters.get_int("downsample")),
                  ci.parameters.get_int("blur") != 0),
        composite_(ci.ctx, ci.compiler, ci.width, ci.height) {
    const auto& p = ci.parameters;
    resolution_ = voxel_resolution(p);
    cone_count_ = uint32_t(p.get_int("cone_count"));
    bounces_ = uint32_t(p.get_int("bounces"));
    aperture_ = float(p.get("cone_aperture"));
    max_distance_ = float(p.get("max_distance"));
    step_factor_ = float(p.get("step_factor"));
    start_offset_ = float(p.get("start_offset"));
    guard_ = float(p.get("footprint_guard"));
    history_ = float(p.get("temporal_blend"));
    // The blend mixes the new level-0 chains with what they held before: the previous frame's
    // only when a single bounce rebuilds them once per frame.
    if (history_ > 0.0f && bounces_ > 1)
      throw InputError("", "--param",
                       "temporal_blend=" + std::to_string(history_) + " with bounces=" +
                           std::to_string(bounces_) + ": the temporal blend needs bounces=1");
    ao_ = p.get_int("ao") != 0;
    blur_ = p.get_int("blur") != 0;
    ao_falloff_ = float(p.get("ao_falloff"));

    // The cube around the scene's bounds at creation, one voxel of margin on each side so
    // that surfaces on the bounds are inside it. Geometry that moves out of it is not
    // voxelised (docs/techniques/vct.md).
    const glm::vec3 extent = ci.scene.bounds.extent();
    const float side = std::max(std::max(extent.x, std::max(extent.y, extent.z)), 1e-6f);
    const float voxel = side / float(resolution_ - 2);
    const glm::vec3 centre = 0.5f * (ci.scene.bounds.lo + ci.scene.bounds.hi);
    grid_.origin = glm::vec4(centre - glm::vec3(0.5f * voxel * float(resolution_)), voxel);
    grid_.size = glm::uvec4(resolution_, chain_levels(resolution_), 0, 0);
    // Shadow rays leave the surface by a thousandth of a voxel: far above float rounding at
    // the scene's scale, far below any feature the voxels resolve.
    ray_offset_ = 1e-3f * voxel;

    base_ = Volume(ci.ctx, resolution_, 1);
    for (auto& c : chains_) c = Volume(ci.ctx, resolution_ / 2, grid_.size.y);
    emitters_ = voxel_emitters(ci.scene);
    emitter_buffer_ =
        Buffer(ci.ctx, std::max<uint64_t>(16, emitters_.size() * sizeof(gpu::VctEmitter)),
               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload);
    upload_emitters();
    scale_ = voxel_radiance_scale(ci.scene, emitters_, int(bounces_));

    const ImageDesc low{upsample_.low_width(), upsample_.low_height(), 1,
                        VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT};
    low_ = Image(ci.ctx, low);
    if (ao_) {
      ao_low_ = Image(ci.ctx, low);
      ao_upsample_ =
          std::make_unique<UpsamplePass>(ci.ctx, ci.compiler, width_, height_, upsample_.factor(),
                                         ci.parameters.get_int("blur") != 0);
    }

    const auto defines = feature_defines(ci.scene.features);
    clear_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxel_clear.comp"),
                               {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, 0);
    auto scene_bindings = SceneGpu::binding_types();
    auto b = scene_bindings;
    b.push_back(VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    voxelize_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxelize.comp", defines), b,
                          sizeof(gpu::VctVoxelPush));
    b.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    b.insert(b.end(), 6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    light_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxel_light.comp", defines),
                          b, sizeof(gpu::VctVoxelPush));
    std::vector<VkDescriptorType> mb(1 + 6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    mb.insert(mb.end(), 6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    mip_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxel_mip.comp", defines),
                             mb, sizeof(gpu::VctVoxelPush));
    b = scene_bindings;
    b.insert(b.end(), 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    b.insert(b.end(), 7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    b.insert(b.end(), 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    cone_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/cone_trace.comp", defines), b,
                          sizeof(gpu::VctConePush));
  }

  std::vector<std::string> passes() const override {
    std::vector<std::string> p = {"shadow_maps", "gbuffer", "direct_lighting"};
    for (uint32_t b = 0; b < bounces_; ++b)
      for (const char* pass : {"voxelize", "voxel_light", "voxel_mips"})
        p.push_back(bounce_pass(pass, b));
    p.insert(p.end(), {"cone_trace", "upsample"});
    if (blur_on()) p.push_back("blur");
    if (ao_) {
      p.push_back("upsample");
      if (blur_on()) p.push_back("blur");
    }
    p.push_back("composite");
    return p;
  }

  void render(const FrameInput& in) override {
    if (in.frame == 0 || in.change != SceneChange::None) {
      if (in.frame == 0 || in.change == SceneChange::Geometry) {
        emitters_ = voxel_emitters(in.scene);
        upload_emitters();
      }
      scale_ = voxel_radiance_scale(in.scene, emitters_, int(bounces_));
    }
    lighting_.record_shadows(in);
    gbuffer_.record(in.cmd, in.camera, in.timer);
    lighting_.record_lighting(in, gbuffer_);
    for (uint32_t b = 0; b < bounces_; ++b) record_voxels(in, b);
    record_cones(in);
    upsample_.record(in.cmd, low_, gbuffer_, in.timer);
    if (ao_) ao_upsample_->record(in.cmd, ao_low_, gbuffer_, in.timer);
    composite_.record(in.cmd, lighting_.output(), upsample_.output(), in.timer);
  }

  std::vector<std::pair<std::string, Image*>> outputs() override {
    std::vector<std::pair<std::string, Image*>> o = {{"", &composite_.output()},
                                                     {"direct", &lighting_.output()},
                                                     {"indirect", &upsample_.output()}};
    if (ao_) o.push_back({"ao", &ao_upsample_->output()});
    return o;
  }

 private:
  bool blur_on() const { return blur_; }
  static std::string bounce_pass(const char* pass, uint32_t bounce) {
    return bounce == 0 ? std::string(pass) : std::string(pass) + "_" + std::to_string(bounce + 1);
  }

  void upload_emitters() {
    if (!emitters_.empty())
      std::memcpy(emitter_buffer_.mapped(), emitters_.data(),
                  emitters_.size() * sizeof(gpu::VctEmitter));
  }

  // One bounce: voxelise, light the voxels (adding, after the first, what they receive from
  // the previous bounce's mips), rebuild the mips.
  void record_voxels(const FrameInput& in, uint32_t bounce) {
    VkCommandBuffer cmd = in.cmd;
    for (auto& c : chains_) c.make_general(cmd);
    in.timer.begin(cmd, bounce_pass("voxelize", bounce));
    base_.make_general(cmd);
    clear_.bind(cmd);
    clear_.push_descriptors(cmd, {base_.storage(0)});
    const uint32_t groups = (resolution_ + 3) / 4;
    vkCmdDispatch(cmd, groups, groups, groups);
    full_barrier(cmd);
    gpu::VctVoxelPush pc{};
    pc.grid = grid_;
    const uint32_t triangles = scene_gpu_.triangle_count();
    pc.grid.size.z = triangles;
    // Workgroups (of 64 threads) per triangle: enough that a few large triangles (a room's
    // walls, each covering up to resolution^2 columns) spread over about 2048 workgroups, so a
    // GPU of a hundred multiprocessors is busy (8 per triangle left an H100 at 1.3 ms for
    // the Cornell box's 32 triangles); with many triangles, each small, one is plenty.
    const uint32_t slices = std::clamp<uint32_t>(2048u / std::max(triangles, 1u), 1u, 256u);
    pc.grid.size.w = slices;
    if (triangles > 0) {
      voxelize_.bind(cmd);
      auto d = scene_gpu_.descriptors();
      d.push_back(base_.storage(0));
      voxelize_.push_descriptors(cmd, d);
      voxelize_.push_constants(cmd, pc);
      const uint32_t gx = std::min(triangles, kMaxGroupsX), gy = (triangles + gx - 1) / gx;
      vkCmdDispatch(cmd, gx, gy, slices);
    }
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, bounce_pass("voxel_light", bounce));
    light_.bind(cmd);
    auto d = scene_gpu_.descriptors();
    d.push_back(base_.storage(0));
    d.push_back(Descriptor::storage(emitter_buffer_));
    for (auto& c : chains_) d.push_back(c.sampled());
    light_.push_descriptors(cmd, d);
    pc.grid.size.z = scene_gpu_.light_count();
    pc.grid.size.w = uint32_t(emitters_.size());
    pc.params = glm::vec4(scale_, ray_offset_, float(cone_count_), bounce > 0 ? 1.0f : 0.0f);
    pc.cone = glm::vec4(aperture_, max_distance_ * grid_.origin.w * float(resolution_),
                        step_factor_, start_offset_);
    pc.guard = glm::vec4(guard_, 0.0f, 0.0f, 0.0f);
    light_.push_constants(cmd, pc);
    const uint32_t g = (resolution_ + 3) / 4;
    vkCmdDispatch(cmd, g, g, g);
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, bounce_pass("voxel_mips", bounce));
    mip_.bind(cmd);
    // The previous frame's voxels are blended in only when there are some and they were
    // encoded with the same scale (a light that changed brightness restarts the history).
    const bool blend = in.frame > 0 && history_ > 0.0f && scale_ == history_scale_;
    history_scale_ = scale_;
    for (uint32_t level = 0; level < grid_.size.y; ++level) {
      std::vector<Descriptor> md = {base_.sampled()};
      for (auto& c : chains_) md.push_back(c.sampled());
      for (auto& c : chains_) md.push_back(c.storage(level));
      mip_.push_descriptors(cmd, md);
      pc.grid.size.z = level;
      pc.grid.size.w = level == 0 && blend ? 1u : 0u;
      pc.params = glm::vec4(1.0f - history_, 0.0f, 0.0f, 0.0f);
      mip_.push_constants(cmd, pc);
      const uint32_t n = ((resolution_ >> (level + 1)) + 3) / 4;
      vkCmdDispatch(cmd, n, n, n);
      full_barrier(cmd);
    }
    in.timer.end(cmd);
  }

  void record_cones(const FrameInput& in) {
    VkCommandBuffer cmd = in.cmd;
    in.timer.begin(cmd, "cone_trace");
    low_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    if (ao_) ao_low_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    cone_.bind(cmd);
    auto d = scene_gpu_.descriptors();
    d.push_back(Descriptor::storage_image(gbuffer_.position()));
    d.push_back(Descriptor::storage_image(gbuffer_.normal()));
    d.push_back(Descriptor::storage_image(gbuffer_.ids()));
    d.push_back(base_.sampled());
    for (auto& c : chains_) d.push_back(c.sampled());
    d.push_back(Descriptor::storage_image(low_));
    d.push_back(Descriptor::storage_image(ao_ ? ao_low_ : low_));
    cone_.push_descriptors(cmd, d);
    gpu::VctConePush pc{};
    pc.eye = glm::vec4(in.camera.position, 1.0f);
    pc.grid = grid_;
    pc.grid.size.z = cone_count_;
    pc.grid.size.w = ao_ ? 1u : 0u;
    const float side = grid_.origin.w * float(resolution_);
    pc.viewport = glm::vec4(float(width_), float(height_), float(upsample_.low_width()),
                            float(upsample_.low_height()));
    pc.cone = glm::vec4(aperture_, max_distance_ * side, step_factor_, start_offset_);
    pc.params = glm::vec4(1.0f / scale_, float(upsample_.factor()), ao_falloff_, guard_);
    cone_.push_constants(cmd, pc);
    cone_.dispatch_2d(cmd, upsample_.low_width(), upsample_.low_height());
    full_barrier(cmd);
    in.timer.end(cmd);
  }

  const SceneGpu& scene_gpu_;
  uint32_t width_, height_;
  GBufferPass gbuffer_;
  DirectLightPass lighting_;
  UpsamplePass upsample_;
  std::unique_ptr<UpsamplePass> ao_upsample_;
  CompositePass composite_;
  uint32_t resolution_ = 256, cone_count_ = 6, bounces_ = 1;
  float aperture_ = 0.577f, max_distance_ = 1.0f, step_factor_ = 0.5f, start_offset_ = 1.0f;
  float history_ = 0.0f, ao_falloff_ = 0.0f, ray_offset_ = 0.0f, guard_ = 1.5f;
  bool ao_ = false, blur_ = true;
  gpu::VctGrid grid_{};
  Volume base_;
  std::array<Volume, 6> chains_;
  std::vector<gpu::VctEmitter> emitters_;
  Buffer emitter_buffer_;
  float scale_ = 1.0f, history_scale_ = 0.0f;
  Image low_, ao_low_;
  Pipeline clear_, voxelize_, light_, mip_, cone_;
};

}  // namespace

TechniqueInfo vct_technique() {
  std::vector<Parameter> parameters = {
      {"voxel_resolution", 256, 8, 512, true, "voxels per side of the base level (a power of two)"},
      {"cone_count", 6, 1, 16, true,
       "diffuse cones: one along the normal (weight 1/4) and the rest on a ring at 60 deg (seed "
       "000's table for 6)"},
      {"cone_aperture", 0.577, 0.05, 1.5, false,
       "diffuse cones' tan(half angle); tan 30 deg in seed 000"},
      {"max_distance", 1.0, 0.01, 2.0, false,
       "cone length, as a fraction of the voxel cube's side"},
      {"step_factor", 0.5, 0.1, 2.0, false,
       "march step as a fraction of the cone's diameter there"},
      {"start_offset", 1.0, 0.0, 4.0, false, "cone apex offset along the normal, in base voxels"},
      {"footprint_guard", 1.5, 0.0, 4.0, false,
       "cap on the sampled cell size: distance from the surface / guard, so that no cone sees "
       "behind its "
       "surface (0: seed 000's log2(diameter / voxel))"},
      {"bounces", 1, 1, 4, true,
       "diffuse bounces: 1 as seed 000; each more re-voxelises and cone-traces from every voxel "
       "(seed 001)"},
      {"temporal_blend", 0.0, 0.0, 0.95, false,
       "weight of the previous frame's voxels (0: re-voxelised from scratch every frame)"},
      {"ao", 0, 0, 1, true,
       "1: also output the cones' ambient occlusion (occluded share, 0 = open) as layer 'ao'"},
      {"ao_falloff", 0.05, 0.0, 10.0, false,
       "AO attenuation with cone diameter (per voxel), seed 000's AOFalloff"},
  };
  for (auto& p : UpsamplePass::parameters(2)) parameters.push_back(std::move(p));
  for (auto& p : DirectLightPass::parameters()) parameters.push_back(std::move(p));
  parameters.push_back(GBufferPass::ray_traced_parameter());
  return {"vct",
          "voxel cone tracing: conservative compute voxelisation of albedo x shadowed direct "
          "light, 6 anisotropic "
          "mip chains, 6 diffuse cones + 1 specular cone at 1/k resolution, edge-aware upsample",
          std::move(parameters),
          [](const TechniqueCreateInfo& ci) { return std::make_unique<Vct>(ci); }};
}

}  // namespace giq::realtime
