// SceneGpu's update (scene_gpu.h): what of a posed scene moved since the last upload, and
// what goes up again: nothing of a still file, the meshes that moved of a file whose layout
// held, or the whole file.
#include <algorithm>

#include "giq/realtime/context.h"
#include "giq/realtime/scene_gpu.h"
#include "scene_gpu_rows.h"

namespace giq::realtime {

SceneGpu::FileChange SceneGpu::file_change(const scenes::Scene& posed) const {
  const FlatGeometry& g = geometry_;
  FileChange change;
  if (g.mesh_first_vertex.size() != posed.meshes.size()) return change;
  size_t v = 0, t = 0, m = 0;
  for (; m < posed.meshes.size() && posed.meshes[m].emitter < 0; ++m) {
    const scenes::Mesh& mesh = posed.meshes[m];
    const size_t n = mesh.positions.size(), k = mesh.triangles.size();
    if (m >= g.mesh_first_vertex.size() || g.mesh_first_vertex[m] != v || g.mesh_first_triangle[m] != t ||
        v + n > g.positions.size() || t + k > g.triangles.size())
      return change;
    for (size_t i = 0; i < k; ++i)
      if (g.triangles[t + i] != mesh.triangles[i] + glm::uvec3(uint32_t(v)) || g.material[t + i] != uint32_t(mesh.material) ||
          g.object_id[t + i] != mesh.object_id)
        return change;
    // flatten's normals: the mesh's, or 0 for a mesh without.
    bool moved = !std::equal(mesh.positions.begin(), mesh.positions.end(), g.positions.begin() + long(v));
    for (size_t i = 0; i < n && !moved; ++i) moved = g.normals[v + i] != (i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f));
    if (moved) change.moved.push_back(uint32_t(m));
    v += n, t += k;
  }
  // No vertex or triangle of the file more than before.
  change.layout = v == g.positions.size() && t == g.triangles.size();
  if (!change.layout) change.moved.clear();
  return change;
}

bool SceneGpu::refit_meshes(const scenes::Scene& posed, const std::vector<uint32_t>& meshes) {
  // The emissive triangles' order gives each triangle record its emissive index: a mesh whose
  // emissive triangles came or went (one shrunk to no area) needs every record again.
  std::vector<glm::uvec2> listed;
  for (const scenes::EmissiveTriangle& e : posed.emissive_triangles)
    if (e.power > 0.0f && posed.meshes[e.mesh].emitter < 0) listed.emplace_back(e.mesh, e.triangle);
  if (listed != emissive_listed_) return false;
  moved_triangles_.assign(geometry_.triangles.size(), 0);
  for (uint32_t m : meshes) {
    const scenes::Mesh& mesh = posed.meshes[m];
    const uint32_t v = geometry_.mesh_first_vertex[m], t = geometry_.mesh_first_triangle[m];
    std::copy(mesh.positions.begin(), mesh.positions.end(), geometry_.positions.begin() + long(v));
    for (size_t i = 0; i < mesh.positions.size(); ++i) geometry_.normals[v + i] = i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f);
    std::fill(moved_triangles_.begin() + long(t), moved_triangles_.begin() + long(t + mesh.triangles.size()), uint8_t(1));
  }
  refit_bvh(bvh_, geometry_.positions, geometry_.triangles, moved_triangles_, refitted_nodes_);
  if (sah_cost(bvh_) > kMaxRefitCost * built_cost_) return false;
  last_bvh_update_ = BvhUpdate::Refitted;
  return true;
}

void SceneGpu::upload_meshes(const scenes::Scene& posed, const std::vector<uint32_t>& meshes) {
  using namespace gpu;
  // Rows: the deformation pass writes its meshes' own.
  for (uint32_t m : meshes) {
    if (deformer_ && posed.meshes[m].deformation) continue;
    const uint32_t first = geometry_.mesh_first_vertex[m], n = uint32_t(posed.meshes[m].positions.size());
    for (uint32_t i = first; i < first + n; ++i) {
      vertices_host_[2 * size_t(i)] = glm::vec4(geometry_.positions[i], 1.0f);
      vertices_host_[2 * size_t(i) + 1] = glm::vec4(geometry_.normals[i], 0.0f);
    }
  }
  vertices_.upload_ranges(vertices_host_.data(), mesh_rows(posed, meshes));
  if (needs_textures(posed.features)) {
    // Tangents turn with their meshes; the rest of a vertex's extras does not move.
    std::vector<GpuVertexExtra> packed;
    std::vector<VkBufferCopy> pieces;
    for (uint32_t m : meshes) {
      const scenes::Mesh& mesh = posed.meshes[m];
      if ((deformer_ && mesh.deformation) || mesh.tangents.size() != mesh.positions.size() || mesh.tangents.empty()) continue;
      pieces.push_back({packed.size() * sizeof(GpuVertexExtra), uint64_t(geometry_.mesh_first_vertex[m]) * sizeof(GpuVertexExtra),
                        mesh.positions.size() * sizeof(GpuVertexExtra)});
      for (size_t i = 0; i < mesh.positions.size(); ++i) packed.push_back(extra_row(mesh, i));
    }
    vertex_extra_.upload_pieces(packed.data(), packed.size() * sizeof(GpuVertexExtra), pieces);
  }
  // The refitted nodes, where the GPU holds the CPU's tree (interior nodes' right children
  // shifted with it).
  const uint32_t offset = cpu_tree_offset();
  std::vector<BvhNode> packed;
  std::vector<VkBufferCopy> pieces;
  for (uint32_t i : refitted_nodes_) {
    BvhNode n = bvh_.nodes[i];
    if (n.count == 0) n.index += offset;
    const uint64_t dst = uint64_t(offset + i) * sizeof(BvhNode);
    if (!pieces.empty() && pieces.back().dstOffset + pieces.back().size == dst)
      pieces.back().size += sizeof(BvhNode);
    else
      pieces.push_back({packed.size() * sizeof(BvhNode), dst, sizeof(BvhNode)});
    packed.push_back(n);
  }
  nodes_.upload_pieces(packed.data(), packed.size() * sizeof(BvhNode), pieces);
}

std::vector<VkBufferCopy> SceneGpu::mesh_rows(const scenes::Scene& posed, const std::vector<uint32_t>& meshes) const {
  std::vector<VkBufferCopy> rows;
  for (uint32_t m : meshes) {
    if (deformer_ && posed.meshes[m].deformation) continue;
    const uint64_t first = uint64_t(geometry_.mesh_first_vertex[m]) * sizeof(gpu::GpuVertex);
    rows.push_back({first, first, posed.meshes[m].positions.size() * sizeof(gpu::GpuVertex)});
  }
  return rows;
}

SceneChange SceneGpu::update(const scenes::Scene& posed) {
  SceneChange change = SceneChange::None;
  // What moved: the file's meshes, and the particles, which move whenever there are any (the
  // GPU places them). When only they did, the host uploads nothing of the file's, and its
  // flattened arrays stay as they are (compared in place, not copied: a still file of a
  // million triangles costs a read instead of 0.3 s of copies a frame); only the particles'
  // places after them are counted again.
  // When the file's layout held but some of its meshes moved (rigid animation of a few nodes,
  // a skinned character in a still level), only those meshes' vertices go up, and only the
  // tree's nodes above their triangles are refitted and uploaded: a walker in a level of a
  // million triangles no longer costs a million triangles' flattening, copies and uploads a
  // frame. Everything goes up again when the layout changed, when the emissive triangles
  // listed did, or when the refit made the tree too costly (refit_meshes).
  auto has_particles = [](const FlatGeometry& f) { return f.vertex_count > f.positions.size(); };
  FileChange file = file_change(posed);
  const bool file_moved = !file.layout || (!file.moved.empty() && !refit_meshes(posed, file.moved));
  if (file_moved) file.moved.clear();
  const bool had_particles = has_particles(geometry_);
  FlatGeometry moved_file;
  if (file_moved) {
    moved_file = flatten(posed);
  } else {
    size_t file_meshes = 0;
    while (file_meshes < posed.meshes.size() && posed.meshes[file_meshes].emitter < 0) ++file_meshes;
    geometry_.mesh_first_vertex.resize(file_meshes);
    geometry_.mesh_first_triangle.resize(file_meshes);
    geometry_.vertex_count = uint32_t(geometry_.positions.size());
    geometry_.triangle_count = uint32_t(geometry_.triangles.size());
    for (size_t m = file_meshes; m < posed.meshes.size(); ++m) add_stage_places(posed.meshes[m], geometry_);
  }
  const FlatGeometry& g = file_moved ? moved_file : geometry_;
  const bool moved = file_moved || !file.moved.empty() || has_particles(g) || had_particles;
  // The deforming meshes keep their places in the vertex array (they keep every vertex) unless
  // a mesh before them changed its vertex count; then the pass is made anew. (Particles, whose
  // count changes every frame, come after every mesh of the file.)
  const bool keep_deformed = deformer_ && deformer_->fits(g);
  if (keep_deformed) rigid_ranges_ = rigid_ranges(posed, g);

  // The previous frame's vertices in this frame's layout, for motion vectors: a mesh whose
  // vertices are where they were keeps its last ones; meshes whose vertex count changed get
  // this frame's, that is no motion. The deformation pass saves its own vertices' before
  // overwriting them, the particle pass writes where each particle was (a particle is not at
  // the same index from frame to frame). Where the file, or a mesh of it, moved at the last
  // update but not now, its previous vertices are its vertices; where it moved neither now
  // nor then, they already are.
  grow(previous_vertices_, uint64_t(g.vertex_count) * sizeof(gpu::GpuVertex), g.positions.size() * sizeof(gpu::GpuVertex));
  std::vector<glm::vec4> moved_previous;
  if (file_moved) {
    moved_previous = vertex_rows(g);
    for (size_t m = 0; m < posed.meshes.size() && m < geometry_.mesh_first_vertex.size(); ++m) {
      if (posed.meshes[m].emitter >= 0) continue;
      const size_t first = g.mesh_first_vertex[m], count = posed.meshes[m].positions.size();
      const size_t old_first = geometry_.mesh_first_vertex[m];
      const size_t old_end = m + 1 < geometry_.mesh_first_vertex.size() ? geometry_.mesh_first_vertex[m + 1] : geometry_.vertex_count;
      if (old_end - old_first != count) continue;
      std::copy(vertices_host_.begin() + long(2 * old_first), vertices_host_.begin() + long(2 * (old_first + count)),
                moved_previous.begin() + long(2 * first));
    }
  }
  if (file_moved || file_moved_last_) {
    const std::vector<glm::vec4>& previous = file_moved ? moved_previous : vertices_host_;
    if (keep_deformed)
      previous_vertices_.upload_ranges(previous.data(), rigid_ranges_);
    else if (!previous.empty())
      previous_vertices_.upload(previous.data(), previous.size() * sizeof(glm::vec4));
  } else {
    // The host's rows are still the last update's: the moved meshes' previous vertices, and
    // the vertices of those that moved then.
    std::vector<uint32_t> meshes = file.moved;
    meshes.insert(meshes.end(), meshes_moved_last_.begin(), meshes_moved_last_.end());
    previous_vertices_.upload_ranges(vertices_host_.data(), mesh_rows(posed, meshes));
  }
  file_moved_last_ = file_moved;
  meshes_moved_last_ = file.moved;
  if (!file.moved.empty()) upload_meshes(posed, file.moved);

  if (moved) {
    // The CPU's tree holds every triangle but the particles' (which are not in `g`).
    const bool same_triangles = !file_moved || (g.positions.size() == geometry_.positions.size() && g.triangles == geometry_.triangles);
    upload_geometry(posed, file_moved ? std::move(moved_file) : std::move(geometry_), same_triangles, keep_deformed, file_moved);
    change = SceneChange::Geometry;
  }
  if (deformer_) {
    if (!keep_deformed) make_deformer(posed);
    deformer_->set_pose(posed);
  }
  prepare_particles(posed);
  // Every frame, moved or not, so that the previous vertices become the current ones.
  if (deformer_ || !particles_.empty())
    ctx_->submit_and_wait([&](VkCommandBuffer cmd) {
      record_particles(cmd, posed);
      record_deformation(cmd, keep_deformed, file_moved || !file.moved.empty());
    });
  if (upload_lights(posed) && change == SceneChange::None) change = SceneChange::Lights;
  return change;
}

}  // namespace giq::realtime
