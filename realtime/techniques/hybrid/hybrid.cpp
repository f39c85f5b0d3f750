// `hybrid`: one-sample path tracing denoised by SVGF, the hybrid ray-traced pipeline of
// Kim-Chan 2022 (sections 2.2, 3.1, 5.3). On the shared G-buffer, one compute pass per frame
// (hybrid_sample.comp) draws at every pixel one shadow ray towards one randomly chosen light
// and one bounce ray from the diffuse or the GGX lobe, through the shared compute BVH with
// `pt`'s BRDF and light code (shaders/path.glsl); direct and indirect light are then
// denoised separately by SVGF (svgf.h). The technique computes its own direct light
// (FrameNeeds::own_direct): that light is part of what it samples and denoises.
// Parameters: bounces, samples_per_frame, denoise (0: the raw samples are the output), seed,
// and the filter's (Svgf::parameters). Extra layers with the denoiser on: raw_direct and
// raw_indirect (the undenoised samples) and history (frames in each pixel's history).
// docs/techniques/hybrid.md maps the papers' equations to this code.
#include <memory>
#include <string>

#include "giq/realtime/context.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/deferred_gi.h"
#include "techniques/hybrid/hybrid_shared.h"
#include "techniques/hybrid/svgf.h"

namespace giq::realtime {
namespace {

class Hybrid : public IndirectLight {
 public:
  Hybrid(const TechniqueCreateInfo& ci, DeferredGi& frame) : scene_gpu_(ci.scene_gpu) {
    const auto& p = ci.parameters;
    bounces_ = uint32_t(p.get_int("bounces"));
    spp_ = uint32_t(p.get_int("samples_per_frame"));
    seed_ = uint32_t(p.get_int("seed"));
    const ImageDesc full{frame.width(), frame.height(), 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT};
    unfiltered_ = Image(ci.ctx, full);
    albedo_ = Image(ci.ctx, full);
    if (p.get_int("denoise") != 0) {
      raw_direct_ = &frame.add_layer("raw_direct");
      raw_indirect_ = &frame.add_layer("raw_indirect");
      history_ = &frame.add_layer("history");
      svgf_ = std::make_unique<Svgf>(ci.ctx, ci.compiler, frame.width(), frame.height(), Svgf::settings(p));
    }
    auto defines = feature_defines(ci.scene.features);
    defines.push_back({"GIQ_ONE_LIGHT"});
    auto bindings = GBufferPass::receiver_bindings();
    bindings.insert(bindings.end(), 4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    sample_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/hybrid/hybrid_sample.comp", defines), bindings,
                                sizeof(gpu::HybridSamplePush));
  }

  void record(const FrameInput& in, DeferredGi& frame) override {
    VkCommandBuffer cmd = in.cmd;
    // Without the denoiser the samples are the output.
    Image& direct = svgf_ ? *raw_direct_ : frame.direct_target();
    Image& indirect = svgf_ ? *raw_indirect_ : frame.indirect_target();
    for (Image* i : {&direct, &indirect, &unfiltered_, &albedo_}) i->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);

    in.timer.begin(cmd, "hybrid_sample");
    gpu::HybridSamplePush pc{};
    pc.camera = gpu::make_gpu_camera(in.camera);
    pc.environment = glm::vec4(in.scene.environment, float(in.scene.environment_map));
    pc.size = {frame.width(), frame.height()};
    pc.max_bounces = bounces_ + 1;  // path vertices after the camera: the first hit and `bounces` more
    pc.light_count = scene_gpu_.light_count();
    pc.emissive_count = scene_gpu_.emissive_count();
    pc.samples = spp_;
    pc.first_sample = uint32_t(in.frame) * spp_;
    pc.seed = seed_;
    sample_.bind(cmd);
    auto d = frame.gbuffer().receiver_descriptors();
    for (Image* i : {&direct, &indirect, &unfiltered_, &albedo_}) d.push_back(Descriptor::storage_image(*i));
    sample_.push_descriptors(cmd, d);
    sample_.push_constants(cmd, pc);
    sample_.dispatch_2d(cmd, frame.width(), frame.height());
    full_barrier(cmd);
    in.timer.end(cmd);

    if (svgf_)
      svgf_->record(cmd,
                    {direct, indirect, unfiltered_, albedo_, frame.direct_target(), frame.indirect_target(), *history_},
                    frame.gbuffer(), in.camera, in.frame == 0, in.timer);
  }

 private:
  const SceneGpu& scene_gpu_;
  uint32_t bounces_ = 1, spp_ = 1, seed_ = 0;
  Image unfiltered_, albedo_;
  Image *raw_direct_ = nullptr, *raw_indirect_ = nullptr, *history_ = nullptr;  // the frame's layers
  std::unique_ptr<Svgf> svgf_;
  Pipeline sample_;
};

}  // namespace

TechniqueInfo hybrid_technique() {
  FrameNeeds needs;
  needs.own_direct = true;
  needs.motion_vectors = true;
  std::vector<Parameter> own = {
      {"bounces", 1, 1, 64, true,
       "surfaces the bounce ray's path visits after the first hit (1: one bounce, Kim-Chan 2022); Russian roulette "
       "after 3"},
      {"samples_per_frame", 1, 1, 16, true, "paths per pixel each frame (one shadow ray and one bounce ray each)"},
      {"denoise", 1, 0, 1, true, "1: SVGF; 0: the raw samples are the output"},
      {"seed", 0, 0, 2147483647, true, "random sequence; same seed, same image"}};
  for (auto& p : Svgf::parameters()) own.push_back(std::move(p));
  TechniqueInfo info = deferred_technique<Hybrid>(
      "hybrid",
      "1-sample path tracing (Kim-Chan 2022: one shadow ray to one random light, one bounce ray from the diffuse or "
      "GGX lobe) denoised by SVGF (Schied et al. 2017), direct and indirect light filtered separately",
      // The quality knob is the bounce count: with the history accumulating the samples, one
      // bounce's missing light, not noise, dominates the error (samples_per_frame 1 to 4 moves
      // FLIP on the Cornell box from 0.418 to 0.417; bounces 1 to 64 from 0.418 to 0.179:
      // bench/results/hybrid-h200.md).
      needs, std::move(own), {"bounces", {1, 2, 3, 4, 8}});
  info.lights_with_environment = true;  // bounce rays that miss see it
  return info;
}

}  // namespace giq::realtime
