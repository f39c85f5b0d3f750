// `vct`: voxel cone tracing for the indirect light (Afanasev 2021 ch. IV; Crassin et al. 2011;
// Turánszki 2017, "Voxel-based Global Illumination"):
//   voxelize     the scene's triangles into the base level (voxelize.comp)
//   voxel_light  albedo x shadowed direct light per marked voxel (voxel_light.comp)
//   voxel_mips   six anisotropic mip chains (voxel_mip.comp), optionally blended over time
//   cone_trace   diffuse cones + one specular cone per pixel at 1/k resolution (cone_trace.comp)
// at 1/k resolution, inside the deferred frame (passes/deferred_gi.h), which upsamples and
// composites it.
// Everything is re-voxelised every frame, so moving lights and geometry need no bookkeeping
// beyond the temporal blend's reset.
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
#include "passes/cube_grid.h"
#include "passes/deferred_gi.h"
#include "techniques/vct/vct_shared.h"
#include "techniques/vct/voxel_scale.h"

namespace giq::realtime {
namespace {

constexpr uint32_t kMaxGroupsX = 65535;     // minimum maxComputeWorkGroupCount[0]
constexpr uint32_t kCoarsestChainSize = 4;  // Afanasev 2021 ch. V: chains stop at 4^3

uint32_t voxel_resolution(const ParameterValues& p) {
  const int r = p.get_int("voxel_resolution");
  if (r < 8 || (r & (r - 1)) != 0)
    throw InputError(
        "", "--param",
        "voxel_resolution=" + std::to_string(r) + ": expected a power of two from 8 to 512");
  return uint32_t(r);
}

// A voxel volume: 32 bits a texel, written as R32_UINT storage (so that voxelisation can use
// 32-bit atomics, and shaders pack the value themselves) and read as R8G8B8A8_SRGB with
// trilinear mip filtering: the hardware decodes sRGB before it filters, so cones average
// linear radiance while 8 bits per channel keep a quantisation step of 0.9% to 1.5% of the
// value over 2.5 decades. Afanasev 2021 ch. V counts 256^3 x 4 bytes plus 6 anisotropic chains
// x 4 bytes: this layout is that budget.
ImageDesc volume_desc(uint32_t size, uint32_t levels) {
  ImageDesc d{size, size, 1, VK_FORMAT_R32_UINT, VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT};
  d.depth = size;
  d.levels = levels;
  d.sampled_format = VK_FORMAT_R8G8B8A8_SRGB;
  return d;
}

uint32_t chain_levels(uint32_t resolution) {
  uint32_t levels = 1;
  for (uint32_t s = resolution / 2; s > kCoarsestChainSize; s /= 2) ++levels;
  return levels;
}

class Vct : public IndirectLight {
 public:
  Vct(const TechniqueCreateInfo& ci, DeferredGi& frame) : scene_gpu_(ci.scene_gpu) {
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
    ao_falloff_ = float(p.get("ao_falloff"));
    if (p.get_int("ao") != 0) ao_ = &frame.add_layer("ao");

    // The cube around the scene's bounds at creation, one voxel of margin on each side so
    // that surfaces on the bounds are inside it. Geometry that moves out of it is not
    // voxelised (docs/techniques/vct.md).
    const CubeGrid fitted = fit_cube_grid(ci.scene.bounds, resolution_);
    const float voxel = fitted.cell;
    grid_.origin = glm::vec4(fitted.origin, voxel);
    grid_.resolution = resolution_;
    grid_.levels = chain_levels(resolution_);
    // Shadow rays leave the surface by a thousandth of a voxel: far above float rounding at
    // the scene's scale, far below any feature the voxels resolve.
    ray_offset_ = 1e-3f * voxel;

    base_ = Image(ci.ctx, volume_desc(resolution_, 1));
    for (auto& c : chains_) c = Image(ci.ctx, volume_desc(resolution_ / 2, grid_.levels));
    volume_sampler_ = Sampler::trilinear_transparent(ci.ctx, float(grid_.levels));
    emitters_ = voxel_emitters(ci.scene);
    emitter_buffer_ =
        Buffer(ci.ctx, std::max<uint64_t>(16, emitters_.size() * sizeof(gpu::VctEmitter)),
               VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload);
    upload_emitters();
    scale_ = voxel_radiance_scale(ci.scene, emitters_, int(bounces_), grid_.origin.w, scene_gpu_.particle_light_distances());

    const auto defines = feature_defines(ci.scene.features);
    clear_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxel_clear.comp"),
                               {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE}, 0);
    auto scene_bindings = SceneGpu::binding_types();
    auto b = scene_bindings;
    b.push_back(VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    voxelize_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxelize.comp", defines), b,
                          sizeof(gpu::VctVoxelizePush));
    b.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    b.insert(b.end(), 6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    light_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxel_light.comp", defines),
                          b, sizeof(gpu::VctLightPush));
    std::vector<VkDescriptorType> mb(1 + 6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    mb.insert(mb.end(), 6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    mip_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/voxel_mip.comp", defines),
                             mb, sizeof(gpu::VctMipPush));
    b = GBufferPass::receiver_bindings();
    b.insert(b.end(), 7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    b.insert(b.end(), 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    cone_ =
        Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/vct/cone_trace.comp", defines), b,
                          sizeof(gpu::VctConePush));
  }

  void record(const FrameInput& in, DeferredGi& frame) override {
    if (in.frame == 0 || in.change != SceneChange::None) {
      if (in.frame == 0 || in.change == SceneChange::Geometry) {
        emitters_ = voxel_emitters(in.scene);
        upload_emitters();
      }
      scale_ = voxel_radiance_scale(in.scene, emitters_, int(bounces_), grid_.origin.w, scene_gpu_.particle_light_distances());
    }
    for (uint32_t b = 0; b < bounces_; ++b) record_voxels(in, b);
    record_cones(in, frame);
  }

 private:
  gpu::VctCone cone(float max_distance) const {
    gpu::VctCone c{};
    c.aperture = aperture_;
    c.max_distance = max_distance;
    c.step_factor = step_factor_;
    c.start_offset = start_offset_;
    c.guard = guard_;
    c.ao_falloff = ao_falloff_;
    c.count = cone_count_;
    return c;
  }
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
    for (auto& c : chains_) c.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    in.timer.begin(cmd, bounce_pass("voxelize", bounce));
    base_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    clear_.bind(cmd);
    clear_.push_descriptors(cmd, {Descriptor::storage_image(base_, 0)});
    const uint32_t groups = (resolution_ + 3) / 4;
    vkCmdDispatch(cmd, groups, groups, groups);
    full_barrier(cmd);
    gpu::VctVoxelizePush vp{};
    vp.grid = grid_;
    const uint32_t triangles = scene_gpu_.triangle_count();
    vp.triangle_count = triangles;
    // Workgroups (of 64 threads) per triangle: enough that a few large triangles (a room's
    // walls, each covering up to resolution^2 columns) spread over about 2048 workgroups, so a
    // GPU of a hundred multiprocessors is busy (8 per triangle left an H100 at 1.3 ms for
    // the Cornell box's 32 triangles); with many triangles, each small, one is plenty.
    const uint32_t slices = std::clamp<uint32_t>(2048u / std::max(triangles, 1u), 1u, 256u);
    if (triangles > 0) {
      voxelize_.bind(cmd);
      auto d = scene_gpu_.descriptors();
      d.push_back(Descriptor::storage_image(base_, 0));
      voxelize_.push_descriptors(cmd, d);
      voxelize_.push_constants(cmd, vp);
      const uint32_t gx = std::min(triangles, kMaxGroupsX), gy = (triangles + gx - 1) / gx;
      vkCmdDispatch(cmd, gx, gy, slices);
    }
    full_barrier(cmd);
    in.timer.end(cmd);

    in.timer.begin(cmd, bounce_pass("voxel_light", bounce));
    light_.bind(cmd);
    auto d = scene_gpu_.descriptors();
    d.push_back(Descriptor::storage_image(base_, 0));
    d.push_back(Descriptor::storage(emitter_buffer_));
    for (auto& c : chains_) d.push_back(Descriptor::sampled(c, volume_sampler_));
    light_.push_descriptors(cmd, d);
    gpu::VctLightPush lp{};
    lp.grid = grid_;
    lp.cone = cone(max_distance_ * grid_.origin.w * float(resolution_));
    lp.light_count = scene_gpu_.light_count();
    lp.emitter_count = uint32_t(emitters_.size());
    lp.scale = scale_;
    lp.ray_offset = ray_offset_;
    lp.add_bounce = bounce > 0 ? 1u : 0u;
    light_.push_constants(cmd, lp);
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
    for (uint32_t level = 0; level < grid_.levels; ++level) {
      std::vector<Descriptor> md = {Descriptor::sampled(base_, volume_sampler_)};
      for (auto& c : chains_) md.push_back(Descriptor::sampled(c, volume_sampler_));
      for (auto& c : chains_) md.push_back(Descriptor::storage_image(c, level));
      mip_.push_descriptors(cmd, md);
      gpu::VctMipPush mp{};
      mp.grid = grid_;
      mp.level = level;
      mp.blend = level == 0 && blend ? 1u : 0u;
      mp.new_weight = 1.0f - history_;
      mip_.push_constants(cmd, mp);
      const uint32_t n = ((resolution_ >> (level + 1)) + 3) / 4;
      vkCmdDispatch(cmd, n, n, n);
      full_barrier(cmd);
    }
    in.timer.end(cmd);
  }

  void record_cones(const FrameInput& in, DeferredGi& frame) {
    VkCommandBuffer cmd = in.cmd;
    Image& target = frame.indirect_target();
    in.timer.begin(cmd, "cone_trace");
    target.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    if (ao_) ao_->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    cone_.bind(cmd);
    auto d = frame.gbuffer().receiver_descriptors();
    d.push_back(Descriptor::sampled(base_, volume_sampler_));
    for (auto& c : chains_) d.push_back(Descriptor::sampled(c, volume_sampler_));
    d.push_back(Descriptor::storage_image(target));
    d.push_back(Descriptor::storage_image(ao_ ? *ao_ : target));
    cone_.push_descriptors(cmd, d);
    gpu::VctConePush pc{};
    pc.eye = gpu::gpu_eye(in.camera);
    pc.grid = grid_;
    const float side = grid_.origin.w * float(resolution_);
    pc.cone = cone(max_distance_ * side);
    pc.size = glm::uvec2(frame.width(), frame.height());
    pc.low_size = glm::uvec2(frame.target_width(), frame.target_height());
    pc.decode_scale = 1.0f / scale_;
    pc.factor = frame.factor();
    pc.ao = ao_ ? 1u : 0u;
    cone_.push_constants(cmd, pc);
    cone_.dispatch_2d(cmd, frame.target_width(), frame.target_height());
    full_barrier(cmd);
    in.timer.end(cmd);
  }

  const SceneGpu& scene_gpu_;
  uint32_t resolution_ = 256, cone_count_ = 6, bounces_ = 1;
  float aperture_ = 0.577f, max_distance_ = 1.0f, step_factor_ = 0.5f, start_offset_ = 1.0f;
  float history_ = 0.0f, ao_falloff_ = 0.0f, ray_offset_ = 0.0f, guard_ = 1.5f;
  Image* ao_ = nullptr;  // the frame's "ao" layer when the parameter asks for it
  gpu::VctGrid grid_{};
  // The base level and the six anisotropic chains (volume_desc()).
  Image base_;
  std::array<Image, 6> chains_;
  Sampler volume_sampler_;
  std::vector<gpu::VctEmitter> emitters_;
  Buffer emitter_buffer_;
  float scale_ = 1.0f, history_scale_ = 0.0f;
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
       "diffuse cones' tan(half angle); tan 30 deg in Afanasev 2021"},
      {"max_distance", 1.0, 0.01, 2.0, false,
       "cone length, as a fraction of the voxel cube's side"},
      {"step_factor", 0.5, 0.1, 2.0, false,
       "march step as a fraction of the cone's diameter there"},
      {"start_offset", 1.0, 0.0, 4.0, false, "cone apex offset along the normal, in base voxels"},
      {"footprint_guard", 1.5, 0.0, 4.0, false,
       "cap on the sampled cell size: distance from the surface / guard, so that no cone sees "
       "behind its "
       "surface (0: Afanasev 2021's log2(diameter / voxel))"},
      {"bounces", 1, 1, 4, true,
       "diffuse bounces: 1 as Afanasev 2021; each more re-voxelises and cone-traces from every voxel "
       "(Turánszki 2017)"},
      {"temporal_blend", 0.0, 0.0, 0.95, false,
       "weight of the previous frame's voxels (0: re-voxelised from scratch every frame)"},
      {"ao", 0, 0, 1, true,
       "1: also output the cones' ambient occlusion (occluded share, 0 = open) as layer 'ao'"},
      {"ao_falloff", 0.05, 0.0, 10.0, false,
       "AO attenuation with cone diameter (per voxel), Afanasev 2021's AOFalloff"},
  };
  FrameNeeds needs;
  needs.downsample = 2;
  return deferred_technique<Vct>(
      "vct",
      "voxel cone tracing: conservative compute voxelisation of albedo x shadowed direct light, 6 anisotropic mip "
      "chains, 6 diffuse cones + 1 specular cone at 1/k resolution, edge-aware upsample",
      needs, std::move(parameters), {"voxel_resolution", {16, 32, 64, 128, 256}});
}

}  // namespace giq::realtime
