#include "lights.h"

#include <cmath>

#include "giq/reference/ray_offset.h"

namespace giq::reference {

using scenes::luminance;

LightSampler::LightSampler(const scenes::Scene& scene, const EmbreeScene& bvh, glm::vec3 centre, float scene_radius)
    : scene_(scene), centre_(centre) {
  std::vector<double> weights;
  triangle_entry_.resize(scene.meshes.size());
  const double pi = 3.14159265358979323846;
  // Power estimates (pbrt-v4, the lights' Phi() methods): they only steer the pick
  // probabilities, so a rough estimate costs variance, never bias.
  for (size_t i = 0; i < scene.emissive_triangles.size(); ++i) {
    const scenes::EmissiveTriangle& t = scene.emissive_triangles[i];
    if (!(t.power > 0.0f)) continue;
    std::vector<int32_t>& map = triangle_entry_[t.mesh];
    if (map.empty()) map.assign(scene.meshes[t.mesh].triangles.size(), -1);
    map[t.triangle] = int32_t(entries_.size());
    entries_.push_back({LightKind::Triangle, uint32_t(i)});
    emitters_.resize(scene.emissive_triangles.size());
    Emitter& em = emitters_[i];
    em.mesh = &scene.meshes[t.mesh];
    em.material = &scene.materials[size_t(em.mesh->material)];
    em.triangle = em.mesh->triangles[t.triangle];
    const std::vector<glm::vec3>& pos = bvh.positions()[t.mesh];
    em.p0 = pos[em.triangle.x], em.p1 = pos[em.triangle.y], em.p2 = pos[em.triangle.z];
    const TriangleShape& shape = bvh.shapes()[t.mesh][t.triangle];
    em.area = shape.area;
    em.n = shape.normal;
    em.offset = ray_offset(em.p0, em.p1, em.p2);
    weights.push_back(t.power);
  }
  const double r2 = double(scene_radius) * double(scene_radius);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const scenes::Light& l = scene.lights[i];
    const double phi = l.power(scene_radius);
    const LightKind kind = l.type == scenes::LightType::Spot          ? LightKind::Spot
                           : l.type == scenes::LightType::Directional ? LightKind::Directional
                                                                      : LightKind::Point;
    if (!(phi > 0.0) || !std::isfinite(phi)) continue;
    entries_.push_back({kind, uint32_t(i)});
    weights.push_back(phi);
  }
  const double env = luminance(scene.environment);
  if (env > 0.0 && std::isfinite(env)) {
    environment_entry_ = int32_t(entries_.size());
    entries_.push_back({LightKind::Environment, 0});
    weights.push_back(4.0 * pi * pi * r2 * env);  // pbrt-v4 UniformInfiniteLight::Phi (of the map's mean)
    if (scene.environment_map >= 0) environment_map_ = EnvironmentDistribution(scene.textures[size_t(scene.environment_map)]);
  }
  if (!weights.empty()) table_ = AliasTable(weights);
}

}  // namespace giq::reference
