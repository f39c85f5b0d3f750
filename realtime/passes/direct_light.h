#pragma once
// The shared direct-lighting pass: shadow maps for every light (passes/shadow_maps.h) and one
// compute pass that lights each G-buffer texel with emission seen directly plus the light
// arriving straight from the light sources (direct_light.comp). `direct` is this pass alone;
// every GI technique adds its indirect light to this pass's output, so all of them share one
// direct term and their differences are differences of indirect light only.
//
// Punctual lights are evaluated exactly (glTF units and falloff); each emissive mesh is one
// area light, integrated exactly when unshadowed and shadowed from a representative point
// (hard shadows) or, with `area_shadow_rays`, by rays to points on it (soft shadows).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "passes/direct_light_shared.h"
#include "passes/shadow_maps.h"

namespace giq::realtime {

class GBufferPass;

class DirectLightPass {
 public:
  // The parameters this pass reads (shadow_map_size, pcf_radius, normal_offset,
  // cascade_split_lambda, cache_static_shadows, particle_lights, particle_cut, area_shadow_rays,
  // particle_shadow_map_size, shadow_maps_ray_traced); a technique lists them among its own.
  static std::vector<Parameter> parameters();

  explicit DirectLightPass(const TechniqueCreateInfo& ci);

  // Records "shadow_maps" (before the G-buffer is needed) and then "direct_lighting". When
  // in.change says the scene moved, the shadow sources and area lights follow it first.
  void record_shadows(const FrameInput& in);
  void record_lighting(const FrameInput& in, GBufferPass& gbuffer);

  Image& output() { return direct_; }  // RGBA32F, GENERAL after record_lighting()
  ShadowMaps& shadows() { return shadows_; }
  // Shadow-map layer of punctual light i (scene order), and the area lights.
  const std::vector<uint32_t>& light_layers() const { return light_layer_; }
  const std::vector<gpu::GpuAreaLight>& area_lights() const { return area_lights_; }
  // The area lights as the GPU reads them (GpuAreaLight, GpuAreaTriangle; a stage of glowing
  // particles reads its particles from the scene's vertices, passes/area_light_parts.glsl), for
  // passes that light other points than the G-buffer's; rebuilt when emitters move, so take
  // them when recording, after record_shadows().
  const Buffer& area_light_buffer() const { return area_light_buffer_; }
  const Buffer& area_triangle_buffer() const { return area_triangle_buffer_; }
  // The particles' light tree (LinearBvh::LightTree: nodes, clusters, stage roots) for passes
  // that weigh a stage of particles by cluster, as an area light's extent.w says.
  std::array<Descriptor, 3> particle_tree_descriptors() const;

 private:
  void build_area_lights(const scenes::Scene& scene);
  // The shadow sources of the scene's lights and of area_lights_ (their layers into them).
  void declare_shadows(const scenes::Scene& scene);
  void upload_area_lights(Context& ctx);
  void follow(const scenes::Scene& scene, SceneChange change);

  Context* ctx_;
  const SceneGpu& scene_gpu_;
  uint32_t width_, height_;
  uint32_t pcf_radius_;
  float normal_offset_;
  bool particle_lights_;          // light particle stages particle by particle
  float particle_cut_;            // clusters of particles light as one below this size over distance
  uint32_t particle_shadow_size_;  // texels per side of a particle stage's shadow cube
  uint32_t area_shadow_rays_;      // 0: area lights' shadow cubes; else rays a pixel to each
  ShadowMaps shadows_;
  std::vector<uint32_t> light_layer_;
  std::vector<gpu::GpuAreaLight> area_lights_;
  std::vector<gpu::GpuAreaTriangle> area_triangles_;
  Buffer light_layer_buffer_, area_light_buffer_, area_triangle_buffer_;
  Image direct_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
