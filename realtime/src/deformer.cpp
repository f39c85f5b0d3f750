#include "giq/realtime/deformer.h"

#include <map>
#include <stdexcept>

#include "giq/realtime/context.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/shader.h"
#include "shaders/deform_shared.h"

namespace giq::realtime {

namespace {
constexpr uint32_t kBindings = 11;
}

Deformer::Deformer(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& scene, const FlatGeometry& geometry, bool tangents)
    : ctx_(&ctx),
      pipeline_(Pipeline::compute(ctx, compiler.compile("shaders/deform.comp"),
                                  std::vector<VkDescriptorType>(kBindings, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER), 2 * sizeof(uint32_t))) {
  using namespace gpu;
  std::vector<GpuRestVertex> rest, displacements;
  std::vector<GpuInfluence> influences;
  std::vector<glm::uvec2> slots;
  std::vector<glm::uvec4> triangles;
  // Where each rest pose went: instances of one primitive share theirs.
  struct Placed {
    uint32_t first_vertex, first_triangle, first_influence, first_displacement;
  };
  std::map<const scenes::DeformationRest*, Placed> placed;
  uint32_t matrices = 0, weights = 0;

  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    if (!mesh.deformation) continue;
    const scenes::DeformationRest& r = *mesh.deformation->rest;
    const uint32_t n = uint32_t(r.positions.size());
    auto [it, fresh] = placed.try_emplace(&r, Placed{uint32_t(rest.size()), uint32_t(triangles.size()), uint32_t(influences.size()),
                                                     uint32_t(displacements.size())});
    if (fresh) {
      for (uint32_t i = 0; i < n; ++i) {
        GpuRestVertex v{glm::vec4(r.positions[i], 1.0f), glm::vec4(0.0f), glm::vec4(0.0f)};
        if (i < r.normals.size()) v.normal = glm::vec4(r.normals[i], 0.0f);
        if (i < r.tangents.size()) v.tangent = r.tangents[i];
        rest.push_back(v);
      }
      for (const glm::uvec3& t : r.triangles) triangles.emplace_back(t, 0u);
      for (size_t set = 0; set < r.joints.size(); ++set)
        for (uint32_t i = 0; i < n; ++i) influences.push_back({r.joints[set][i], r.weights[set][i]});
      // A target without an attribute displaces it by zero, which adds nothing.
      for (const scenes::MorphTarget& t : r.targets)
        for (uint32_t i = 0; i < n; ++i)
          displacements.push_back({glm::vec4(i < t.positions.size() ? t.positions[i] : glm::vec3(0.0f), 0.0f),
                                   glm::vec4(i < t.normals.size() ? t.normals[i] : glm::vec3(0.0f), 0.0f),
                                   glm::vec4(i < t.tangents.size() ? t.tangents[i] : glm::vec3(0.0f), 0.0f)});
    }
    const Placed& p = it->second;
    const bool flat = r.normals.empty();
    const uint32_t count = flat ? 3 * uint32_t(r.triangles.size()) : n;
    if (count != mesh.positions.size())
      throw std::logic_error("Deformer: mesh " + mesh.name + " has " + std::to_string(mesh.positions.size()) + " vertices; its rest pose makes " +
                             std::to_string(count));
    const uint32_t flags = (flat ? GIQ_DEFORM_FLAT : 0u) | (tangents && !r.tangents.empty() ? GIQ_DEFORM_TANGENTS : 0u);
    const uint32_t record = uint32_t(meshes_.size());
    // The triangle whose face replaces a collapsed normal: the last one using the vertex, as
    // scenes/src/pose.cpp (there the last that has not collapsed at this instant).
    std::vector<uint32_t> fallback(flat ? 0 : n, GIQ_DEFORM_NO_TRIANGLE);
    for (uint32_t k = 0; k < uint32_t(r.triangles.size()) && !flat; ++k)
      for (int c = 0; c < 3; ++c) fallback[r.triangles[k][c]] = k;
    for (uint32_t i = 0; i < count; ++i) slots.emplace_back(record, flat ? GIQ_DEFORM_NO_TRIANGLE : fallback[i]);

    const glm::uvec4 rows[4] = {{slot_count_, count, geometry.mesh_first_vertex[m], flags},
                                {p.first_vertex, n, p.first_triangle, p.first_influence},
                                {matrices, uint32_t(mesh.deformation->joints.size()), weights, uint32_t(r.targets.size())},
                                {mesh.deformation->skinned ? uint32_t(r.joints.size()) : 0u, p.first_displacement, 0u, 0u}};
    records_host_.insert(records_host_.end(), std::begin(rows), std::end(rows));
    meshes_.push_back(m);
    base_flags_.push_back(flags);
    slot_count_ += count;
    matrices += uint32_t(mesh.deformation->joints.size());
    weights += uint32_t(r.targets.size());
  }
  static_assert(sizeof(GpuDeformMesh) == 4 * sizeof(glm::uvec4));
  rest_ = Buffer::storage(ctx, rest);
  displacements_ = Buffer::storage(ctx, displacements);
  influences_ = Buffer::storage(ctx, influences);
  slots_ = Buffer::storage(ctx, slots);
  rest_triangles_ = Buffer::storage(ctx, triangles);
  matrices_ = Buffer::storage(ctx, std::vector<glm::mat4>(matrices));
  weights_ = Buffer::storage(ctx, std::vector<float>(weights));
  records_ = Buffer::storage(ctx, records_host_);
  set_pose(scene);
}

std::vector<std::pair<uint32_t, uint32_t>> Deformer::ranges() const {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  for (size_t k = 0; k < meshes_.size(); ++k) out.emplace_back(records_host_[4 * k].z, records_host_[4 * k].y);
  return out;
}

bool Deformer::fits(const FlatGeometry& g) const {
  for (size_t k = 0; k < meshes_.size(); ++k)
    if (meshes_[k] >= g.mesh_first_vertex.size() || g.mesh_first_vertex[meshes_[k]] != records_host_[4 * k].z) return false;
  return true;
}

void Deformer::set_pose(const scenes::Scene& posed) {
  if (empty()) return;
  std::vector<glm::mat4> matrices;
  std::vector<float> weights;
  for (size_t k = 0; k < meshes_.size(); ++k) {
    const scenes::Mesh& mesh = posed.meshes.at(meshes_[k]);
    const glm::uvec4* record = &records_host_[4 * k];
    if (!mesh.deformation || mesh.deformation->joints.size() != record[2].y || mesh.deformation->weights.size() != record[2].w ||
        (mesh.deformation->skinned ? record[3].x == 0 : record[3].x != 0))
      throw std::logic_error("Deformer::set_pose: mesh " + mesh.name + " is not deformed as it was");
    matrices.insert(matrices.end(), mesh.deformation->joints.begin(), mesh.deformation->joints.end());
    weights.insert(weights.end(), mesh.deformation->weights.begin(), mesh.deformation->weights.end());
    records_host_[4 * k].w = base_flags_[k] | (mesh.deformation->mirrored ? GIQ_DEFORM_MIRRORED : 0u);
  }
  if (!matrices.empty()) matrices_.upload(matrices.data(), matrices.size() * sizeof(glm::mat4));
  if (!weights.empty()) weights_.upload(weights.data(), weights.size() * sizeof(float));
  records_.upload(records_host_.data(), records_host_.size() * sizeof(glm::uvec4));
}

void Deformer::record(VkCommandBuffer cmd, const Buffer& vertices, const Buffer& previous, const Buffer& vertex_extra,
                      bool save_previous) const {
  if (empty()) return;
  pipeline_.bind(cmd);
  pipeline_.push_descriptors(cmd, {Descriptor::storage(vertices), Descriptor::storage(previous), Descriptor::storage(vertex_extra),
                                   Descriptor::storage(rest_), Descriptor::storage(displacements_), Descriptor::storage(influences_),
                                   Descriptor::storage(matrices_), Descriptor::storage(weights_), Descriptor::storage(records_),
                                   Descriptor::storage(slots_), Descriptor::storage(rest_triangles_)});
  const uint32_t push[2] = {slot_count_, save_previous ? 1u : 0u};
  pipeline_.push_constants(cmd, push, sizeof(push));
  pipeline_.dispatch_1d(cmd, slot_count_);
}

}  // namespace giq::realtime
