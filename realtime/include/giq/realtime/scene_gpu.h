#pragma once
// The scene on the GPU for every technique: vertices, triangles, materials, the BVH, punctual
// lights, the emissive triangles with their power CDF and, for textured scenes, texture
// coordinates, tangents and texels, bound as bindings 0..9 of any pipeline that reads the
// scene (shaders/scene_shared.h, shaders/scene.glsl). An animated scene is uploaded once and
// then updated per frame with the posed scene: what moved is re-uploaded (and the BVH refitted
// or rebuilt when geometry moved), so pipelines must take descriptors() when they record,
// never keep them across frames. Skinned and morphing meshes are deformed on the GPU
// (Deformer) from their rest pose each frame; each emitter's particles are simulated on the GPU
// (ParticleSystem) and written there as the octahedra every pass draws and traces (their
// vertices, triangles, indices and emissive triangles), with a tree of their own built there
// each frame (LinearBvh), and a light tree over them for the passes that light by cluster of
// particles, beside the CPU's tree of the other triangles, whose bounds are
// refitted there after the deformation (BvhRefitter). The host needs only each stage's
// particle count (a scene posed with scenes::ParticleDetail::Counted); where a stage's
// particles are comes back from the GPU (ParticleBounds, complete()).
//
// All meshes are concatenated in Scene::meshes order; a triangle's global index (reported by
// ray queries) is its mesh's offset plus its index in the mesh.

#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "giq/realtime/bvh.h"
#include "giq/realtime/bvh_refitter.h"
#include "giq/realtime/deformer.h"
#include "giq/realtime/linear_bvh.h"
#include "giq/realtime/particle_bounds.h"
#include "giq/realtime/particle_system.h"
#include "giq/realtime/pipeline.h"
#include "giq/realtime/resources.h"
#include "giq/realtime/technique.h"
#include "giq/scenes/scene.h"

namespace giq::realtime {

class Context;

// The scene's meshes in the GPU's arrays. The file's meshes' vertices and triangles are here;
// the particles' (the stage meshes, which come after them: Mesh::particles, six vertices and
// eight triangles each) only have their places, since the GPU writes them, unless asked for
// (`placed`: a scene that placed its particles, the CPU's counterpart of what the GPU holds).
struct FlatGeometry {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::uvec3> triangles;  // global vertex indices
  std::vector<uint32_t> material;     // per triangle
  std::vector<uint32_t> object_id;    // per triangle
  std::vector<uint32_t> mesh_first_triangle;  // every mesh's, the particle stages' too
  std::vector<uint32_t> mesh_first_vertex;
  uint32_t vertex_count = 0, triangle_count = 0;  // with the particles'
};
FlatGeometry flatten(const scenes::Scene& scene, bool placed = false);
// What the views from an area light's representative point (its shadow cube, its reflective
// shadow map) leave out, as vertices [x, x + y) and triangles [z, z + w) of `g`: the light's
// own mesh, whose faces would hide a closed emitter's light from its centre; for a stage of
// glowing particles, every particle mesh next to it (the scene library places them together,
// after the file's meshes), since from the one point at a stage's centroid the particles of the
// other stages around it would cast shadows metres wide.
glm::uvec4 own_geometry(const scenes::Scene& scene, const FlatGeometry& g, uint32_t mesh);

// Where each texture's texel words go: textures of `words` words each, in scene order, packed
// into chunks of at most `chunk_words` (next fit). chunk[i] is -1 for a texture larger than a
// chunk (the caller refuses it); an empty texture gets chunk 0, offset 0 and no words.
struct TexelPacking {
  std::vector<int> chunk;
  std::vector<uint64_t> first_word;
  std::vector<uint64_t> chunk_words;  // the words each chunk holds
};
TexelPacking pack_texels(const std::vector<uint64_t>& words, uint64_t chunk_words);

// Mip levels of a width x height texture down to 1 x 1, each side max(1, side >> level)
// (shaders/textures.glsl's mip_size), and the texels of levels 0..levels-1 together.
uint32_t mip_levels(uint32_t width, uint32_t height);
uint64_t mip_chain_texels(uint32_t width, uint32_t height, uint32_t levels);

class GpuTimer;
class ShaderCompiler;

class SceneGpu {
 public:
  // Textures whose sampler asks for mip maps get their levels made on the GPU
  // (shaders/texture_mips.comp), hence the compiler.
  SceneGpu(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene);
  ~SceneGpu();  // where gpu::GpuParticleStage is complete

  // Brings the buffers to `posed` (the same scene at another time: same meshes, materials and
  // lights, moved) and says what moved. The vertices before the call become previous_vertices().
  SceneChange update(const scenes::Scene& posed);
  // Gives `posed`, the scene of the last update (or of the constructor), what its particles'
  // places decide and only the GPU knows when the scene counted them: each glowing stage's
  // area light at the centroid of its particles as drawn, with the extent that holds them
  // (scenes::AreaLight::centroid, representative, extent), and the bounds grown to hold
  // them. Placed particles get the same, from the GPU's octahedra. Nothing without emitters.
  void complete(scenes::Scene& posed);

  static std::vector<VkDescriptorType> binding_types();  // GIQ_SCENE_BINDING_COUNT storage buffers
  std::vector<Descriptor> descriptors() const;

  const Buffer& index_buffer() const { return indices_; }  // uint32 triples, for rasterisation
  uint32_t triangle_count() const { return triangle_count_; }
  uint32_t light_count() const { return light_count_; }
  uint32_t emissive_count() const { return emissive_count_; }
  // The tree as built or refitted on the CPU over every triangle but the particles'; with
  // deforming meshes, the GPU's copy has the same topology and bounds refitted to the vertices
  // the GPU deformed.
  const Bvh& bvh() const { return bvh_; }
  // How the last change of the file's geometry (not the particles') reached the BVH: built
  // anew, or refitted (the same triangles moved: skinning, morph targets, rigid animation)
  // while the refitted tree's SAH cost stays within kMaxRefitCost of the cost it had when
  // built.
  enum class BvhUpdate { Built, Refitted };
  BvhUpdate last_bvh_update() const { return last_bvh_update_; }
  double bvh_cost_growth() const { return built_cost_ > 0.0 ? sah_cost(bvh_) / built_cost_ : 1.0; }
  static constexpr double kMaxRefitCost = 1.3;
  // GpuVertex array of the frame before the last update() (the current one before any), for
  // motion vectors.
  const Buffer& previous_vertices() const { return previous_vertices_; }
  // The GpuVertex array, the GpuVertexExtra array (textured scenes) and the BVH's nodes and
  // prims as the GPU holds them (tests compare deformed vertices and the trees' bounds with
  // the CPU's). With particles, node 0 is a root over the CPU's tree, from node
  // cpu_tree_offset() = 1 on, and the particles' tree, built on the GPU (LinearBvh).
  const Buffer& vertices() const { return vertices_; }
  const Buffer& triangles() const { return triangles_; }  // GpuTriangle
  const Buffer& emissive() const { return emissive_; }    // GpuEmissive
  const Buffer& vertex_extra() const { return vertex_extra_; }
  const Buffer& bvh_nodes() const { return nodes_; }
  const Buffer& bvh_prims() const { return prims_; }
  uint32_t cpu_tree_offset() const { return particle_bvh_ ? 1 : 0; }
  // Vertices deformed on the GPU each frame (0 without skins and morph targets).
  uint32_t deformed_vertex_count() const { return deformer_ ? deformer_->vertex_count() : 0; }
  // Records what update() runs for deforming meshes: the deformation pass at the pose of the
  // last update (`save_previous`: copying each vertex to the previous vertices first), then,
  // when `refit`, the BVH refit, each between timestamps of `timer` when given ("deform",
  // "bvh refit"). Nothing without deforming meshes.
  void record_deformation(VkCommandBuffer cmd, bool save_previous, bool refit, GpuTimer* timer = nullptr) const;
  // Particles written by the GPU's simulation each update (0 without emitters).
  uint32_t particle_vertex_count() const { return particle_vertices_; }
  uint32_t first_particle_vertex() const { return uint32_t(geometry_.positions.size()); }
  // The light tree over the glowing particles, built on the GPU each update (LinearBvh's
  // LightTree, leaf j the particle at first_particle_vertex() + 6 j), for the passes that
  // light by cluster of particles; null when no stage glows, or when there are more stages
  // than it holds. A stage's subtree is at stage_roots[particle_light_slot(its material)].
  const LinearBvh::LightTree* particle_light_tree() const { return light_bvh_ ? &light_tree_ : nullptr; }
  uint32_t particle_light_slot(uint32_t material) const { return material - stage_material_; }
  const FlatGeometry& geometry() const { return geometry_; }
  const scenes::Bounds& bounds() const { return bounds_; }  // of the geometry now uploaded
  // After complete(): per light of the scene (scenes::Scene::lights), at most the distance
  // from it to the nearest particle's surface as the GPU drew them, infinity for a
  // directional light; empty without particles. What bounds the irradiance a particle
  // receives, which the host cannot take from particles it only counted.
  const std::vector<float>& particle_light_distances() const { return particle_light_distance_; }
  // The FeatureSet the scene was uploaded for; passes compile their shaders with its defines.
  const scenes::FeatureSet& features() const { return features_; }
  uint32_t texture_count() const { return texture_count_; }
  uint64_t texture_bytes() const { return texture_bytes_; }  // texel buffers (mip levels included) and decode table
  // The largest texel buffer SceneGpu makes (smaller where the device's largest allocation is).
  static constexpr uint64_t kTexelChunkBytes = 1ull << 30;

 private:
  void upload_materials(const scenes::Scene& scene, std::vector<uint32_t>& mip_levels);
  void make_mips(ShaderCompiler& compiler, const scenes::Scene& scene, const std::vector<uint32_t>& mip_levels);
  // `may_refit`: the triangles are those of the BVH already built, only moved. `keep_deformed`:
  // the deforming meshes' vertices stay where they are in the buffers (the deformation pass
  // writes them), only the others are uploaded. `file_moved` false: only the particles moved,
  // so the file's vertices, triangles and tree stay as they are on both sides (its emissive
  // triangles' CDF, which the particles' power changes, is uploaded again).
  void upload_geometry(const scenes::Scene& scene, FlatGeometry flat, bool may_refit = false, bool keep_deformed = false,
                       bool file_moved = true);
  // The deformer for `scene`'s deforming meshes (none without), the vertex ranges of the
  // other meshes, and the GPU refit of the BVH (made once).
  void make_deformer(const scenes::Scene& scene);
  // GpuVertex rows of `g`'s vertices (the particles' are the GPU's); the bytes of the vertex
  // array that no deformation writes.
  static std::vector<glm::vec4> vertex_rows(const FlatGeometry& g);
  static std::vector<VkBufferCopy> rigid_ranges(const scenes::Scene& scene, const FlatGeometry& g);
  // Grows `buffer` to hold `bytes` (twice that where counts change: with particles, or once it
  // has grown), carrying over its first `keep` bytes (what the GPU wrote there, the deformed
  // vertices, or what the host will not upload again); true when it made a new buffer.
  bool grow(Buffer& buffer, uint64_t bytes, uint64_t keep, VkBufferUsageFlags extra = 0);
  // Where the GPU writes each stage's particles (gpu::GpuParticleStage), given the emissive
  // triangles the host lists, `fixed` of them with `power` in all: the stages' CDF runs on
  // from the host's. Sets emissive_count_; returns the power of all emissive triangles.
  double place_particle_stages(const scenes::Scene& scene, uint32_t fixed, double power);
  bool upload_lights(const scenes::Scene& scene);  // false when nothing changed
  // What of `posed`'s file meshes (all but the particles') differs from geometry_. `layout`:
  // the same meshes with the same vertex counts, triangles, materials and object ids in the
  // same places; then `moved` lists those whose vertices or normals moved (in mesh order).
  struct FileChange {
    bool layout = false;
    std::vector<uint32_t> moved;
  };
  FileChange file_change(const scenes::Scene& posed) const;
  // For a file whose layout held: `meshes`' vertices and normals into geometry_, and the CPU's
  // tree refitted over their triangles alone (refitted_nodes_). False when the emissive
  // triangles listed changed, or the refit left the tree over kMaxRefitCost times as costly
  // as built: then the whole file goes up again.
  bool refit_meshes(const scenes::Scene& posed, const std::vector<uint32_t>& meshes);
  // Uploads what refit_meshes changed: the meshes' vertex rows (not those the deformation
  // pass writes), their tangents, and the refitted nodes.
  void upload_meshes(const scenes::Scene& posed, const std::vector<uint32_t>& meshes);
  // The byte ranges of `meshes`' rows in the GpuVertex arrays (not those the deformation
  // pass writes).
  std::vector<VkBufferCopy> mesh_rows(const scenes::Scene& posed, const std::vector<uint32_t>& meshes) const;
  // Brings each emitter's GPU particles to `posed`'s time.
  void prepare_particles(const scenes::Scene& posed);
  // The particle passes, then their tree (LinearBvh) and their stages' bounds (ParticleBounds),
  // with how near they come to `posed`'s punctual lights.
  void record_particles(VkCommandBuffer cmd, const scenes::Scene& posed);

  Context* ctx_;
  ShaderCompiler* compiler_;
  std::unique_ptr<Deformer> deformer_;
  std::unique_ptr<BvhRefitter> refitter_;
  std::vector<std::unique_ptr<ParticleSystem>> particles_;  // one per emitter
  std::unique_ptr<LinearBvh> particle_bvh_;                 // with emitters
  std::unique_ptr<ParticleBounds> particle_bounds_;         // with emitters
  std::unique_ptr<LinearBvh> light_bvh_;                    // with glowing particles
  LinearBvh::LightTree light_tree_;
  uint32_t stage_material_ = 0;  // the material of the first emitter's first stage
  uint32_t fixed_triangles_ = 0;  // the triangles before the particles', in the CPU's tree
  std::vector<std::vector<gpu::GpuParticleStage>> stages_;  // per emitter, of each stage's mesh
  std::vector<uint32_t> stage_mesh_;                        // the mesh of each stage, emitter by emitter
  double frame_seconds_ = 0.0;
  uint32_t particle_vertices_ = 0;
  std::vector<VkBufferCopy> rigid_ranges_;  // bytes of the GpuVertex array that no deformation writes
  FlatGeometry geometry_;
  scenes::Bounds bounds_;
  std::vector<float> particle_light_distance_;  // per light (particle_light_distances())
  scenes::FeatureSet features_;
  Bvh bvh_;
  double built_cost_ = 0.0;  // sah_cost(bvh_) when last built
  BvhUpdate last_bvh_update_ = BvhUpdate::Built;
  bool file_moved_last_ = false;  // the whole file went up at the last update
  std::vector<uint32_t> meshes_moved_last_;  // or these meshes of it alone (upload_meshes)
  std::vector<glm::uvec2> emissive_listed_;  // the file's emissive triangles listed (mesh, triangle)
  std::vector<uint8_t> moved_triangles_;     // refit_meshes' working arrays
  std::vector<uint32_t> refitted_nodes_;
  // What the vertex and light buffers hold (gpu::GpuVertex, gpu::GpuLight as vec4 rows).
  std::vector<glm::vec4> vertices_host_, lights_host_;
  Buffer vertices_, triangles_, materials_, nodes_, prims_, lights_, emissive_, indices_, previous_vertices_;
  Buffer vertex_extra_, textures_, decode_;
  std::vector<Buffer> texel_chunks_;  // read through device addresses (GpuTexture::texels)
  uint32_t triangle_count_ = 0, light_count_ = 0, emissive_count_ = 0, texture_count_ = 0;
  uint64_t texture_bytes_ = 0;
};

}  // namespace giq::realtime
