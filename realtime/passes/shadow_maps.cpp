#include "passes/shadow_maps.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "giq/realtime/context.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "giq/realtime/raster.h"
#include "giq/realtime/timer.h"
#include "passes/shadow_maps_shared.h"

namespace giq::realtime {

// The rasteriser's slope-scaled depth bias (vkCmdSetDepthBias): surfaces at grazing angles to
// the light need the most. The rays add the same (shadow_maps_rays.comp).
constexpr float kSlopeBias = 1.5f;

ShadowMaps::ShadowMaps(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene, const scenes::Bounds& bounds,
                       uint32_t size, bool ray_traced)
    : ctx_(ctx), scene_(scene), bounds_(bounds), size_(size), ray_traced_(ray_traced), sampler_(ctx, false, true) {
  const auto defines = feature_defines(scene.features());
  if (ray_traced_) {
    auto bindings = SceneGpu::binding_types();
    bindings.insert(bindings.end(), 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    pipeline_ = Pipeline::compute(ctx, compiler.compile("passes/shadow_maps_rays.comp", defines), bindings,
                                  sizeof(gpu::ShadowRayPush));
    return;
  }
  GraphicsDesc g;
  g.vertex_spirv = compiler.compile("passes/shadow_maps.vert", defines);
  // Depth only, except where alpha-masked casters need their cut-outs discarded.
  if (scene.features().alpha_mask) g.fragment_spirv = compiler.compile("passes/shadow_maps.frag", defines);
  g.depth_format = VK_FORMAT_D32_SFLOAT;
  g.depth_bias = true;
  pipeline_ = Pipeline::graphics(ctx, g, SceneGpu::binding_types(), sizeof(gpu::ShadowPush));
}

uint32_t ShadowMaps::add_cube(glm::vec3 position, glm::uvec4 skip, uint32_t size) {
  const uint32_t first = uint32_t(layers_.size());
  sources_.push_back({true, position, first, size == 0 ? size_ : std::min(size, size_)});
  layers_.resize(first + 6);
  params_.resize(first + 6);
  skip_.resize(first + 6, skip);
  place_cube(sources_.back());
  return first;
}

glm::mat4 ShadowMaps::cube_face_view_proj(glm::vec3 position, const scenes::Bounds& bounds, int face) {
  // Near plane: a thousandth of the scene; far: beyond the farthest point of the scene.
  const float diag = bounds.diagonal();
  const float znear = 1e-3f * diag, zfar = 2.0f * diag + glm::length(position - bounds.centre());
  const glm::mat4 proj = glm::perspectiveRH_ZO(glm::radians(90.0f), 1.0f, znear, zfar);
  const glm::vec3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  return proj * glm::lookAtRH(position, position + dirs[face], ups[face]);
}

void ShadowMaps::place_cube(const Source& s) {
  for (int f = 0; f < 6; ++f) {
    layers_[s.first_layer + f] = cube_face_view_proj(s.v, bounds_, f);
    // A 90-degree face is 2 units wide at distance 1.
    params_[s.first_layer + f] = glm::vec4(GIQ_SHADOW_CUBE_FACE, 2.0f / float(s.size), 0.0f, float(s.size) / float(size_));
  }
}

void ShadowMaps::move(size_t source, glm::vec3 v) {
  Source& s = sources_.at(source);
  const glm::vec3 moved = s.cube ? v : glm::normalize(v);
  if (moved == s.v) return;
  s.v = moved;
  if (s.cube) {
    place_cube(s);
    cubes_stale_ = true;
  }
}

void ShadowMaps::set_skip(size_t source, glm::uvec4 skip) {
  const Source& s = sources_.at(source);
  if (!s.cube || skip_[s.first_layer] == skip) return;
  std::fill(skip_.begin() + s.first_layer, skip_.begin() + s.first_layer + 6, skip);
  cubes_stale_ = true;
}

void ShadowMaps::clear() {
  sources_.clear(), layers_.clear(), params_.clear(), skip_.clear();
  depth_ = Image();
  layer_buffer_ = Buffer();
  cubes_stale_ = true;
}

void ShadowMaps::set_bounds(const scenes::Bounds& bounds) {
  bounds_ = bounds;
  for (const auto& s : sources_)
    if (s.cube) place_cube(s);
  cubes_stale_ = true;
}

uint32_t ShadowMaps::add_cascades(glm::vec3 direction) {
  const uint32_t first = uint32_t(layers_.size());
  sources_.push_back({false, glm::normalize(direction), first, size_});
  for (int c = 0; c < kCascades; ++c) {
    layers_.emplace_back(1.0f);
    params_.emplace_back(GIQ_SHADOW_CASCADE, 0.0f, 0.0f, 1.0f);
    skip_.emplace_back(0u);
  }
  return first;
}

void ShadowMaps::create_resources() {
  const uint32_t n = std::max<uint32_t>(1, layer_count());
  // An array view even for one layer (a scene without lights): the shaders read a 2D array.
  depth_ = Image(ctx_, {size_, size_, n, VK_FORMAT_D32_SFLOAT,
                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, true});
  layer_buffer_ = Buffer(ctx_, n * sizeof(gpu::GpuShadowLayer), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUsage::Upload);
  if (ray_traced_)
    ray_depth_ = Buffer(ctx_, uint64_t(size_) * size_ * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        MemoryUsage::Device);
}

void ShadowMaps::update_cascades(const Source& s, const scenes::Camera& camera, float aspect) {
  // The camera frustum from its near plane to the farthest point of the scene, split into
  // kCascades slices; each slice's bounding sphere sets a square orthographic window.
  const glm::vec3 lo = bounds_.lo, hi = bounds_.hi;
  float far_d = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    far_d = std::max(far_d, glm::dot(corner - camera.position, camera.forward));
  }
  const float near_d = camera.znear > 0.0f ? camera.znear : 1e-3f;
  far_d = std::max(far_d, 2.0f * near_d);
  const float t = std::tan(0.5f * camera.yfov);
  // The light's view is fixed for the scene (so texel snapping below is stable as the camera
  // moves): looking along the light from outside the scene's bounding sphere.
  const float radius = 0.5f * bounds_.diagonal();
  const glm::vec3 c0 = bounds_.centre();
  const glm::vec3 up = std::abs(s.v.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::mat4 view = glm::lookAtRH(c0 - s.v * (2.0f * radius), c0, up);
  auto split = [&](int i) {
    const float f = float(i) / float(kCascades);
    const float log_split = near_d * std::pow(far_d / near_d, f), uni = near_d + (far_d - near_d) * f;
    return split_lambda_ * log_split + (1.0f - split_lambda_) * uni;
  };
  for (int c = 0; c < kCascades; ++c) {
    const float d0 = split(c), d1 = split(c + 1);
    glm::vec3 corners[8];
    glm::vec3 mid(0.0f);
    for (int i = 0; i < 8; ++i) {
      const float d = (i & 4) ? d1 : d0;
      const float x = (i & 1) ? 1.0f : -1.0f, y = (i & 2) ? 1.0f : -1.0f;
      // A slice of a pinhole's frustum widens with depth; an orthographic one does not.
      const float half_h = camera.orthographic() ? camera.ymag : d * t;
      corners[i] = camera.position + d * camera.forward + half_h * (x * aspect * camera.right + y * camera.up);
      mid += corners[i] / 8.0f;
    }
    float r = 0.0f;
    for (const auto& p : corners) r = std::max(r, glm::length(p - mid));
    r = std::min(r, radius * 1.01f + glm::length(mid - c0));  // no bigger than needed for the scene
    const float texel = 2.0f * r / float(size_);
    // Snap the window to whole texels in light space: a moving camera then does not make the
    // shadow edges crawl.
    glm::vec4 m = view * glm::vec4(mid, 1.0f);
    m.x = std::round(m.x / texel) * texel;
    m.y = std::round(m.y / texel) * texel;
    const glm::mat4 proj = glm::orthoRH_ZO(m.x - r, m.x + r, m.y - r, m.y + r, 0.0f, 4.0f * radius);
    layers_[s.first_layer + c] = proj * view;
    params_[s.first_layer + c] = glm::vec4(GIQ_SHADOW_CASCADE, texel, d1, 1.0f);
  }
}

void ShadowMaps::record(VkCommandBuffer cmd, const scenes::Camera& camera, float aspect, GpuTimer& timer) {
  if (!depth_) create_resources();
  for (const auto& s : sources_)
    if (!s.cube) update_cascades(s, camera, aspect);
  auto* out = static_cast<gpu::GpuShadowLayer*>(layer_buffer_.mapped());
  // The texel rays start on a layer's near plane: the matrix inverted in double, so that the
  // rays of a light far from the origin keep float's precision. The rasteriser needs none.
  for (uint32_t i = 0; i < layer_count(); ++i)
    out[i] = {layers_[i], ray_traced_ ? glm::mat4(glm::inverse(glm::dmat4(layers_[i]))) : glm::mat4(1.0f), params_[i]};

  timer.begin(cmd, "shadow_maps");
  depth_.transition(cmd, ray_traced_ ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  pipeline_.bind(cmd);
  auto d = scene_.descriptors();
  if (ray_traced_) {
    d.push_back(Descriptor::storage(layer_buffer_));
    d.push_back(Descriptor::storage(ray_depth_));
  }
  pipeline_.push_descriptors(cmd, d);
  for (uint32_t l = 0; l < layer_count(); ++l) {
    if (cache_static_ && !cubes_stale_ && params_[l].x == GIQ_SHADOW_CUBE_FACE) continue;
    const uint32_t size = uint32_t(std::lround(params_[l].w * float(size_)));
    if (ray_traced_)
      cast_rays(cmd, l, size);
    else
      rasterise(cmd, l, size);
  }
  depth_.transition(cmd, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  cubes_stale_ = false;
  timer.end(cmd);
}

void ShadowMaps::rasterise(VkCommandBuffer cmd, uint32_t l, uint32_t size) {
  begin_rendering(cmd, size, size, {{}, depth_.layer_view(l), true});
  vkCmdSetDepthBias(cmd, 0.0f, 0.0f, kSlopeBias);
  pipeline_.push_constants(cmd, gpu::ShadowPush{layers_[l], skip_[l]});
  draw_scene(cmd, scene_);
  vkCmdEndRendering(cmd);
}

void ShadowMaps::cast_rays(VkCommandBuffer cmd, uint32_t l, uint32_t size) {
  // One buffer serves every layer in turn: the rays fill it, a copy moves it into the layer
  // (a depth image cannot be a storage image).
  pipeline_.push_constants(cmd, gpu::ShadowRayPush{skip_[l], l, size, kSlopeBias, 0u});
  pipeline_.dispatch_2d(cmd, size, size);
  full_barrier(cmd);
  VkBufferImageCopy c{};
  c.bufferRowLength = size;
  c.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, l, 1};
  c.imageExtent = {size, size, 1};
  vkCmdCopyBufferToImage(cmd, ray_depth_.handle(), depth_.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &c);
  full_barrier(cmd);
}

}  // namespace giq::realtime
