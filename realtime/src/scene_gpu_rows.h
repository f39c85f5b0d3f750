#pragma once
// What SceneGpu's upload (scene_gpu.cpp) and its update (scene_gpu_update.cpp) both decide or
// write: whether a scene needs its vertex extras, a vertex's extras, and where a stage of
// particles goes in the flattened arrays.

#include "giq/realtime/scene_gpu.h"
#include "shaders/scene_shared.h"

namespace giq::realtime {

// Scenes that sample textures, map normals or cut out by alpha get their texture
// coordinates, tangents and texels; the others a 16-byte empty buffer per binding, so that
// every pipeline has the same scene bindings.
inline bool needs_textures(const scenes::FeatureSet& f) {
  return f.textures || f.normal_maps || f.alpha_mask || f.vertex_colors || f.environment_map;
}

// Vertex i of `mesh`'s extras: what it has of tangent, texture coordinates and colour.
inline gpu::GpuVertexExtra extra_row(const scenes::Mesh& mesh, size_t i) {
  gpu::GpuVertexExtra e{glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(1.0f)};
  if (i < mesh.tangents.size()) e.tangent = mesh.tangents[i];
  if (i < mesh.uvs.size()) e.uv.x = mesh.uvs[i].x, e.uv.y = mesh.uvs[i].y;
  if (i < mesh.uvs2.size()) e.uv.z = mesh.uvs2[i].x, e.uv.w = mesh.uvs2[i].y;
  if (i < mesh.colors.size()) e.color = mesh.colors[i];
  return e;
}

// A stage of particles that the GPU writes: its places in the arrays, after the meshes before it.
inline void add_stage_places(const scenes::Mesh& m, FlatGeometry& g) {
  g.mesh_first_triangle.push_back(g.triangle_count);
  g.mesh_first_vertex.push_back(g.vertex_count);
  g.vertex_count += scenes::kParticleVertices * m.particles;
  g.triangle_count += scenes::kParticleTriangles * m.particles;
}

}  // namespace giq::realtime
