#pragma once
// The shared shadow-map pass (Kim-Chan 2022, section 5.4): cube maps for point and spot lights and
// for the representative points of area lights, cascaded maps for directional lights, all as
// layers of one depth 2D array so that lookups need no descriptor indexing. A cube is six
// 90-degree layers (+x, -x, +y, -y, +z, -z); the lighting shader picks the face by the major
// axis of the light-to-point direction. Depth uses slope-scaled bias when rendering and a
// normal offset of a few texels when sampling (shaders/shadow.glsl); filtering is PCF over a
// (2r+1)^2 texel grid. In scenes with alpha masks a fragment shader discards the cut-outs,
// which cast no shadow. Layers are rasterised, or cast as one ray per texel centre
// (shadow_maps_rays.comp: the same depths but where a texel centre's ray passes within the
// rasteriser's subpixel precision of a triangle's edge), as the builder says
// (giq/realtime/pass_builder.h, "shadow_maps_ray_traced").

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/scenes/camera.h"
#include "giq/scenes/scene.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class SceneGpu;
class ShaderCompiler;

class ShadowMaps {
 public:
  static constexpr int kCascades = 3;

  ShadowMaps(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene, const scenes::Bounds& bounds, uint32_t size,
             bool ray_traced = false);

  // View-projection of face f (+x, -x, +y, -y, +z, -z) of a cube centred at `position`, with
  // near and far planes covering `bounds`; shared with the reflective shadow maps (passes/rsm.h).
  static glm::mat4 cube_face_view_proj(glm::vec3 position, const scenes::Bounds& bounds, int face);

  // Declare the maps before the first record(); each returns its first layer. A cube may leave
  // out a mesh: its vertices [skip.x, skip.x + skip.y), which are its triangles [skip.z,
  // skip.z + skip.w) (own_geometry, scene_gpu.h: an emissive mesh's own, so that a closed
  // emitter does not shadow its light from its centre: Scene::AreaLight::representative), and
  // may use `size` texels per side (at most size(); 0: size()), the corner of its layers.
  uint32_t add_cube(glm::vec3 position, glm::uvec4 skip = glm::uvec4(0u), uint32_t size = 0);
  uint32_t add_cascades(glm::vec3 direction);
  // The fraction between logarithmic (1) and uniform (0) cascade splits (Zhang et al. 2006,
  // "Parallel-Split Shadow Maps", practical split scheme).
  void set_split_lambda(float lambda) { split_lambda_ = lambda; }
  // Render cube maps only when they are stale (first record, a moved source, moved geometry);
  // cascades follow the camera and are always re-rendered.
  void set_cache_static(bool cache) { cache_static_ = cache; }
  // Moves source `source` (numbered in the order of the add_ calls) to a new position (cube)
  // or direction (cascades), for a light that moved.
  void move(size_t source, glm::vec3 v);
  // The mesh cube `source` leaves out (add_cube's `skip`) moved or changed in size.
  void set_skip(size_t source, glm::uvec4 skip);
  // Forgets every source, to declare them anew (the set of lights changed).
  void clear();
  // The geometry moved: new scene bounds, and every cube map is re-rendered.
  void set_bounds(const scenes::Bounds& bounds);

  // Renders every layer; cascades follow the camera. Pass name "shadow_maps".
  void record(VkCommandBuffer cmd, const scenes::Camera& camera, float aspect, GpuTimer& timer);

  uint32_t layer_count() const { return uint32_t(layers_.size()); }
  uint32_t size() const { return size_; }
  bool ray_traced() const { return ray_traced_; }
  const Image& depth() const { return depth_; }
  const Buffer& layers() const { return layer_buffer_; }
  const Sampler& sampler() const { return sampler_; }

 private:
  struct Source {
    bool cube;
    glm::vec3 v;  // position (cube) or direction (cascades)
    uint32_t first_layer;
    uint32_t size;  // texels per side used
  };
  std::vector<glm::uvec4> skip_;  // per layer: the mesh left out (add_cube)
  void create_resources();
  void rasterise(VkCommandBuffer cmd, uint32_t layer, uint32_t size);
  void cast_rays(VkCommandBuffer cmd, uint32_t layer, uint32_t size);
  void place_cube(const Source& s);
  void update_cascades(const Source& s, const scenes::Camera& camera, float aspect);

  Context& ctx_;
  const SceneGpu& scene_;
  scenes::Bounds bounds_;
  uint32_t size_;
  bool ray_traced_;
  float split_lambda_ = 0.5f;
  bool cache_static_ = true;
  bool cubes_stale_ = true;
  std::vector<Source> sources_;
  std::vector<glm::mat4> layers_;
  std::vector<glm::vec4> params_;
  Image depth_;
  Buffer layer_buffer_;
  Buffer ray_depth_;  // one layer's depths from the rays, copied into depth_
  Sampler sampler_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
