#pragma once
// Skinned and morphing meshes deformed on the GPU, once a frame, in one compute pass
// (shaders/deform.comp): the rest vertices, morph target displacements and joint influences
// are uploaded once; each frame brings only the joint matrices, the morph weights and the
// windings (scenes::Deformation). The pass writes each vertex's last value to the previous-
// vertex buffer before overwriting it (motion vectors), and the tangents of textured scenes.
// SceneGpu runs it, then refits the BVH on the GPU (BvhRefitter).

#include <cstdint>
#include <utility>
#include <vector>

#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/scenes/scene.h"

namespace giq::realtime {

class Context;
class ShaderCompiler;
struct FlatGeometry;

class Deformer {
 public:
  // For the deforming meshes of `scene` (Mesh::deformation), whose vertices lie in the scene's
  // vertex buffer from geometry.mesh_first_vertex on. `tangents`: the scene's vertex extras are
  // filled (SceneGpu does for textured scenes), so deformed tangents are written there.
  Deformer(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene, const FlatGeometry& geometry, bool tangents);

  bool empty() const { return slot_count_ == 0; }
  uint32_t vertex_count() const { return slot_count_; }  // vertices deformed each frame

  // The scene vertices it writes, [first, first + count) per deforming mesh; whether they are
  // still where `g` puts its meshes.
  std::vector<std::pair<uint32_t, uint32_t>> ranges() const;
  bool fits(const FlatGeometry& g) const;

  // Brings the matrices, weights and windings to `posed` (the same scene at another instant).
  void set_pose(const scenes::Scene& posed);
  // One dispatch. `save_previous`: copy each vertex's value to `previous` before overwriting
  // it; false on the first frame, when `previous` gets the new value too.
  void record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& previous, const Buffer& vertex_extra, bool save_previous) const;

 private:
  Context* ctx_;
  Pipeline pipeline_;
  std::vector<size_t> meshes_;  // the scene's deforming meshes, in scene order
  std::vector<uint32_t> base_flags_;  // per deforming mesh: GIQ_DEFORM_* but MIRRORED
  uint32_t slot_count_ = 0;
  Buffer rest_, displacements_, influences_, slots_, rest_triangles_;  // uploaded once
  Buffer matrices_, weights_, records_;                                // each frame
  std::vector<glm::uvec4> records_host_;                               // GpuDeformMesh rows
};

}  // namespace giq::realtime
