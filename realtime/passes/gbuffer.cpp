#include "passes/gbuffer.h"

#include "giq/realtime/context.h"
#include "giq/realtime/raster.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "passes/gbuffer_shared.h"

namespace giq::realtime {

Parameter GBufferPass::ray_traced_parameter() {
  return pass_builder_parameter("gbuffer_ray_traced", "G-buffer");
}

GBufferPass::GBufferPass(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene,
                         const scenes::FeatureSet& features, uint32_t width, uint32_t height, PassBuilder builder)
    : scene_(scene), width_(width), height_(height),
      ray_traced_(casts_rays(builder, ctx)),
      compiler_(compiler), ctx_(ctx) {
  const VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
  position_ = Image(ctx, {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, color});
  normal_ = Image(ctx, {width, height, 1, VK_FORMAT_R32G32B32A32_SFLOAT, color});
  ids_ = Image(ctx, {width, height, 1, VK_FORMAT_R32G32B32A32_UINT, color});
  depth_ = Image(ctx, {width, height, 1, VK_FORMAT_D32_SFLOAT, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
  const auto defines = feature_defines(features);
  if (ray_traced_) {
    auto bindings = SceneGpu::binding_types();
    bindings.insert(bindings.end(), 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    pipeline_ = Pipeline::compute(ctx, compiler.compile("passes/gbuffer_rays.comp", defines), bindings,
                                  sizeof(gpu::GBufferPush));
    return;
  }
  GraphicsDesc g;
  g.vertex_spirv = compiler.compile("passes/gbuffer.vert", defines);
  g.fragment_spirv = compiler.compile("passes/gbuffer.frag", defines);
  g.color_formats = {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32G32B32A32_UINT};
  g.depth_format = VK_FORMAT_D32_SFLOAT;
  pipeline_ = Pipeline::graphics(ctx, g, SceneGpu::binding_types(), sizeof(gpu::GBufferPush));
}

GBufferPass::GBufferPass(const TechniqueCreateInfo& ci)
    : GBufferPass(ci.ctx, ci.compiler, ci.scene_gpu, ci.scene.features, ci.width, ci.height,
                  pass_builder(ci.parameters, "gbuffer_ray_traced")) {}

std::vector<VkDescriptorType> GBufferPass::receiver_bindings() {
  auto b = SceneGpu::binding_types();
  b.insert(b.end(), 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  return b;
}

std::vector<Descriptor> GBufferPass::receiver_descriptors() {
  auto d = scene_.descriptors();
  for (Image* i : {&position_, &normal_, &ids_}) d.push_back(Descriptor::storage_image(*i));
  return d;
}

void GBufferPass::record(VkCommandBuffer cmd, const scenes::Camera& camera, GpuTimer& timer) {
  // A camera without a near plane (znear 0) would map every depth to 1; 1 mm keeps the
  // rasteriser working at every scene scale the tests use.
  const float znear = camera.znear > 0.0f ? camera.znear : 1e-3f;
  // An orthographic depth is linear from the near plane to the scene's farthest point (the
  // reference sees everything in front of the camera, so no far plane may clip it).
  float zscale = 0.0f;
  if (camera.orthographic() && !scene_.bounds().empty()) {
    const scenes::Bounds& b = scene_.bounds();
    float far_d = 0.0f;
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner((i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z);
      far_d = std::max(far_d, glm::dot(corner - camera.position, camera.forward));
    }
    zscale = 1.0f / std::max(1.001f * (far_d - znear), znear);
  }
  const gpu::GBufferPush pc{gpu::make_gpu_camera(camera), glm::vec2(float(width_), float(height_)), znear, zscale};
  timer.begin(cmd, "gbuffer");
  if (ray_traced_) {
    for (Image* i : {&position_, &normal_, &ids_}) i->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
    pipeline_.bind(cmd);
    auto d = scene_.descriptors();
    for (Image* i : {&position_, &normal_, &ids_}) d.push_back(Descriptor::storage_image(*i));
    pipeline_.push_descriptors(cmd, d);
    pipeline_.push_constants(cmd, pc);
    pipeline_.dispatch_2d(cmd, width_, height_);
    full_barrier(cmd);
    timer.end(cmd);
    record_motion(cmd, camera, timer);
    return;
  }
  for (Image* i : {&position_, &normal_, &ids_}) i->transition(cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  depth_.transition(cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  begin_rendering(cmd, width_, height_, {{position_.view(), normal_.view(), ids_.view()}, depth_.view(), false});
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, scene_.descriptors());
  pipeline_.push_constants(cmd, pc);
  draw_scene(cmd, scene_);
  vkCmdEndRendering(cmd);
  for (Image* i : {&position_, &normal_, &ids_}) i->transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  timer.end(cmd);
  record_motion(cmd, camera, timer);
}

void GBufferPass::enable_motion_vectors() {
  if (motion_) return;
  motion_ = Image(ctx_, {width_, height_, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_IMAGE_USAGE_STORAGE_BIT});
  auto bindings = SceneGpu::binding_types();
  bindings.insert(bindings.end(), {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
                                   VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE});
  motion_pipeline_ = Pipeline::compute(ctx_, compiler_.compile("passes/motion_vectors.comp"), bindings,
                                       sizeof(gpu::MotionPush));
}

void GBufferPass::record_motion(VkCommandBuffer cmd, const scenes::Camera& camera, GpuTimer& timer) {
  const scenes::Camera previous = has_previous_camera_ ? previous_camera_ : camera;
  previous_camera_ = camera;
  has_previous_camera_ = true;
  if (!motion_) return;
  timer.begin(cmd, "motion_vectors");
  motion_.transition(cmd, VK_IMAGE_LAYOUT_GENERAL);
  motion_pipeline_.bind(cmd);
  auto d = scene_.descriptors();
  d.push_back(Descriptor::storage(scene_.previous_vertices()));
  d.push_back(Descriptor::storage_image(position_));
  d.push_back(Descriptor::storage_image(ids_));
  d.push_back(Descriptor::storage_image(motion_));
  motion_pipeline_.push_descriptors(cmd, d);
  motion_pipeline_.push_constants(cmd, gpu::MotionPush{gpu::make_gpu_camera(camera), gpu::make_gpu_camera(previous)});
  motion_pipeline_.dispatch_2d(cmd, width_, height_);
  full_barrier(cmd);
  timer.end(cmd);
}

}  // namespace giq::realtime
