#pragma once
// The shared G-buffer pass: the scene rasterised once from the camera into float32 targets
// that any technique's lighting reads. Positions are not interpolated: each fragment
// intersects the camera ray through its pixel centre with its triangle's plane, so a G-buffer
// texel holds exactly the point the reference's camera ray at that pixel centre would hit.
//
// Targets (RGBA32F unless noted, GENERAL layout after record()):
//   position: xyz local-frame position, w = 1 where a surface was hit, 0 elsewhere
//   normal:   xyz shading normal turned to the viewer's side, w = 0
//   ids (RGBA32UI): x = triangle + 1 (0 = nothing), y = material, z = object id, w = 1 back face
//   motion (only after enable_motion_vectors()): xy = where this pixel's surface point was in
//     the previous frame minus this pixel's centre, in pixels (so the history of pixel p is
//     read at p + 0.5 + motion.xy); w = 1 when that place was in front of the previous camera
//     and inside the image. Camera and geometry motion both count; on the first frame, and
//     for anything that did not move, it is 0. Pass "motion_vectors".

#include <cstdint>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "giq/scenes/camera.h"
#include "giq/scenes/features.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class SceneGpu;
class ShaderCompiler;

class GBufferPass {
 public:
  // "gbuffer_ray_traced" (0 or 1), for techniques to list among their parameters.
  static Parameter ray_traced_parameter();

  // ray_traced: cast the pixel-centre camera rays through the BVH in a compute shader
  // instead of rasterising (gbuffer_rays.comp); same contents, for GPUs whose graphics units
  // are few (the H100's).
  GBufferPass(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene, const scenes::FeatureSet& features,
              uint32_t width, uint32_t height, bool ray_traced = false);
  // For temporal techniques: also write motion vectors on every record().
  void enable_motion_vectors();
  void record(VkCommandBuffer cmd, const scenes::Camera& camera, GpuTimer& timer);

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
