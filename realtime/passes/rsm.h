#pragma once
// The shared reflective-shadow-map pass (Afanasev 2021, chapter II; Dachsbacher and Stamminger 2005,
// "Reflective Shadow Maps"): every light's view of the scene as virtual point lights (VPLs),
// one texel each: position, normal and the flux density the surface reflects diffusely
// (rsm.frag). `rsm` gathers one bounce from them; `lpv` downsamples and injects them.
//
// Layers, all in two 2D arrays (RGBA32UI position + octahedral normal, RGBA16F flux):
//   - a point or spot light: six 90-degree cube faces around it, the shadow maps' cube views
//     (ShadowMaps::cube_face_view_proj), `rsm_cube_size` texels per side;
//   - an emissive mesh (area light): the same cube around its representative point (the
//     shadow maps' point), lit by a cosine-weighted emitter there whose radiant intensity along
//     the mesh's mean normal is the sum of radiance x area over its triangles (exact for a
//     planar light seen from afar; what a near receiver sees of the light's extent is lost);
//   - a directional light: one orthographic window over the whole scene's bounding sphere
//     (not the camera-following shadow cascades: indirect light comes from all of the sunlit
//     scene, seen or not), `rsm_size` texels per side.
// Layers are rendered on the first frame and again when the lights or the geometry moved,
// rasterised (rsm.vert, rsm.frag) or by one ray per texel centre (rsm_rays.comp), as
// `rsm_ray_traced` says (giq/realtime/pass_builder.h): the same texels but where a texel
// centre's ray passes within the rasteriser's subpixel precision of a triangle's edge.

#include <cstdint>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "passes/rsm_shared.h"

namespace giq::realtime {

class ReflectiveShadowMaps {
 public:
  // rsm_size (directional lights' window), rsm_cube_size (per cube face), rsm_ray_traced.
  static std::vector<Parameter> parameters();

  ReflectiveShadowMaps(const TechniqueCreateInfo& ci);

  bool ray_traced() const { return ray_traced_; }
  // Pass name "rsm"; leaves surface() and flux() in GENERAL layout.
  void record(const FrameInput& in);

  uint32_t layer_count() const { return uint32_t(layers_.size()); }
  uint32_t emitter_count() const { return uint32_t(emitters_.size()); }
  uint32_t extent() const { return extent_; }  // texels per side of the arrays
  Image& surface() { return surface_; }        // RGBA32UI: position bits, octahedral normal
  Image& flux() { return flux_; }              // RGBA16F: flux density x layer's scale
  const Buffer& layer_buffer() const { return layer_buffer_; }      // GpuRsmLayer[]
  const Buffer& emitter_buffer() const { return emitter_buffer_; }  // GpuRsmEmitter[]
  const std::vector<gpu::GpuRsmLayer>& layers() const { return layers_; }

 private:
  void update(const scenes::Scene& scene);
  // Both builders' first bindings: the scene's, the emitters, the layers.
  std::vector<Descriptor> builder_descriptors() const;
  gpu::RsmLayerPush layer_push(uint32_t layer) const;
  void rasterise(const FrameInput& in);
  void cast_rays(const FrameInput& in);

  const SceneGpu& scene_gpu_;
  uint32_t ortho_size_, cube_size_, extent_ = 1;
  bool ray_traced_;
  std::vector<gpu::GpuRsmEmitter> emitters_;
  std::vector<gpu::GpuRsmLayer> layers_;
  std::vector<float> draw_scale_;  // flux scale per layer
  Image surface_, flux_, depth_;  // depth_: rasterised only
  Buffer layer_buffer_, emitter_buffer_;
  Pipeline pipeline_;
};

}  // namespace giq::realtime
