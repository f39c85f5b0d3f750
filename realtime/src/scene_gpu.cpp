#include "giq/realtime/scene_gpu.h"

#include <cmath>
#include <cstring>

#include "giq/base/error.h"
#include "giq/realtime/context.h"
#include "shaders/scene_shared.h"

namespace giq::realtime {

FlatGeometry flatten(const scenes::Scene& scene) {
  FlatGeometry g;
  for (const auto& m : scene.meshes) {
    const uint32_t base = uint32_t(g.positions.size());
    g.mesh_first_triangle.push_back(uint32_t(g.triangles.size()));
    for (size_t i = 0; i < m.positions.size(); ++i) {
      g.positions.push_back(m.positions[i]);
      g.normals.push_back(i < m.normals.size() ? m.normals[i] : glm::vec3(0.0f));
    }
    for (const auto& t : m.triangles) {
      g.triangles.push_back(t + glm::uvec3(base));
      g.material.push_back(uint32_t(m.material));
      g.object_id.push_back(m.object_id);
    }
  }
  return g;
}

namespace {
// Features the real-time module does not render are refused at load time: a silently
// different image would be compared with the reference as if it were right.
void require_supported(const scenes::Scene& scene) {
  const std::pair<bool, const char*> unsupported[] = {{scene.features.textures, "textures"},
                                                      {scene.features.normal_maps, "normal_maps"},
                                                      {scene.features.alpha_mask, "alpha_mask"}};
  for (const auto& [present, name] : unsupported)
    if (present)
      throw InputError(scene.path.string(), "features",
                       std::string("the scene uses ") + name +
                           ", which giq realtime does not render; expected a scene without " + name);
}
}  // namespace

SceneGpu::SceneGpu(Context& ctx, const scenes::Scene& scene) : ctx_(&ctx) {
  require_supported(scene);
  upload_geometry(scene, flatten(scene));
  previous_vertices_ = Buffer::storage(ctx, vertices_host_);
  upload_lights(scene);
}

SceneChange SceneGpu::update(const scenes::Scene& posed) {
  // The previous frame's vertices, for motion vectors: what is current now, before it moves.
  previous_vertices_.upload(vertices_host_.data(), vertices_host_.size() * sizeof(glm::vec4));
  SceneChange change = SceneChange::None;
  FlatGeometry g = flatten(posed);
  if (g.positions != geometry_.positions || g.normals != geometry_.normals) {
    upload_geometry(posed, std::move(g));
    change = SceneChange::Geometry;
  }
  if (upload_lights(posed) && change == SceneChange::None) change = SceneChange::Lights;
  return change;
}

void SceneGpu::upload_geometry(const scenes::Scene& scene, FlatGeometry flat) {
  using namespace gpu;
  Context& ctx = *ctx_;
  geometry_ = std::move(flat);
  triangle_count_ = uint32_t(geometry_.triangles.size());
  bvh_ = build_bvh(geometry_.positions, geometry_.triangles);

  static_assert(sizeof(GpuVertex) == 2 * sizeof(glm::vec4));
  vertices_host_.clear();
  for (size_t i = 0; i < geometry_.positions.size(); ++i)
    vertices_host_.insert(vertices_host_.end(), {glm::vec4(geometry_.positions[i], 1.0f), glm::vec4(geometry_.normals[i], 0.0f)});
  // Emissive triangles: chosen by power, as the reference does; the CDF is accumulated in
  // double so that a million small lights still end at exactly 1.
  std::vector<GpuEmissive> emissive;
  std::vector<uint32_t> emissive_of_triangle(triangle_count_, 0);
  double total = 0.0;
  for (const auto& e : scene.emissive_triangles) total += std::max(0.0f, e.power);
  double acc = 0.0;
  for (const auto& e : scene.emissive_triangles) {
    if (!(total > 0.0) || !(e.power > 0.0f)) continue;
    const uint32_t tri = geometry_.mesh_first_triangle[e.mesh] + e.triangle;
    acc += e.power;
    GpuEmissive g;
    g.triangle = glm::uvec4(tri, 0, 0, 0);
    g.radiance = glm::vec4(e.radiance, e.area);
    g.sampling = glm::vec4(float(acc / total), float(e.power / total), 0.0f, 0.0f);
    emissive.push_back(g);
    emissive_of_triangle[tri] = uint32_t(emissive.size());
  }
  if (!emissive.empty()) emissive.back().sampling.x = 1.0f;
  emissive_count_ = uint32_t(emissive.size());

  std::vector<GpuTriangle> triangles(triangle_count_);
  std::vector<uint32_t> indices;
  indices.reserve(3 * triangle_count_);
  for (uint32_t i = 0; i < triangle_count_; ++i) {
    const auto t = geometry_.triangles[i];
    triangles[i].v = glm::uvec4(t, geometry_.material[i]);
    triangles[i].extra = glm::uvec4(emissive_of_triangle[i], geometry_.object_id[i], 0, 0);
    indices.insert(indices.end(), {t.x, t.y, t.z});
  }

  std::vector<GpuMaterial> materials;
  for (const auto& m : scene.materials) {
    GpuMaterial g;
    g.base_color = glm::vec4(glm::vec3(m.base_color), 1.0f);
    g.emissive = glm::vec4(m.emissive, m.is_emissive() ? 1.0f : 0.0f);
    g.specular_color = glm::vec4(m.specular_color, 0.0f);
    g.params = glm::vec4(m.metallic, m.roughness, m.has_specular_lobe() ? m.specular : 0.0f, m.double_sided ? 1.0f : 0.0f);
    materials.push_back(g);
  }

  std::vector<GpuBvhNode> nodes(bvh_.nodes.size());
  static_assert(sizeof(GpuBvhNode) == sizeof(BvhNode));
  std::memcpy(nodes.data(), bvh_.nodes.data(), nodes.size() * sizeof(GpuBvhNode));

  vertices_ = Buffer::storage(ctx, vertices_host_);
  triangles_ = Buffer::storage(ctx, triangles);
  materials_ = Buffer::storage(ctx, materials);
  nodes_ = Buffer::storage(ctx, nodes);
  prims_ = Buffer::storage(ctx, bvh_.prims);
  emissive_ = Buffer::storage(ctx, emissive);
  indices_ = Buffer::storage(ctx, indices, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
}

bool SceneGpu::upload_lights(const scenes::Scene& scene) {
  using namespace gpu;
  std::vector<GpuLight> lights;
  for (const auto& l : scene.lights) {
    GpuLight g;
    const float type = l.type == scenes::LightType::Directional ? GIQ_LIGHT_DIRECTIONAL
                       : l.type == scenes::LightType::Point     ? GIQ_LIGHT_POINT
                                                                : GIQ_LIGHT_SPOT;
    g.position = glm::vec4(l.position, type);
    g.direction = glm::vec4(glm::normalize(l.direction), l.range);
    g.radiant = glm::vec4(l.radiant(), 0.0f);
    // KHR_lights_punctual's recommended spot falloff, precomputed in the same float
    // arithmetic as scenes::spot_attenuation so the GPU evaluates the identical ramp.
    const float cos_outer = std::cos(l.outer_cone);
    const float scale = 1.0f / std::max(0.001f, std::cos(l.inner_cone) - cos_outer);
    g.cone = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    lights.push_back(g);
  }
  light_count_ = uint32_t(lights.size());
  static_assert(sizeof(GpuLight) % sizeof(glm::vec4) == 0);
  const size_t bytes = lights.size() * sizeof(GpuLight);
  if (lights_ && bytes == lights_host_.size() * sizeof(glm::vec4) &&
      std::memcmp(lights.data(), lights_host_.data(), bytes) == 0)
    return false;
  lights_ = Buffer::storage(*ctx_, lights);
  lights_host_.resize(bytes / sizeof(glm::vec4));
  std::memcpy(lights_host_.data(), lights.data(), bytes);
  return true;
}

std::vector<VkDescriptorType> SceneGpu::binding_types() {
  return std::vector<VkDescriptorType>(GIQ_SCENE_BINDING_COUNT, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

std::vector<Descriptor> SceneGpu::descriptors() const {
  return {Descriptor::storage(vertices_), Descriptor::storage(triangles_), Descriptor::storage(materials_),
          Descriptor::storage(nodes_),    Descriptor::storage(prims_),     Descriptor::storage(lights_),
          Descriptor::storage(emissive_)};
}

}  // namespace giq::realtime
