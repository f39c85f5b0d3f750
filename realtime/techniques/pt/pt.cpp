// `pt`: one compute pass per frame that adds samples_per_frame paths per pixel to running
// sums and writes the means; the sums restart when the scene or the camera moves. Parameters:
// samples_per_frame, max_bounces, seed. It is the one technique outside the deferred frame
// (passes/deferred_gi.h): it traces its own camera rays, so its direct light comes from the
// same paths as its indirect light (the reference's split), not from the shared direct pass,
// and it needs no G-buffer.
#include "giq/realtime/technique.h"

#include "giq/realtime/context.h"
#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "techniques/pt/pt_shared.h"

namespace giq::realtime {
namespace {

class PathTracer : public Technique {
 public:
  explicit PathTracer(const TechniqueCreateInfo& ci)
      : scene_gpu_(ci.scene_gpu), width_(ci.width), height_(ci.height) {
    spp_ = uint32_t(ci.parameters.get_int("samples_per_frame"));
    max_bounces_ = uint32_t(ci.parameters.get_int("max_bounces"));
    seed_ = uint32_t(ci.parameters.get_int("seed"));
    ImageDesc d{width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT};
    for (Image* img : {&sum_direct_, &sum_indirect_, &sum_square_, &beauty_, &direct_, &indirect_, &variance_})
      *img = Image(ci.ctx, d);
    auto bindings = SceneGpu::binding_types();
    bindings.insert(bindings.end(), 7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    pipeline_ = Pipeline::compute(ci.ctx, ci.compiler.compile("techniques/pt/pt.comp", feature_defines(ci.scene.features)),
                                  bindings, sizeof(gpu::PtPush));
  }

  void render(const FrameInput& in) override {
    if (in.frame == 0)
      for (Image* img : images()) img->transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
    // Samples of a scene that has since moved belong to another image: start again, with new
    // random numbers so that consecutive restarts do not repeat the same noise.
    if (in.frame == 0 || in.change != SceneChange::None || in.camera.position != camera_.position ||
        in.camera.forward != camera_.forward || in.camera.up != camera_.up || in.camera.yfov != camera_.yfov ||
        in.camera.ymag != camera_.ymag) {
      accumulated_ = 0;
      ++restarts_;
    }
    camera_ = in.camera;
    gpu::PtPush pc{};
    pc.camera = gpu::make_gpu_camera(in.camera);
    pc.environment = glm::vec4(in.scene.environment, float(in.scene.environment_map));
    pc.width = width_;
    pc.height = height_;
    pc.samples_per_frame = 1;
    pc.max_bounces = max_bounces_;
    pc.emissive_count = scene_gpu_.emissive_count();
    pc.light_count = scene_gpu_.light_count();
    // 0x9E3779B9: the golden-ratio increment, so restart r's seeds are far from restart r-1's.
    pc.seed = seed_ + 0x9E3779B9u * (restarts_ - 1);
    in.timer.begin(in.cmd, "path_trace");
    pipeline_.bind(in.cmd);
    auto d = scene_gpu_.descriptors();
    for (Image* img : images()) d.push_back(Descriptor::storage_image(*img));
    pipeline_.push_descriptors(in.cmd, d);
    // One dispatch per sample: a shader invocation never runs more than one path. lavapipe
    // (llvmpipe) ends any loop after 65535 iterations per invocation to guard against hangs,
    // which silently cut BVH traversals short when one invocation traced hundreds of paths.
    for (uint32_t k = 0; k < spp_; ++k) {
      pc.first_sample = accumulated_ + k;
      pipeline_.push_constants(in.cmd, pc);
      pipeline_.dispatch_2d(in.cmd, width_, height_);
      full_barrier(in.cmd);
    }
    accumulated_ += spp_;
    in.timer.end(in.cmd);
  }

  std::vector<std::pair<std::string, Image*>> outputs() override {
    return {{"", &beauty_}, {"direct", &direct_}, {"indirect", &indirect_}, {"variance", &variance_}};
  }

 private:
  std::vector<Image*> images() {
    return {&sum_direct_, &sum_indirect_, &sum_square_, &beauty_, &direct_, &indirect_, &variance_};
  }
  const SceneGpu& scene_gpu_;
  uint32_t width_, height_, spp_ = 1, max_bounces_ = 64, seed_ = 0;
  uint32_t accumulated_ = 0, restarts_ = 0;  // samples per pixel since the last restart
  scenes::Camera camera_;                    // of the previous frame
  Image sum_direct_, sum_indirect_, sum_square_, beauty_, direct_, indirect_, variance_;
  Pipeline pipeline_;
};

}  // namespace

TechniqueInfo pt_technique() {
  return {"pt",
          "GPU progressive path tracer (NEE + MIS, the reference's BRDF and light sampling); accumulates across frames",
          {{"samples_per_frame", 1, 1, 1024, true, "paths per pixel added each frame"},
           {"max_bounces", 64, 1, 1024, true, "surface interactions after the camera ray; Russian roulette after 3"},
           {"seed", 0, 0, 2147483647, true, "random sequence; same seed, same image"}},
          {"samples_per_frame", {1, 2, 4, 8, 16}},
          [](const TechniqueCreateInfo& ci) { return std::make_unique<PathTracer>(ci); },
          /*lights_with_environment=*/true};
}

}  // namespace giq::realtime
