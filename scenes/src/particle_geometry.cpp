#include "particle_geometry.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "giq/base/error.h"

namespace giq::scenes {

void complete_emitter(Emitter& e, const std::vector<Mesh>& meshes, std::vector<Material>& materials, const std::string& file,
                      const std::string& field) {
  std::vector<double> areas;
  for (const Mesh& m : meshes) {
    if (m.node != e.node) continue;
    for (const glm::uvec3& t : m.triangles) {
      const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
      const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
      if (!(area > 0.0)) continue;
      e.surface.insert(e.surface.end(), {a, b, c});
      areas.push_back(area);
    }
  }
  double total = 0.0;
  for (double a : areas) total += a;
  if (!(total > 0.0) || !std::isfinite(total)) throw InputError(file, field, "node " + std::to_string(e.node) + " has no triangle with area to emit from");
  // Triangle k is chosen for random words in (choice[k - 1], choice[k]]: its share of 2^32.
  // A triangle too small for a single word is left out.
  std::vector<glm::dvec3> kept;
  double sum = 0.0;
  uint64_t previous = 0;
  for (size_t k = 0; k < areas.size(); ++k) {
    sum += areas[k];
    const uint64_t end = k + 1 == areas.size() ? (uint64_t(1) << 32) : uint64_t(std::min(std::ldexp(sum / total, 32), 4294967296.0));
    if (end <= previous) continue;
    kept.insert(kept.end(), e.surface.begin() + long(3 * k), e.surface.begin() + long(3 * k + 3));
    e.choice.push_back(uint32_t(end - 1));
    previous = end;
  }
  e.surface = std::move(kept);

  e.first_material = int(materials.size());
  for (int s = 0; s < e.stages; ++s) {
    Material m;
    m.name = e.name + " stage " + std::to_string(s);
    m.base_color = glm::vec4(e.color, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    m.emissive = glm::vec3(glm::dvec3(e.emission) * e.stage_strength(s));
    materials.push_back(m);
  }
}

std::vector<glm::vec3> particle_centres(const Mesh& m) {
  std::vector<glm::vec3> centres;
  // Vertices 0 and 1 of each particle are its +x and -x corners.
  for (size_t v = 0; v + 1 < m.positions.size(); v += std::size(kParticleAxes)) centres.push_back(0.5f * (m.positions[v] + m.positions[v + 1]));
  return centres;
}

void add_particle_meshes(const std::vector<Emitter>& emitters, double t, double frame, ParticleDetail detail,
                         std::vector<Mesh>& meshes, const std::string& file) {
  for (size_t i = 0; i < emitters.size(); ++i) {
    const Emitter& e = emitters[i];
    if (e.rate * t >= 4294967295.0)
      throw InputError(file, "extras.giq.emitters[" + std::to_string(i) + "]",
                       "emitter \"" + e.name + "\" has emitted 2^32 particles by t = " + std::to_string(t) + " s; expected fewer (a lower rate or a shorter sequence)");
    const AliveRange alive = alive_range(e, t);
    const std::vector<uint64_t> starts = stage_starts(e, t);
    std::vector<Mesh> stage(size_t(e.stages));
    // Each stage's particles are known from the integers alone (stage_range), so its arrays
    // are allocated once: a million particles would otherwise spend most of their time in the
    // vectors' regrowth.
    for (int s = 0; s < e.stages; ++s) {
      const size_t n = size_t(stage_range(alive, starts, s).count());
      Mesh& m = stage[size_t(s)];
      m.particles = uint32_t(n);
      if (detail == ParticleDetail::Counted) continue;
      m.positions.reserve(n * kParticleVertices);
      m.previous_positions.reserve(n * kParticleVertices);
      m.normals.reserve(n * kParticleVertices);
      m.triangles.reserve(n * kParticleTriangles);
    }
    for (uint64_t id = alive.first; id < alive.end && detail == ParticleDetail::Placed; ++id) {
      const ParticleBirth birth = particle_birth(e, uint32_t(id));
      const Particle p = particle_at(e, uint32_t(id), birth, t, starts);
      // One frame earlier by the same closed form, before its birth too (the motion it would
      // have had), so that a newborn particle moves like the others. (Its stage then is unused.)
      const glm::dvec3 was = particle_at(e, uint32_t(id), birth, t - frame, {}).position;
      Mesh& m = stage[size_t(p.stage)];
      const uint32_t base = uint32_t(m.positions.size());
      for (const glm::dvec3& axis : kParticleAxes) {
        m.positions.push_back(glm::vec3(p.position + e.size * axis));
        m.previous_positions.push_back(glm::vec3(was + e.size * axis));
        m.normals.push_back(glm::vec3(axis));
      }
      for (const glm::uvec3& f : kParticleFaces) m.triangles.push_back(f + glm::uvec3(base));
    }
    // Every stage, with particles or none, so that the scene's meshes and lights are the same
    // set in every frame.
    for (int s = 0; s < e.stages; ++s) {
      Mesh& m = stage[size_t(s)];
      m.name = e.name;
      m.emitter = int(i);
      m.object_id = e.object_id;
      m.material = e.first_material + s;
      meshes.push_back(std::move(m));
    }
  }
}

}  // namespace giq::scenes
