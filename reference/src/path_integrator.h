#pragma once
// Unidirectional path tracing with next-event estimation and multiple importance sampling
// (Veach 1997, thesis, section 9.2, power heuristic eq. 9.13), one light sample and one BSDF
// sample per vertex, Russian roulette after the third bounce (Arvo & Kirk 1990, "Particle
// Transport and Image Synthesis"), specialised on the feature mask F.
//
// A sample's contributions are split as the reference EXR wants them: "direct" is emission
// seen by the camera ray plus light arriving at the first vertex straight from an emitter
// (by light sampling or by the first BSDF sample); everything else is "indirect".
//
// This is the integrator one path at a time. lane_integrator.h runs the same estimator on
// eight paths at once where the scene allows, with the same bits; a change here is a change
// there.

#include <glm/glm.hpp>

#include <cmath>
#include <limits>

#include "feature_mask.h"
#include "giq/reference/bsdf.h"
#include "giq/reference/film.h"
#include "giq/reference/ray_offset.h"
#include "giq/reference/sampling.h"
#include "render_context.h"
#include "surface.h"

namespace giq::reference {

// Russian roulette's survival probability is min(1, kRouletteScale x the path throughput's
// largest component). Roulette trades variance (its 1/q weights) for shorter paths; the best
// trade keeps a path while its expected contribution, the throughput times the radiance still
// to be gathered, is worth its cost relative to the pixel's value (Vorba & Krivanek 2016,
// "Adjoint-Driven Russian Roulette and Splitting in Light Transport Simulation": the weight
// window). Without estimates of either radiance their ratio is taken as a constant. Scale 1
// (pbrt's choice) assumes it is 1; under diffuse interreflection the light arriving at a
// vertex is about 1 / albedo times what leaves it, so it is nearer 2. Measured efficiency
// (1 / (time x relMSE), 128x128, 512 spp, 3 seeds) against scale 1: scale 2 gains 13 %, 16 %
// and 19 % on the sunroom, Cornell box and movinglight scenes; scale 4 gains 6 %, 19 %, 22 %;
// Cycles' sqrt(throughput) 9 %, 11 %, 15 %. Where little light interreflects it changes
// nothing measurable: -1 % and -2 % (within the noise) on tests/data/scenes/textured_room and
// lights_cameras.
inline constexpr float kRouletteScale = 2.0f;

// What one camera path brings back.
struct PathResult {
  glm::vec3 direct{0.0f}, indirect{0.0f};
  uint32_t rays = 0;  // traced: camera, bounce and shadow rays
};

// Adds one path's result to its pixel. A non-finite sample is discarded as a zero-valued one,
// so every pixel keeps the same sample count; it is counted and reported.
inline void add_sample(PixelAccumulator& acc, glm::vec3 direct, glm::vec3 indirect) {
  const glm::vec3 beauty = direct + indirect;
  float b[3], d[3];
  bool finite = true;
  for (int k = 0; k < 3; ++k) {
    b[k] = beauty[k], d[k] = direct[k];
    finite = finite && std::isfinite(b[k]) && std::isfinite(d[k]);
  }
  if (!finite) {
    ++acc.nonfinite;
    for (int k = 0; k < 3; ++k) b[k] = d[k] = 0.0f;
  }
  acc.add(b, d);
}

template <unsigned F>
class PathIntegrator {
 public:
  static constexpr bool kSpec = has(F, kSpecular);
  explicit PathIntegrator(const RenderContext& ctx) : c_(ctx) {}

  PathResult trace(int x, int y, uint32_t sample_index) const {
    using D = SampleDimensions;
    const RenderSettings& rs = c_.settings;
    const PathSampler s(uint32_t(y) * uint32_t(rs.width) + uint32_t(x), sample_index, rs.seed, rs.block());
    const PathSampler::Group j = s.get(D::kPixel);
    const float fx = float(x) + (rs.pixel_centre ? 0.5f : j[0]), fy = float(y) + (rs.pixel_centre ? 0.5f : j[1]);
    glm::vec3 d = c_.rays.direction(fx, fy);
    glm::vec3 o = c_.eye + c_.rays.origin_offset(fx, fy);
    glm::vec3 beta(1.0f), direct(0.0f), indirect(0.0f);
    float prev_pdf = 0.0f;  // BSDF pdf of the direction that led to the current hit
    uint32_t rays = 0;
    for (int depth = 0;; ++depth) {
      // Emission found at hit `depth` is direct for the camera's hit and the first bounce's.
      glm::vec3& emitted_to = depth <= 1 ? direct : indirect;
      const Hit hit = depth == 0 ? c_.bvh.intersect_camera(o, d) : c_.bvh.intersect(o, d);
      ++rays;
      if (!hit.valid()) {
        if constexpr (has(F, kEnvironment)) {
          const float w = depth == 0 ? 1.0f : bsdf_hit_weight(prev_pdf, c_.lights.environment_pdf(d));
          emitted_to += beta * w * c_.scene.environment_radiance(d);
        }
        break;
      }
      const Surface sf = make_surface<F>(c_, hit, d);
      if (sf.black) break;
      if constexpr (has(F, kEmissive)) {
        if (sf.emission != glm::vec3(0.0f)) {
          float w = 1.0f;
          if (depth > 0) {
            // The light-sampling pdf of this point, in solid angle from the previous vertex.
            float pdf_light = c_.lights.triangle_pmf(hit.mesh, hit.triangle) * hit.t * hit.t / (sf.area * sf.cos_ray);
            if (!std::isfinite(pdf_light)) pdf_light = std::numeric_limits<float>::max();
            w = bsdf_hit_weight(prev_pdf, pdf_light);
          }
          emitted_to += beta * w * sf.emission;
        }
      }
      if (depth >= rs.max_bounces) break;

      const glm::vec3 wo = -d;
      const Frame frame = Frame::from_normal(sf.ns);
      const glm::vec3 wo_l = frame.to_local(wo);
      const glm::vec3 origin = offset_ray_origin(sf.p, sf.ng, sf.offset);

      // Next-event estimation: one light sample.
      if (!c_.lights.empty()) {
        const LightSample ls = c_.lights.sample<F>(sf.p, s.get(D::light(depth)));
        const bool use = ls.delta || rs.estimator != Estimator::BsdfOnly;
        if (use && ls.pdf > 0.0f && glm::dot(ls.wi, sf.ng) > 0.0f && ls.radiance != glm::vec3(0.0f)) {
          const BsdfEval e = bsdf_evaluate<kSpec>(sf.bsdf, wo_l, frame.to_local(ls.wi));
          if (e.f != glm::vec3(0.0f) && (++rays, !shadowed(origin, ls))) {
            const float w = ls.delta || rs.estimator == Estimator::LightOnly ? 1.0f : power_heuristic(ls.pdf, e.pdf);
            const float cos_s = glm::dot(ls.wi, sf.ns);
            (depth == 0 ? direct : indirect) += beta * e.f * ls.radiance * (w * cos_s / ls.pdf);
          }
        }
      }

      // BSDF sampling continues the path.
      glm::vec3 wi_l;
      const PathSampler::Group u = s.get(D::bsdf(depth));
      // The lobe's number only where there is a lobe to choose (bsdf_sample reads it there alone).
      const float u_lobe = kSpec && sf.bsdf.specular_lobe ? u[2] : 0.0f;
      if (!bsdf_sample<kSpec>(sf.bsdf, wo_l, u_lobe, {u[0], u[1]}, wi_l))
        break;
      const glm::vec3 wi = frame.to_world(wi_l);
      // Reflection only: a direction below the geometric surface would leak through it.
      if (glm::dot(wi, sf.ng) <= 0.0f) break;
      const BsdfEval e = bsdf_evaluate<kSpec>(sf.bsdf, wo_l, wi_l);
      if (!(e.pdf > 0.0f)) break;
      beta *= e.f * (wi_l.z / e.pdf);
      prev_pdf = e.pdf;
      if (depth >= 3) {
        // Unbiased Russian roulette: survive with q, divide by q.
        const float q = std::min(1.0f, kRouletteScale * max_component(beta));
        if (!(u[3] < q)) break;
        beta /= q;
      }
      o = origin;
      d = wi;
    }
    return {direct, indirect, rays};
  }

  // First-hit layers of the pixel centre's ray.
  PixelAux aux(int x, int y) const {
    PixelAux a;
    const glm::vec3 d = c_.rays.direction(float(x) + 0.5f, float(y) + 0.5f);
    const Hit hit = c_.bvh.intersect_camera(c_.eye + c_.rays.origin_offset(float(x) + 0.5f, float(y) + 0.5f), d);
    if (!hit.valid()) return a;
    const Surface sf = make_surface<F>(c_, hit, d);
    const glm::vec3 albedo = sf.black ? glm::vec3(0.0f) : sf.bsdf.base;
    // Non-finite material or vertex data must not reach the file either: written as 0.
    const auto finite = [](float v) { return std::isfinite(v) ? v : 0.0f; };
    for (int k = 0; k < 3; ++k) a.albedo[k] = finite(albedo[k]), a.normal[k] = finite(sf.ns[k]);
    a.depth = finite(hit.t * glm::dot(d, c_.camera.forward));
    a.object_id = c_.scene.meshes[hit.mesh].object_id;
    return a;
  }

 private:
  // MIS weight of light found by BSDF sampling, given the light-sampling pdf of the same
  // direction.
  float bsdf_hit_weight(float pdf_bsdf, float pdf_light) const {
    switch (c_.settings.estimator) {
      case Estimator::Mis: return power_heuristic(pdf_bsdf, pdf_light);
      case Estimator::LightOnly: return 0.0f;
      case Estimator::BsdfOnly: return 1.0f;
    }
    return 0.0f;
  }

  bool shadowed(glm::vec3 origin, const LightSample& ls) const {
    if (ls.area) {
      // End the shadow ray just off the light's surface, on the shading point's side.
      const glm::vec3 target = offset_ray_origin(ls.point, ls.normal, ls.offset);
      const glm::vec3 v = target - origin;
      const float len = glm::length(v);
      return len > 0.0f && c_.bvh.occluded(origin, v / len, len);
    }
    return c_.bvh.occluded(origin, ls.wi, ls.distance);
  }

  const RenderContext& c_;
};

}  // namespace giq::reference
