#include "passes/rsm.h"

#include <algorithm>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

#include "giq/realtime/context.h"
#include "giq/realtime/raster.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/timer.h"
#include "giq/realtime/pass_builder.h"
#include "passes/shadow_maps.h"

namespace giq::realtime {

namespace {

float max3(glm::vec3 v) {
  return std::max(v.x, std::max(v.y, v.z));
}

// The layers and emitters the scene's lights need, in a fixed order: the scene's lights, then
// one area light per emissive mesh (as passes/direct_light.cpp builds them).
// An area light's emission lobe for rsm.frag: its mean normal, w 1 when double-sided; or, for
// a closed emitter, w 2: isotropic.
glm::vec4 area_emitter_normal(const scenes::AreaLight& a) {
  if (!a.flat) return glm::vec4(0.0f, 0.0f, 0.0f, 2.0f);
  return glm::vec4(a.normal, a.two_sided ? 1.0f : 0.0f);
}

void build(const scenes::Scene& scene, const FlatGeometry& geometry, uint32_t ortho_size, uint32_t cube_size,
           std::vector<gpu::GpuRsmEmitter>& emitters, std::vector<gpu::GpuRsmLayer>& layers) {
  emitters.clear();
  layers.clear();
  const scenes::Bounds& b = scene.bounds;
  const float diag = b.diagonal();
  const glm::vec3 c0 = b.centre();
  auto add_cube = [&](glm::vec3 position, glm::vec3 intensity) {
    const float emitter = float(emitters.size());
    for (int f = 0; f < 6; ++f)
      layers.push_back({ShadowMaps::cube_face_view_proj(position, b, f), glm::mat4(1.0f), glm::vec4(0.0f),
                        glm::vec4(GIQ_RSM_CUBE_FACE, float(cube_size), max3(intensity), emitter)});
  };
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const scenes::Light& l = scene.lights[i];
    const glm::vec3 radiant = l.radiant();
    gpu::GpuRsmEmitter e{glm::vec4(l.position, GIQ_RSM_PUNCTUAL), glm::vec4(0.0f),
                         glm::vec4(radiant, float(i)),
                         glm::uvec4(uint32_t(layers.size()), 0, 0, 0)};
    if (l.type == scenes::LightType::Directional) {
      // The scene's bounding sphere seen along the light, from outside it.
      const float r = 0.5f * diag;
      const glm::vec3 dir = glm::normalize(l.direction);
      const glm::vec3 up = std::abs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
      const glm::mat4 view = glm::lookAtRH(c0 - dir * (2.0f * r), c0, up);
      const glm::mat4 proj = glm::orthoRH_ZO(-r, r, -r, r, 0.0f, 4.0f * r);
      layers.push_back(
          {proj * view, glm::mat4(1.0f), glm::vec4(dir, 2.0f * r),
           glm::vec4(GIQ_RSM_ORTHO, float(ortho_size), max3(radiant), float(emitters.size()))});
      e.layers.y = 1;
    } else {
      add_cube(l.position, radiant);
      e.layers.y = 6;
    }
    emitters.push_back(e);
  }
  for (const scenes::AreaLight& a : scene.area_lights) {
    // The emitter's own triangles are left out of its cube (rsm.frag, own_geometry): from the
    // centre of a closed emitter they would be all it sees.
    const glm::uvec4 own = own_geometry(scene, geometry, a.mesh);
    gpu::GpuRsmEmitter e{glm::vec4(a.representative, GIQ_RSM_AREA), area_emitter_normal(a),
                         glm::vec4(a.intensity, 0.0f), glm::uvec4(uint32_t(layers.size()), 6, own.z, own.w)};
    add_cube(a.representative, a.intensity);
    emitters.push_back(e);
  }
  // The texel rays start on a layer's near plane: the matrix inverted in double, so that the
  // rays of a light far from the origin keep float's precision.
  for (gpu::GpuRsmLayer& l : layers) l.clip_to_world = glm::mat4(glm::inverse(glm::dmat4(l.view_proj)));
}

}  // namespace

std::vector<Parameter> ReflectiveShadowMaps::parameters() {
  return {{"rsm_size", 1024, 16, 8192, true,
           "RSM texels per side of a directional light's window over the scene"},
          {"rsm_cube_size", 512, 16, 4096, true,
           "RSM texels per side of each cube face (point, spot and area lights)"},
          pass_builder_parameter("rsm_ray_traced", "Reflective shadow maps'")};
}

ReflectiveShadowMaps::ReflectiveShadowMaps(const TechniqueCreateInfo& ci)
    : scene_gpu_(ci.scene_gpu),
      ortho_size_(uint32_t(ci.parameters.get_int("rsm_size"))),
      cube_size_(uint32_t(ci.parameters.get_int("rsm_cube_size"))),
      ray_traced_(casts_rays(pass_builder(ci.parameters, "rsm_ray_traced"), ci.ctx)) {
  build(ci.scene, scene_gpu_.geometry(), ortho_size_, cube_size_, emitters_, layers_);
  extent_ = 1;
  for (const auto& l : layers_) extent_ = std::max(extent_, uint32_t(l.params.y));
  const uint32_t n = std::max<uint32_t>(1, layer_count());
  const VkImageUsageFlags usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
  surface_ = Image(ci.ctx, {extent_, extent_, n, VK_FORMAT_R32G32B32A32_UINT, usage, true});
  flux_ = Image(ci.ctx, {extent_, extent_, n, VK_FORMAT_R16G16B16A16_SFLOAT, usage, true});
  layer_buffer_ = Buffer(ci.ctx, std::max<size_t>(1, layers_.size()) * sizeof(gpu::GpuRsmLayer),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload);
  emitter_buffer_ =
      Buffer(ci.ctx, std::max<size_t>(1, emitters_.size()) * sizeof(gpu::GpuRsmEmitter),
             VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload);

  const auto defines = feature_defines(ci.scene.features);
  auto bindings = SceneGpu::binding_types();
  bindings.insert(bindings.end(), 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);  // emitters, layers
  if (ray_traced_) {
    bindings.insert(bindings.end(), 2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
    pipeline_ = Pipeline::compute(ci.ctx, ci.compiler.compile("passes/rsm_rays.comp", defines), bindings,
                                  sizeof(gpu::RsmLayerPush));
    return;
  }
  // One depth buffer serves every layer in turn.
  depth_ = Image(ci.ctx, {extent_, extent_, 1, VK_FORMAT_D32_SFLOAT,
                          VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT});
  GraphicsDesc g;
  g.vertex_spirv = ci.compiler.compile("passes/rsm.vert", defines);
  g.fragment_spirv = ci.compiler.compile("passes/rsm.frag", defines);
  g.color_formats = {VK_FORMAT_R32G32B32A32_UINT, VK_FORMAT_R16G16B16A16_SFLOAT};
  g.depth_format = VK_FORMAT_D32_SFLOAT;
  pipeline_ = Pipeline::graphics(ci.ctx, g, bindings, sizeof(gpu::RsmLayerPush));
}

void ReflectiveShadowMaps::update(const scenes::Scene& scene) {
  const size_t n_layers = layers_.size(), n_emitters = emitters_.size();
  build(scene, scene_gpu_.geometry(), ortho_size_, cube_size_, emitters_, layers_);
  if (layers_.size() != n_layers || emitters_.size() != n_emitters)
    throw std::logic_error(
        "reflective shadow maps: the scene's lights changed in number during a sequence");
  draw_scale_.clear();
  // The stored flux is density x scale with scale = 1 / the light's brightest channel, so every
  // stored value lies in [0, 1] (fp16 keeps ~3 significant digits there and cannot overflow for
  // any light); a dark light stores zeros. Readers multiply by params.z = 1 / scale.
  for (auto& l : layers_) draw_scale_.push_back(l.params.z > 0.0f ? 1.0f / l.params.z : 0.0f);
  if (!layers_.empty())
    std::memcpy(layer_buffer_.mapped(), layers_.data(), layers_.size() * sizeof(layers_[0]));
  if (!emitters_.empty())
    std::memcpy(emitter_buffer_.mapped(), emitters_.data(),
                emitters_.size() * sizeof(emitters_[0]));
}

void ReflectiveShadowMaps::record(const FrameInput& in) {
  const bool render = in.frame == 0 || in.change != SceneChange::None || draw_scale_.empty();
  if (render) update(in.scene);
  in.timer.begin(in.cmd, "rsm");
  if (render) {
    if (ray_traced_)
      cast_rays(in);
    else
      rasterise(in);
    surface_.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
    flux_.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
  }
  in.timer.end(in.cmd);
}

std::vector<Descriptor> ReflectiveShadowMaps::builder_descriptors() const {
  auto d = scene_gpu_.descriptors();
  d.push_back(Descriptor::storage(emitter_buffer_));
  d.push_back(Descriptor::storage(layer_buffer_));
  return d;
}

gpu::RsmLayerPush ReflectiveShadowMaps::layer_push(uint32_t l) const {
  return {l, uint32_t(layers_[l].params.w), draw_scale_[l], uint32_t(layers_[l].params.y)};
}

void ReflectiveShadowMaps::rasterise(const FrameInput& in) {
  surface_.transition(in.cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  flux_.transition(in.cmd, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  depth_.transition(in.cmd, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  pipeline_.bind(in.cmd);
  pipeline_.push_descriptors(in.cmd, builder_descriptors());
  for (uint32_t l = 0; l < layer_count(); ++l) {
    const uint32_t size = uint32_t(layers_[l].params.y);
    // The whole layer is cleared (empty texels hold zero flux: injection reads the array's
    // full extent), the layer's own size drawn.
    begin_rendering(in.cmd, extent_, extent_, {{surface_.layer_view(l), flux_.layer_view(l)}, depth_.view(), false},
                    {size, size});
    pipeline_.push_constants(in.cmd, layer_push(l));
    draw_scene(in.cmd, scene_gpu_);
    vkCmdEndRendering(in.cmd);
  }
}

void ReflectiveShadowMaps::cast_rays(const FrameInput& in) {
  surface_.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
  flux_.transition(in.cmd, VK_IMAGE_LAYOUT_GENERAL);
  pipeline_.bind(in.cmd);
  auto d = builder_descriptors();
  d.push_back(Descriptor::storage_image(surface_));
  d.push_back(Descriptor::storage_image(flux_));
  pipeline_.push_descriptors(in.cmd, d);
  // Every layer is written whole (cleared beyond its own size) and no layer reads another, so
  // the dispatches need no barrier between them.
  for (uint32_t l = 0; l < layer_count(); ++l) {
    pipeline_.push_constants(in.cmd, layer_push(l));
    pipeline_.dispatch_2d(in.cmd, extent_, extent_);
  }
  full_barrier(in.cmd);
}

}  // namespace giq::realtime
