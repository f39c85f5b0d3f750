#pragma once
// The shared G-buffer pass: the scene rasterised once from the camera into float32 targets
// that any technique's lighting reads. Positions are not interpolated: each fragment
// intersects the camera ray through its pixel centre with its triangle's plane, so a G-buffer
// texel holds exactly the point the reference's camera ray at that pixel centre would hit.
//
// Targets (RGBA32F unless noted, GENERAL layout after record()):
//   position: xyz local-frame position, w = 1 where a surface was hit, 0 elsewhere
//   normal:   xyz shading normal as the reference's first hit has it (interpolated,
//             normal-mapped, turned to the viewer's side; shaders/surface.glsl), w = the
//             pixel's footprint on the surface (pixel_footprint, shaders/camera.glsl): the
//             distance to the neighbouring pixels' points, which selects the mip levels of
//             the textures looked up there (texture_lod, shaders/textures.glsl)
// Alpha-masked cut-outs are no surface: the rasteriser discards them, the ray caster passes
// through them.
//   ids (RGBA32UI): x = triangle + 1 (0 = nothing), y = material, z = object id, w = 1 back face
//   motion (only after enable_motion_vectors()): xy = where this pixel's surface point was in
//     the previous frame minus this pixel's centre, in pixels (so the history of pixel p is
//     read at p + 0.5 + motion.xy); w = 1 when that place was in front of the previous camera
//     and inside the image. Camera and geometry motion both count; on the first frame, and
//     for anything that did not move, it is 0. Pass "motion_vectors".

#include <cstdint>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "giq/scenes/camera.h"
#include "giq/scenes/features.h"
#include "giq/realtime/pass_builder.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class SceneGpu;
class ShaderCompiler;

class GBufferPass {
 public:
  // "gbuffer_ray_traced" (giq/realtime/pass_builder.h), for techniques to list among their
  // parameters. The ray-traced builder is gbuffer_rays.comp.
  static Parameter ray_traced_parameter();

  GBufferPass(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene, const scenes::FeatureSet& features,
              uint32_t width, uint32_t height, PassBuilder builder = PassBuilder::Raster);
  // At the technique's resolution, with the builder its "gbuffer_ray_traced" parameter names.
  explicit GBufferPass(const TechniqueCreateInfo& ci);
  bool ray_traced() const { return ray_traced_; }
  // For temporal techniques: also write motion vectors on every record().
  void enable_motion_vectors();
  void record(VkCommandBuffer cmd, const scenes::Camera& camera, GpuTimer& timer);

  // A deferred lighting pass's first bindings: the scene's, then position, normal and ids
  // (passes/receiver.glsl).
  static std::vector<VkDescriptorType> receiver_bindings();
  std::vector<Descriptor> receiver_descriptors();

  Image& position() { return position_; }
  Image& normal() { return normal_; }
  Image& ids() { return ids_; }
  Image& motion() { return motion_; }

 private:
  const SceneGpu& scene_;
  uint32_t width_, height_;
  bool ray_traced_;
  Image position_, normal_, ids_, depth_, motion_;
  Pipeline pipeline_, motion_pipeline_;
  ShaderCompiler& compiler_;
  Context& ctx_;
  bool has_previous_camera_ = false;
  scenes::Camera previous_camera_;

  void record_motion(VkCommandBuffer cmd, const scenes::Camera& camera, GpuTimer& timer);
};

}  // namespace giq::realtime
