#pragma once
// The shared G-buffer pass: the scene rasterised once from the camera into float32 targets
// that any technique's lighting reads. Positions are not interpolated: each fragment
// intersects the camera ray through its pixel centre with its triangle's plane, so a G-buffer
// texel holds exactly the point the reference's camera ray at that pixel centre would hit.
//
// Targets (RGBA32F unless noted, GENERAL layout after record()):
//   position: xyz local-frame position, w = 1 where a surface was hit, 0 elsewhere
//   normal:   xyz shading normal as the reference's first hit has it (interpolated,
//             normal-mapped, turned to the viewer's side; shaders/surface.glsl), w = 0
// Alpha-masked cut-outs are no surface: the rasteriser discards them, the ray caster passes
// through them.
//   ids (RGBA32UI): x = triangle + 1 (0 = nothing), y = material, z = object id, w = 1 back face

#include <cstdint>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/scenes/camera.h"
#include "giq/scenes/features.h"

namespace giq::realtime {

class Context;
class GpuTimer;
class SceneGpu;
class ShaderCompiler;

class GBufferPass {
 public:
  // ray_traced: cast the pixel-centre camera rays through the BVH in a compute shader
  // instead of rasterising (gbuffer_rays.comp); same contents, for GPUs whose graphics units
  // are few (the H100's).
  GBufferPass(Context& ctx, ShaderCompiler& compiler, const SceneGpu& scene, const scenes::FeatureSet& features,
              uint32_t width, uint32_t height, bool ray_traced = false);
  void record(VkCommandBuffer cmd, const scenes::Camera& camera, GpuTimer& timer);

  Image& position() { return position_; }
  Image& normal() { return normal_; }
  Image& ids() { return ids_; }

 private:
  const SceneGpu& scene_;
  uint32_t width_, height_;
  bool ray_traced_;
  Image position_, normal_, ids_, depth_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
