// SceneGpu's particles (scene_gpu.h): where each stage's particles go in the scene's arrays,
// the passes that write them there, and what comes back from the GPU about where they are.
#include <algorithm>
#include <limits>
#include <numbers>

#include "giq/realtime/scene_gpu.h"
#include "shaders/particles_shared.h"
#include "shaders/scene_shared.h"

namespace giq::realtime {

void SceneGpu::prepare_particles(const scenes::Scene& posed) {
  if (particles_.empty()) return;
  frame_seconds_ = 1.0 / posed.sequence.fps;
  particle_vertices_ = geometry_.vertex_count - uint32_t(geometry_.positions.size());
  for (const auto& p : particles_) p->prepare(posed.time);
}

double SceneGpu::place_particle_stages(const scenes::Scene& scene, uint32_t fixed, double power) {
  stages_.assign(particles_.size(), {});
  stage_mesh_.clear();
  // Each glowing stage's triangles all have one power (the scene library's, from the face's
  // closed-form area), chosen in proportion to it like the host's emissive triangles.
  std::vector<double> face_power;
  const double host = power;
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const scenes::Mesh& mesh = scene.meshes[m];
    if (mesh.emitter < 0 || size_t(mesh.emitter) >= particles_.size()) continue;
    const scenes::Emitter& e = scene.emitters[size_t(mesh.emitter)];
    const scenes::Material& mat = scene.materials[size_t(mesh.material)];
    const float area = float(e.face_area());
    const glm::vec3 radiance = mat.is_emissive() ? mat.emissive : glm::vec3(0.0f);
    const double p = std::numbers::pi * double(area) * scenes::luminance(radiance) * (mat.double_sided ? 2.0 : 1.0);
    const bool glows = p > 0.0 && (radiance.r > 0.0f || radiance.g > 0.0f || radiance.b > 0.0f);
    gpu::GpuParticleStage st{};
    st.first = glm::uvec4(geometry_.mesh_first_vertex[m], 0u, geometry_.mesh_first_triangle[m], 0u);
    st.triangle = glm::uvec4(uint32_t(mesh.material), mesh.object_id, GIQ_TRIANGLE_HAS_NORMALS, 0u);
    st.radiance = glm::vec4(radiance, area);
    face_power.push_back(glows ? p : 0.0);
    power += double(scenes::kParticleTriangles) * mesh.particles * face_power.back();
    // scenes::Scene::at appends an emitter's stage meshes in stage order.
    stages_[size_t(mesh.emitter)].push_back(st);
    stage_mesh_.push_back(uint32_t(m));
  }
  // The CDF runs on from the host's triangles through the stages in mesh order (emitter by
  // emitter), as the scene library lists placed particles' emissive triangles.
  double acc = host;
  uint32_t next = fixed;
  size_t k = 0;
  for (auto& stages : stages_)
    for (gpu::GpuParticleStage& st : stages) {
      const uint32_t n = scenes::kParticleTriangles * scene.meshes[stage_mesh_[k]].particles;
      if (face_power[k] > 0.0 && n > 0) {
        st.first.w = next + 1;
        st.sampling = glm::vec4(float(acc / power), float(face_power[k] / power), 0.0f, 0.0f);
        acc += n * face_power[k];
        next += n;
      }
      ++k;
    }
  for (auto& stages : stages_)
    for (gpu::GpuParticleStage& st : stages) st.triangle.w = next;
  emissive_count_ = next;
  return power;
}

void SceneGpu::record_particles(VkCommandBuffer cmd, const scenes::Scene& posed) {
  if (particles_.empty()) return;
  const ParticleSystem::SceneArrays arrays{vertices_, previous_vertices_, triangles_, indices_, emissive_};
  std::vector<ParticleBounds::Range> ranges;
  for (size_t e = 0; e < particles_.size(); ++e) {
    particles_[e]->record(cmd);
    particles_[e]->record_vertices(cmd, arrays, stages_[e], frame_seconds_);
    const std::vector<uint32_t>& counts = particles_[e]->stage_counts();
    for (size_t s = 0; s < stages_[e].size() && s < counts.size(); ++s) ranges.push_back({stages_[e][s].first.x, counts[s]});
  }
  const uint32_t particles = (triangle_count_ - fixed_triangles_) / scenes::kParticleTriangles;
  particle_bvh_->record(cmd, vertices_, triangles_, nodes_, prims_, fixed_triangles_, particles);
  if (light_bvh_) light_bvh_->record_lights(cmd, vertices_, triangles_, light_tree_, fixed_triangles_, particles, stage_material_);
  std::vector<glm::vec4> points;
  for (const scenes::Light& l : posed.lights) points.emplace_back(l.position, l.type == scenes::LightType::Directional ? 0.0f : 1.0f);
  particle_bounds_->record(cmd, vertices_, ranges, points);
}

void SceneGpu::complete(scenes::Scene& posed) {
  if (!particle_bounds_) return;
  const std::vector<ParticleBounds::Stage> stages = particle_bounds_->read();
  particle_light_distance_.assign(posed.lights.size(), std::numeric_limits<float>::infinity());
  for (size_t k = 0; k < stages.size() && k < stage_mesh_.size(); ++k) {
    const ParticleBounds::Stage& st = stages[k];
    if (st.particles == 0) continue;
    posed.bounds.extend(st.lo);
    posed.bounds.extend(st.hi);
    for (size_t i = 0; i < st.nearest.size() && i < particle_light_distance_.size(); ++i)
      particle_light_distance_[i] = std::min(particle_light_distance_[i], st.nearest[i]);
    for (scenes::AreaLight& l : posed.area_lights) {
      if (l.mesh != stage_mesh_[k]) continue;
      // A cloud of octahedra is closed (scenes::Scene::derive_area_lights): its representative
      // point is its centroid, inside it.
      l.centroid = l.representative = st.centroid;
      l.extent = st.extent;
    }
  }
  bounds_ = posed.bounds;
}

}  // namespace giq::realtime
