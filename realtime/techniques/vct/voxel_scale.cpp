#include "techniques/vct/voxel_scale.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

namespace giq::realtime {
namespace {

// Squared distance from q to triangle (a, b, c) (Ericson 2004, "Real-Time Collision
// Detection", 5.1.5).
float distance2_to_triangle(glm::vec3 q, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
  const glm::vec3 ab = b - a, ac = c - a, ap = q - a;
  const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  auto d2of = [&](glm::vec3 p) { return glm::dot(q - p, q - p); };
  if (d1 <= 0.0f && d2 <= 0.0f) return d2of(a);
  const glm::vec3 bp = q - b;
  const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return d2of(b);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) return d2of(a + ab * (d1 / (d1 - d3)));
  const glm::vec3 cp = q - c;
  const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return d2of(c);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) return d2of(a + ac * (d2 / (d2 - d6)));
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
    return d2of(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const float denom = 1.0f / (va + vb + vc);
  return d2of(a + ab * (vb * denom) + ac * (vc * denom));
}

float max_channel(glm::vec3 v) {
  return std::max(v.x, std::max(v.y, v.z));
}

}  // namespace

std::vector<gpu::VctEmitter> voxel_emitters(const scenes::Scene& scene) {
  std::vector<gpu::VctEmitter> out;
  for (const scenes::AreaLight& a : scene.area_lights) {
    gpu::VctEmitter em;
    // A closed emitter's centre is inside it: shadow rays stop at the sphere around it that
    // holds the mesh.
    em.position = glm::vec4(a.representative, a.extent);
    em.normal = a.flat ? glm::vec4(a.normal, a.two_sided ? 1.0f : 0.0f) : glm::vec4(0.0f, 0.0f, 0.0f, 2.0f);
    em.power = glm::vec4(a.intensity, a.area);
    out.push_back(em);
  }
  return out;
}

float voxel_radiance_scale(const scenes::Scene& scene, const std::vector<gpu::VctEmitter>& emitters,
                           int bounces, float voxel, const std::vector<float>& particle_distance) {
  double irradiance = 0.0;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const scenes::Light& l = scene.lights[i];
    const float intensity = max_channel(l.radiant());
    if (!(intensity > 0.0f)) continue;
    if (l.type == scenes::LightType::Directional) {
      irradiance += intensity;
      continue;
    }
    float d2 = std::numeric_limits<float>::infinity();
    for (const auto& mesh : scene.meshes)
      for (const auto& t : mesh.triangles)
        d2 = std::min(d2, distance2_to_triangle(l.position, mesh.positions[t.x],
                                                mesh.positions[t.y], mesh.positions[t.z]));
    if (i < particle_distance.size()) d2 = std::min(d2, particle_distance[i] * particle_distance[i]);
    // Nearer than half a voxel, the voxels clip (voxel_scale.h); the smallest normal float
    // keeps the scale finite for a voxel of no size.
    const double near = 0.5 * double(voxel);
    irradiance += double(intensity) / std::max({double(d2), near * near, 1e-30});
  }
  for (const auto& e : emitters)
    if (e.power.w > 0.0f)
      irradiance += double(max_channel(glm::vec3(e.power))) * M_PI / double(e.power.w);
  // Each bounce adds at most the direct light's bound again (albedo <= 1, cone weights sum
  // to 1), so n bounces stay below n times it.
  const double radiance = irradiance / M_PI * double(std::max(bounces, 1));
  if (!(radiance > 0.0)) return 1.0f;
  return float(std::exp2(std::clamp(std::floor(std::log2(1.0 / radiance)), -120.0, 120.0)));
}

}  // namespace giq::realtime
