#include "giq/realtime/renderer.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "giq/base/error.h"
#include "giq/base/version.h"
#include "giq/realtime/context.h"
#include "giq/realtime/pass_builder.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/technique.h"

namespace giq::realtime {

image::Image read_outputs(Technique& technique, uint32_t width, uint32_t height) {
  image::Image out{int(width), int(height)};
  for (auto& [layer, img] : technique.outputs()) {
    const std::vector<float> rgba = img->read_floats();
    const std::string prefix = layer.empty() ? "" : layer + ".";
    const char* names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      float* dst = out.add_channel(prefix + names[c]);
      for (size_t i = 0; i < out.pixel_count(); ++i) dst[i] = rgba[4 * i + c];
    }
  }
  return out;
}

nlohmann::json render_sequence(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene,
                               const RenderOptions& options, const std::function<void(RenderedFrame&)>& on_frame) {
  const TechniqueInfo& info = find_technique(options.technique);
  const ParameterValues params(info.parameters, options.parameters);
  const uint32_t max_side = std::min<uint32_t>(16384, ctx.properties().limits.maxImageDimension2D);
  if (options.width < 1 || options.height < 1 || options.width > max_side || options.height > max_side)
    throw InputError("", "--width/--height", "resolution " + std::to_string(options.width) + "x" +
                                                 std::to_string(options.height) + " is outside 1.." +
                                                 std::to_string(max_side) + " (this device's largest image side)");
  if (options.frames < 1) throw InputError("", "--frames", std::to_string(options.frames) + " frames; expected at least 1");
  if (options.warmup < 0) throw InputError("", "--warmup", std::to_string(options.warmup) + "; expected 0 or more");
  const scenes::View& view0 = scene.view(options.view);  // throws InputError naming the views
  const std::string view_name = view0.name;

  GpuTimer timer(ctx);
  // One technique instance for the whole sequence, so temporal techniques keep their history:
  // an animated scene is posed per frame into `posed` (which the technique holds by
  // reference) and the GPU scene is updated in place; the technique learns what moved. The
  // GPU places the particles, so the pose only counts them, and the GPU scene completes it.
  scenes::Scene posed = scene.features.animation ? scene.at_frame(0, scenes::ParticleDetail::Counted) : scene;
  // Device memory the scene and the technique keep resident (sub-allocated bytes, so what
  // the resources need, not the 64 MiB blocks around them); measured after the first frame,
  // since passes may create resources when they first record.
  const uint64_t memory_before = ctx.allocator().bytes_in_use();
  if (options.on_progress) options.on_progress(-1);
  SceneGpu scene_gpu(ctx, compiler, posed);
  scene_gpu.complete(posed);
  const uint64_t memory_scene = ctx.allocator().bytes_in_use();
  std::unique_ptr<Technique> technique =
      info.create({ctx, compiler, posed, scene_gpu, options.width, options.height, params});
  uint64_t memory_technique = 0;
  std::vector<FrameTiming> timings;
  int technique_frame = 0;
  const int total = options.warmup + options.frames;
  for (int f = 0; f < total; ++f) {
    SceneChange change = SceneChange::None;
    if (f > 0 && scene.features.animation) {
      scene.at(f / scene.sequence.fps, scenes::ParticleDetail::Counted, posed);
      change = scene_gpu.update(posed);
      scene_gpu.complete(posed);
    }
    const scenes::Camera camera = posed.view(view_name).camera;
    FrameTiming t;
    t.frame = f;
    t.warmup = f < options.warmup;
    const auto start = std::chrono::steady_clock::now();
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      technique->render({cmd, technique_frame, camera, timer, posed, change});
    });
    t.cpu_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (f == 0) memory_technique = ctx.allocator().bytes_in_use() - memory_scene;
    t.passes = timer.resolve();
    t.gpu_ms = timer.frame_ms();
    timings.push_back(t);
    ++technique_frame;
    if (t.warmup) {
      if (options.on_progress) options.on_progress(f + 1);
      continue;
    }

    RenderedFrame out;
    out.frame = f;
    out.timing = t;
    if (options.read_back) out.image = read_outputs(*technique, options.width, options.height);
    nlohmann::json pj = params.all();
    out.image.metadata = {{"giq.version", version()},
                          {"giq.renderer", "realtime"},
                          {"giq.technique", info.name},
                          {"giq.parameters", pj.dump()},
                          {"giq.scene", scene.path.string()},
                          {"giq.scene_hash", scene.content_hash},
                          {"giq.view", view_name},
                          {"giq.frame", std::to_string(f)},
                          {"giq.technique_frame", std::to_string(technique_frame)},
                          {"giq.device", ctx.info().name},
                          {"giq.driver", ctx.info().driver},
                          {"giq.gpu_ms", std::to_string(t.gpu_ms)}};
    on_frame(out);
    if (options.on_progress) options.on_progress(f + 1);
  }

  nlohmann::json run = {
      {"giq_version", version()},
      {"technique", info.name},
      {"parameters", params.all()},
      {"builders", resolved_builders(info.parameters, params, ctx)},
      {"scene", scene.path.string()},
      {"scene_hash", scene.content_hash},
      {"view", view_name},
      {"resolution", {options.width, options.height}},
      {"device", {{"name", ctx.info().name}, {"driver", ctx.info().driver}, {"type", ctx.info().type},
                  {"vulkan", std::to_string(VK_API_VERSION_MAJOR(ctx.info().api_version)) + "." +
                                 std::to_string(VK_API_VERSION_MINOR(ctx.info().api_version)) + "." +
                                 std::to_string(VK_API_VERSION_PATCH(ctx.info().api_version))}}},
      {"gpu_memory_mb", {{"scene", double(memory_scene - memory_before) / (1 << 20)},
                         {"textures", double(scene_gpu.texture_bytes()) / (1 << 20)},  // part of "scene"
                         {"technique", double(memory_technique) / (1 << 20)}}},
      {"validation", ctx.validation_enabled()},
  };
  return timings_json(timings, run);
}

}  // namespace giq::realtime
