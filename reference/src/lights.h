#pragma once
// The scene's lights as one discrete distribution for next-event estimation: emissive
// triangles (area lights, sampled uniformly by area), KHR_lights_punctual lights and the
// constant environment, each picked with probability proportional to an estimate of its power
// (pbrt-v4, "Light Sampling": PowerLightSampler). Positions are in the renderer's frame (the
// scene's local frame shifted by `centre`).

#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <vector>

#include "embree_scene.h"
#include "environment_distribution.h"
#include "feature_mask.h"
#include "giq/reference/alias_table.h"
#include "giq/reference/sampling.h"
#include "giq/scenes/scene.h"

namespace giq::reference {

enum class LightKind : uint8_t { Triangle, Point, Spot, Directional, Environment };

struct LightSample {
  glm::vec3 wi{0.0f};      // unit, from the shading point towards the light
  float distance = 0.0f;   // to the light point (infinite lights: +inf)
  glm::vec3 radiance{0.0f};  // arriving along -wi (delta lights: intensity / d^2, times windows)
  float pdf = 0.0f;        // solid angle, pick probability included; for delta lights the pick
                           // probability alone
  bool delta = false;      // punctual: cannot be hit by BSDF sampling
  bool area = false;       // emissive triangle: the shadow ray ends at `point`
  glm::vec3 point{0.0f};   // on the triangle
  glm::vec3 normal{0.0f};  // triangle's geometric normal, facing the shading point
  float offset = 0.0f;     // ray_offset of the triangle
  LightKind kind = LightKind::Point;
};

class LightSampler {
 public:
  // bvh: the meshes' vertex positions and triangle shapes in the renderer's frame.
  LightSampler(const scenes::Scene& scene, const EmbreeScene& bvh, glm::vec3 centre, float scene_radius);

  bool empty() const { return table_.empty(); }

  // One light sample towards the point p from the four numbers u[0] to u[3] (anything with
  // operator[], such as PathSampler::Group): u[2] and u[3] pick the light, u[0] and u[1] place
  // it. A number is read only where it is used: a scene's only light needs no pick, a punctual
  // light no point, and the Sobol sampler computes each number when asked for it.
  // Returns a sample with pdf 0 when the light does not face p.
  template <unsigned F, class U>
  LightSample sample(glm::vec3 p, const U& u) const;

  // An emissive triangle as sample() reads it, set up once instead of per sample.
  struct Emitter {
    glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};  // renderer's frame
    glm::vec3 n{0.0f};                         // unit geometric normal (counter-clockwise front)
    float area = 0.0f;
    float offset = 0.0f;                       // ray_offset of the triangle
    const scenes::Mesh* mesh = nullptr;
    const scenes::Material* material = nullptr;
    glm::uvec3 triangle{0u};
  };
  // The light sample() picks with the same numbers, for lane_integrator.h, which places the
  // point on an emissive triangle for several samples at once: `emitter` is that triangle,
  // or null for any other light.
  struct Pick {
    const Emitter* emitter;
    float pmf;
  };
  Pick pick(float u_pick, float u_alias) const {
    const AliasTable::Pick p = table_.sample(u_pick, u_alias);
    const Entry& e = entries_[p.index];
    return {e.kind == LightKind::Triangle ? &emitters_[e.index] : nullptr, p.pmf};
  }

  // Probability of picking the emissive triangle (mesh, triangle) / the environment.
  float triangle_pmf(uint32_t mesh, uint32_t triangle) const {
    const int32_t e = triangle_entry_[mesh].empty() ? -1 : triangle_entry_[mesh][triangle];
    return e < 0 ? 0.0f : table_.pmf(size_t(e));
  }
  float environment_pmf() const { return environment_entry_ < 0 ? 0.0f : table_.pmf(size_t(environment_entry_)); }
  // The solid-angle pdf with which sample() finds the environment in direction w (unit), pick
  // included: uniform over the sphere for a constant environment, the map's distribution
  // (EnvironmentDistribution) for a map.
  float environment_pdf(glm::vec3 w) const {
    return environment_pmf() * (environment_map_.empty() ? kUniformSpherePdf : environment_map_.pdf(w));
  }

 private:
  struct Entry {
    LightKind kind;
    uint32_t index;  // emissive triangle index or punctual light index
  };
  const scenes::Scene& scene_;
  glm::vec3 centre_;
  std::vector<Entry> entries_;
  std::vector<Emitter> emitters_;  // per scene.emissive_triangles entry
  AliasTable table_;
  std::vector<std::vector<int32_t>> triangle_entry_;  // per mesh: triangle -> entry, or empty
  int32_t environment_entry_ = -1;
  EnvironmentDistribution environment_map_;  // empty for a constant environment
};

// Radiance emitted by a point of an emissive material (KHR_materials_emissive_strength is
// already folded into Material::emissive), with its emissive texture when textures are on.
template <unsigned F>
glm::vec3 emitted_radiance(const scenes::Scene& scene, const scenes::Material& m, glm::vec2 uv) {
  glm::vec3 e = m.emissive;
  if constexpr (has(F, kTextures)) {
    if (m.emissive_texture >= 0) e *= glm::vec3(scene.textures[size_t(m.emissive_texture)].sample(uv));
  }
  return e;
}


template <unsigned F, class U>
LightSample LightSampler::sample(glm::vec3 p, const U& u) const {
  LightSample s;
  // One light: the table would pick it whatever the numbers (its one bin keeps its entry).
  const AliasTable::Pick pick = table_.size() == 1 ? AliasTable::Pick{0, table_.pmf(0)} : table_.sample(u[2], u[3]);
  const Entry& e = entries_[pick.index];
  s.kind = e.kind;
  if constexpr (has(F, kEmissive)) {
    if (e.kind == LightKind::Triangle) {
      const Emitter& em = emitters_[e.index];
      const glm::vec2 b = square_to_triangle_barycentrics({u[0], u[1]});
      s.point = (1.0f - b.x - b.y) * em.p0 + b.x * em.p1 + b.y * em.p2;
      const float area = em.area;
      s.offset = em.offset;
      glm::vec3 n = em.n;
      const glm::vec3 d = s.point - p;
      const float d2 = glm::dot(d, d);
      if (!(d2 > 0.0f) || !(area > 0.0f)) return s;
      s.distance = std::sqrt(d2);
      s.wi = d / s.distance;
      float cos_l = -glm::dot(n, s.wi);
      const scenes::Material& mat = *em.material;
      if (cos_l <= 0.0f) {
        if (!mat.double_sided) return s;  // glTF: a one-sided emitter emits from its front only
        cos_l = -cos_l, n = -n;
      }
      s.normal = n;
      s.area = true;
      s.radiance = emitted_radiance<F>(scene_, mat, em.mesh->uv_at(em.triangle, b.x, b.y, mat.uv2_slots & scenes::kEmissiveSlot));
      // A ray that found this point would have met the surface with probability equal to
      // its coverage (MASK cut-outs, BLEND): the light found here carries it too.
      if (mat.alpha_mode != scenes::AlphaMode::Opaque) s.radiance *= scene_.coverage(*em.mesh, em.triangle, b.x, b.y);
      // Area measure to solid angle: dA = d^2 / cos(theta_l) dw (pbrt-v4, eq. 4.9). At grazing
      // angles the density can overflow; such a sample carries no light, so it is dropped.
      s.pdf = pick.pmf * d2 / (area * cos_l);
      if (!std::isfinite(s.pdf)) s.pdf = 0.0f;
      return s;
    }
  }
  if constexpr (has(F, kEnvironment)) {
    if (e.kind == LightKind::Environment) {
      s.distance = std::numeric_limits<float>::infinity();
      if (environment_map_.empty()) {
        s.wi = square_to_uniform_sphere({u[0], u[1]});
        s.radiance = scene_.environment;
        s.pdf = pick.pmf * kUniformSpherePdf;
      } else {
        float pdf = 0.0f;
        s.wi = environment_map_.sample({u[0], u[1]}, pdf);
        s.radiance = scene_.environment_radiance(s.wi);
        s.pdf = pick.pmf * pdf;
      }
      return s;
    }
  }
  if constexpr (has(F, kPunctual)) {
    const scenes::Light& l = scene_.lights[e.index];
    s.delta = true;
    s.pdf = pick.pmf;
    if (e.kind == LightKind::Directional) {
      // KHR_lights_punctual: intensity is illuminance (here irradiance) on a facing surface.
      s.wi = -l.direction;
      s.distance = std::numeric_limits<float>::infinity();
      s.radiance = l.radiant();
      return s;
    }
    const glm::vec3 d = (l.position - centre_) - p;
    const float d2 = glm::dot(d, d);
    if (!(d2 > 0.0f)) {
      s.pdf = 0.0f;
      return s;
    }
    s.distance = std::sqrt(d2);
    s.wi = d / s.distance;
    // Inverse-square law with glTF's range window (KHR_lights_punctual, "Range Property").
    float scale = scenes::range_window(s.distance, l.range) / d2;
    if (e.kind == LightKind::Spot) scale *= scenes::spot_attenuation(glm::dot(l.direction, -s.wi), l.inner_cone, l.outer_cone);
    s.radiance = l.radiant() * scale;
    return s;
  }
  s.pdf = 0.0f;
  return s;
}

}  // namespace giq::reference
