#include "techniques/hybrid/svgf.h"

#include <algorithm>
#include <string>

#include "giq/realtime/context.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer.h"
#include "techniques/hybrid/svgf_shared.h"

namespace giq::realtime {

std::vector<Parameter> Svgf::parameters() {
  const SvgfSettings d;
  return {{"iterations", double(d.iterations), 0, 10, true, "a-trous iterations of the 5x5 kernel, step 2^i (0: no spatial filter)"},
          {"feedback_tap", double(d.feedback_tap), -1, 9, true,
           "the a-trous iteration whose output is next frame's history (-1: the unfiltered temporal mean)"},
          {"phi_colour", double(d.phi_colour), 0.01, 1000, false,
           "luminance edge-stopping, in standard deviations of the pixel's luminance"},
          {"phi_normal", double(d.phi_normal), 1, 1024, false, "normal edge-stopping: the power of the normals' cosine"},
          {"alpha_colour", double(d.alpha_colour), 0, 1, false,
           "weight of the new frame in the colour's moving average (at least 1/history)"},
          {"alpha_moments", double(d.alpha_moments), 0, 1, false,
           "weight of the new frame in the luminance moments' moving average (at least 1/history)"},
          {"history_cap", double(d.history_cap), 1, 4096, true, "frames the history length stops growing at"}};
}

SvgfSettings Svgf::settings(const ParameterValues& v) {
  SvgfSettings s;
  s.iterations = v.get_int("iterations");
  s.feedback_tap = v.get_int("feedback_tap");
  s.phi_colour = float(v.get("phi_colour"));
  s.phi_normal = float(v.get("phi_normal"));
  s.alpha_colour = float(v.get("alpha_colour"));
  s.alpha_moments = float(v.get("alpha_moments"));
  s.history_cap = v.get_int("history_cap");
  return s;
}

Svgf::Svgf(Context& ctx, ShaderCompiler& compiler, uint32_t width, uint32_t height, const SvgfSettings& settings)
    : width_(width), height_(height), settings_(settings) {
  auto image = [&](VkFormat f) { return Image(ctx, {width, height, 1, f, VK_IMAGE_USAGE_STORAGE_BIT}); };
  const VkFormat rgba = VK_FORMAT_R32G32B32A32_SFLOAT;
  for (int i = 0; i < 2; ++i) {
    surface_[i] = image(rgba);
    object_[i] = image(VK_FORMAT_R32_UINT);
    moments_[i] = image(rgba);
    length_[i] = image(VK_FORMAT_R32_SFLOAT);
    ping_direct_[i] = image(rgba);
    ping_indirect_[i] = image(rgba);
  }
  history_direct_ = image(rgba);
  history_indirect_ = image(rgba);
  integrated_direct_ = image(rgba);
  integrated_indirect_ = image(rgba);

  const auto img = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  reproject_ = Pipeline::compute(ctx, compiler.compile("techniques/hybrid/svgf_reproject.comp"),
                                 std::vector<VkDescriptorType>(20, img), sizeof(gpu::SvgfReprojectPush));
  variance_ = Pipeline::compute(ctx, compiler.compile("techniques/hybrid/svgf_variance.comp"),
                                std::vector<VkDescriptorType>(9, img), sizeof(gpu::SvgfFilterPush));
  atrous_ = Pipeline::compute(ctx, compiler.compile("techniques/hybrid/svgf_atrous.comp"),
                              std::vector<VkDescriptorType>(7, img), sizeof(gpu::SvgfFilterPush));
  modulate_ = Pipeline::compute(ctx, compiler.compile("techniques/hybrid/svgf_modulate.comp"),
                                std::vector<VkDescriptorType>(8, img), sizeof(gpu::SvgfModulatePush));
}

std::vector<Image*> Svgf::images() {
  std::vector<Image*> all = {&history_direct_, &history_indirect_, &integrated_direct_, &integrated_indirect_};
  for (auto* pair : {&surface_, &object_, &moments_, &length_, &ping_direct_, &ping_indirect_})
    for (Image& i : *pair) all.push_back(&i);
  return all;
}

void Svgf::atrous(VkCommandBuffer cmd, Image& surface, Image& in_direct, Image& in_indirect, Image& out_direct,
                  Image& out_indirect, int step, bool feedback) {
  gpu::SvgfFilterPush pc{};
  pc.size = {width_, height_};
  pc.step = step;
  pc.feedback = feedback ? 1u : 0u;
  pc.phi_colour = settings_.phi_colour;
  pc.phi_normal = settings_.phi_normal;
  atrous_.bind(cmd);
  atrous_.push_descriptors(cmd, {Descriptor::storage_image(surface), Descriptor::storage_image(in_direct),
                                 Descriptor::storage_image(in_indirect), Descriptor::storage_image(out_direct),
                                 Descriptor::storage_image(out_indirect), Descriptor::storage_image(history_direct_),
                                 Descriptor::storage_image(history_indirect_)});
  atrous_.push_constants(cmd, pc);
  atrous_.dispatch_2d(cmd, width_, height_);
  compute_barrier(cmd);
}

void Svgf::record_atrous(VkCommandBuffer cmd, Image& surface, Image& in_direct, Image& in_indirect,
                         Image& out_direct, Image& out_indirect, int step) {
  for (Image* i : images()) i->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  atrous(cmd, surface, in_direct, in_indirect, out_direct, out_indirect, step, false);
  full_barrier(cmd);
}

void Svgf::record(VkCommandBuffer cmd, const Frame& f, GBufferPass& gbuffer, const scenes::Camera& camera,
                  bool restart, GpuTimer& timer) {
  if (restart) has_previous_ = false;
  if (!has_previous_)
    for (Image* i : images()) i->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  const int cur = current_, prev = 1 - current_;
  const glm::uvec2 size{width_, height_};

  timer.begin(cmd, "svgf_reproject");
  gpu::SvgfReprojectPush rp{};
  const scenes::Camera& before = has_previous_ ? previous_ : camera;
  rp.eye = glm::vec4(camera.position, 1.0f);
  rp.forward = glm::vec4(camera.forward, 0.0f);
  rp.previous_eye = glm::vec4(before.position, 1.0f);
  rp.previous_forward = glm::vec4(before.forward, 0.0f);
  rp.size = size;
  rp.alpha_colour = settings_.alpha_colour;
  rp.alpha_moments = settings_.alpha_moments;
  rp.history_cap = float(settings_.history_cap);
  rp.history = has_previous_ ? 1u : 0u;
  reproject_.bind(cmd);
  reproject_.push_descriptors(
      cmd, {Descriptor::storage_image(gbuffer.position()), Descriptor::storage_image(gbuffer.normal()),
            Descriptor::storage_image(gbuffer.ids()), Descriptor::storage_image(gbuffer.motion()),
            Descriptor::storage_image(f.direct), Descriptor::storage_image(f.indirect),
            Descriptor::storage_image(f.unfiltered), Descriptor::storage_image(f.albedo),
            Descriptor::storage_image(surface_[cur]), Descriptor::storage_image(object_[cur]),
            Descriptor::storage_image(surface_[prev]), Descriptor::storage_image(object_[prev]),
            Descriptor::storage_image(history_direct_), Descriptor::storage_image(history_indirect_),
            Descriptor::storage_image(moments_[prev]), Descriptor::storage_image(moments_[cur]),
            Descriptor::storage_image(length_[prev]), Descriptor::storage_image(length_[cur]),
            Descriptor::storage_image(integrated_direct_), Descriptor::storage_image(integrated_indirect_)});
  reproject_.push_constants(cmd, rp);
  reproject_.dispatch_2d(cmd, width_, height_);
  compute_barrier(cmd);
  timer.end(cmd);

  // Falcor's choice of history: the output of iteration min(tap, iterations - 1), or the
  // unfiltered temporal mean (written by the variance pass) for a negative tap or none.
  const int tap = std::min(settings_.feedback_tap, settings_.iterations - 1);
  timer.begin(cmd, "svgf_variance");
  gpu::SvgfFilterPush vp{};
  vp.feedback = tap < 0 ? 1u : 0u;
  vp.size = size;
  vp.step = 1;
  vp.phi_colour = settings_.phi_colour;
  vp.phi_normal = settings_.phi_normal;
  variance_.bind(cmd);
  variance_.push_descriptors(cmd, {Descriptor::storage_image(surface_[cur]), Descriptor::storage_image(integrated_direct_),
                                   Descriptor::storage_image(integrated_indirect_), Descriptor::storage_image(moments_[cur]),
                                   Descriptor::storage_image(length_[cur]), Descriptor::storage_image(ping_direct_[0]),
                                   Descriptor::storage_image(ping_indirect_[0]), Descriptor::storage_image(history_direct_),
                                   Descriptor::storage_image(history_indirect_)});
  variance_.push_constants(cmd, vp);
  variance_.dispatch_2d(cmd, width_, height_);
  compute_barrier(cmd);
  timer.end(cmd);

  int in = 0;
  for (int i = 0; i < settings_.iterations; ++i) {
    timer.begin(cmd, "svgf_atrous_" + std::to_string(i));
    atrous(cmd, surface_[cur], ping_direct_[in], ping_indirect_[in], ping_direct_[1 - in], ping_indirect_[1 - in],
           1 << i, i == tap);
    timer.end(cmd);
    in = 1 - in;
  }

  timer.begin(cmd, "svgf_modulate");
  f.out_direct.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  f.out_indirect.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  f.out_history.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  modulate_.bind(cmd);
  modulate_.push_descriptors(cmd, {Descriptor::storage_image(ping_direct_[in]), Descriptor::storage_image(ping_indirect_[in]),
                                   Descriptor::storage_image(f.albedo), Descriptor::storage_image(f.unfiltered),
                                   Descriptor::storage_image(length_[cur]), Descriptor::storage_image(f.out_direct),
                                   Descriptor::storage_image(f.out_indirect), Descriptor::storage_image(f.out_history)});
  gpu::SvgfModulatePush mp{};
  mp.size = size;
  modulate_.push_constants(cmd, mp);
  modulate_.dispatch_2d(cmd, width_, height_);
  full_barrier(cmd);
  timer.end(cmd);

  current_ = prev;
  previous_ = camera;
  has_previous_ = true;
}

}  // namespace giq::realtime
