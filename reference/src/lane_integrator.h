#pragma once
// The path integrator of path_integrator.h, eight paths at a time: each step traces the eight
// paths' rays as one Embree packet, and the arithmetic of the step (surface frame, ray
// offsets, MIS weights, the Sobol numbers, the point on an emissive triangle, the cosine
// warp, throughput and Russian roulette) runs on all eight lanes with each instruction. What
// needs a lookup per path (the triangle and material behind a hit, the light pick, a
// punctual or environment light) is done lane by lane.
//
// Why: a path's arithmetic is a chain of dependent divisions, square roots and polynomials
// whose latency one path cannot hide, and single-ray traversal leaves Embree's SIMD units
// half used; the eight lanes fill both (the wavefront idea of Laine, Karras & Aila 2013,
// "Megakernels Considered Harmful", kept inside one thread and one tile).
//
// Same estimator, same random numbers, same operations in the same order: a path gives the
// same bits in a lane as in PathIntegrator::trace, and tests/reference/lanes_test.cpp fails
// when the two drift apart (a change to the BSDF, the emissive triangles' sampling or the
// warps must be made in both). The lanes take every scene rendered with the Sobol
// sampler, and each step's arithmetic runs on the eight lanes, the GGX lobe's sampling,
// evaluation and lobe choice included (lane_bsdf.h). What reads textures is done one lane at
// a time with PathIntegrator's own functions, so the same bits by construction: where
// materials read textures (or the environment is a map), each lane builds its surface with
// make_surface, looks up the environment and samples emissive triangles with
// LightSampler::sample; the BSDF, frames, offsets, MIS weights, throughput and roulette then
// run on the eight lanes.

#include <embree3/rtcore.h>

#include <array>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

#include "giq/reference/film.h"
#include "lane_bsdf.h"
#include "lanes.h"
#include "path_integrator.h"

namespace giq::reference {

// Whether the lanes render feature mask F with these settings: with the Sobol sampler, whose
// numbers the lanes draw for eight paths at once, and, unless told always, only where they
// were measured faster: not where a material has a GGX lobe or reads textures, where the two
// integrators are about as fast (bench/results/reference-lanes-amd-epyc-2vcpu.md).
inline bool lanes_support(unsigned F, const RenderSettings& s) {
  using L = RenderSettings::Lanes;
  const bool faster = !has(F, kSpecular) && !has(F, kTextures);
  return s.block() != 0 && (s.lanes == L::Always || (s.lanes == L::Auto && faster));
}

namespace lanes {

// The four numbers of a group, lane by lane as ScrambledSobol4 gives them: `index` is each
// lane's sample index in its block, `scramble` its group's seed (PathSampler::scramble).
// Number `skip` (0 to 3) is left out, or none when skip is 4.
struct Group {
  F u[4];
};
template <int skip>
[[gnu::always_inline]] inline Group sobol_group(U index, U scramble, int block_bits) {
  const U point = owen_scramble(index, scramble) & ((1u << block_bits) - 1u);
  Group g;
  for (int d = 0; d < 4; ++d) {
    if (d == skip) continue;
    U rev;
    for (int l = 0; l < kWidth; ++l) rev[l] = kSobolTable.rev[point[l]][size_t(d)];
    const U x = reverse_bits(lk_hash(rev, hash32(scramble + 0x9e3779b9u * uint32_t(d + 1))));
    g.u[d] = to_float(bits(x >> 8)) * 0x1p-24f;
  }
  return g;
}

// sampling.h's Frame.
struct Frame {
  V3 t, b, n;
  [[gnu::always_inline]] static Frame from_normal(V3 n) {
    const F sign = copysign_one(n.z);
    const F a = -1.0f / (sign + n.z);
    const F bb = n.x * n.y * a;
    return {{1.0f + sign * n.x * n.x * a, sign * bb, -sign * n.x}, {bb, sign + n.y * n.y * a, -n.y}, n};
  }
  [[gnu::always_inline]] V3 to_local(V3 v) const { return {dot(v, t), dot(v, b), dot(v, n)}; }
  [[gnu::always_inline]] V3 to_world(V3 v) const { return t * v.x + b * v.y + n * v.z; }
};

// ray_offset.h's offset_ray_origin (each triangle's offset is TriangleShape's, from the build).
[[gnu::always_inline]] inline V3 offset_ray_origin(V3 p, V3 n, F offset) { return p + offset * n; }

// sampling.h's power_heuristic, special cases included.
[[gnu::always_inline]] inline F power_heuristic(F a, F b) {
  const F r = b / a;
  F w = 1.0f / (1.0f + r * r);
  w = select(is_inf(a), select(is_inf(b), F(0.5f), F(1.0f)), w);
  w = select(b > 0.0f, w, F(1.0f));
  return select(a > 0.0f, w, F{});
}

}  // namespace lanes

template <unsigned F>
class LaneIntegrator {
  using LF = lanes::F;
  using LI = lanes::I;
  using LU = lanes::U;
  using V3 = lanes::V3;
  static constexpr int kWidth = lanes::kWidth;
  // Textured surfaces and emitters one lane at a time, with PathIntegrator's own functions.
  static constexpr bool kPerLane = has(F, kTextures);

 public:
  explicit LaneIntegrator(const RenderContext& ctx) : c_(ctx) {}

  // Adds samples to the pixels [x0, x1) x [y0, y1) until each has `target_spp`, in each
  // pixel's sample order, as PathIntegrator's loop over the pixels does.
  RenderStats render_tile(Film& film, int x0, int y0, int x1, int y1, uint32_t target_spp) const {
    using namespace lanes;
    const RenderSettings& rs = c_.settings;
    Tile tile{film, x0, x1, y1, target_spp, x0, y0};
    Paths s;
    for (int l = 0; l < kWidth; ++l) start(tile, s, l);
    RenderStats stats;
    const LF env_weight_pdf(c_.lights.environment_pmf() * kUniformSpherePdf);
    // The packets' fields that no query changes are set once.
    alignas(32) RTCRayHit8 rh;
    alignas(32) RTCRay8 r;
    alignas(32) int valid[kWidth];
    for (RTCRay8* ray : {&rh.ray, &r}) {
      for (int l = 0; l < kWidth; ++l) {
        ray->tnear[l] = 0.0f, ray->time[l] = 0.0f;
        ray->mask[l] = 0xffffffffu, ray->id[l] = unsigned(l), ray->flags[l] = 0;
      }
    }
    while (any(s.live)) {
      // Trace every live lane's ray.
      bool camera = false;
      for (int l = 0; l < kWidth; ++l) {
        valid[l] = s.live[l];
        rh.ray.org_x[l] = s.origin.x[l], rh.ray.org_y[l] = s.origin.y[l], rh.ray.org_z[l] = s.origin.z[l];
        rh.ray.dir_x[l] = s.dir.x[l], rh.ray.dir_y[l] = s.dir.y[l], rh.ray.dir_z[l] = s.dir.z[l];
        rh.ray.tfar[l] = std::numeric_limits<float>::infinity();
        // The camera's rays pass the backs of single-sided surfaces (intersect_camera).
        rh.ray.id[l] = unsigned(l) | (s.depth[l] == 0 ? EmbreeScene::kCameraRay : 0u);
        camera |= s.live[l] != 0 && s.depth[l] == 0;
        rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
      }
      c_.bvh.intersect(valid, rh, camera);
      for (int l = 0; l < kWidth; ++l) s.rays[l] += s.live[l] != 0;

      LI hit{};
      for (int l = 0; l < kWidth; ++l) hit[l] = s.live[l] != 0 && rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID ? -1 : 0;
      const LI miss = s.live & ~hit;
      const LI emission_direct = s.depth <= 1;  // emission found at the camera's or the first bounce's hit
      LI done = miss;
      if constexpr (has(F, kEnvironment)) {
        if (any(miss)) {
          LF pdf = env_weight_pdf;
          V3 radiance = splat(c_.scene.environment);
          if constexpr (has(F, kTextures)) {  // perhaps a map: its radiance and pdf per direction
            for (int l = 0; l < kWidth; ++l) {
              if (miss[l] == 0) continue;
              const glm::vec3 d = get(s.dir, l);
              pdf[l] = c_.lights.environment_pdf(d);
              set(radiance, l, c_.scene.environment_radiance(d));
            }
          }
          const LF w = select(s.depth == 0, LF(1.0f), bsdf_hit_weight(s.prev_pdf, pdf));
          add(s, miss, emission_direct, (s.beta * w) * radiance);
        }
      }

      const Surfaces sf = surfaces(hit, rh, s);
      done |= hit & sf.black;
      const LI shade = hit & ~sf.black;
      if constexpr (has(F, kEmissive)) {
        const LI emitting = shade & nonzero(sf.emission);
        if (any(emitting)) {
          // The light-sampling pdf of this point, in solid angle from the previous vertex.
          LF pdf_light = sf.light_pmf * sf.t * sf.t / (sf.area * sf.cos_ray);
          pdf_light = select(is_finite(pdf_light), pdf_light, LF(std::numeric_limits<float>::max()));
          const LF w = select(s.depth > 0, bsdf_hit_weight(s.prev_pdf, pdf_light), LF(1.0f));
          add(s, emitting, emission_direct, (s.beta * w) * sf.emission);
        }
      }
      const LI cont = shade & (s.depth < rs.max_bounces);
      done |= shade & ~cont;

      if (any(cont)) {
        const V3 wo = -s.dir;
        const lanes::Frame frame = lanes::Frame::from_normal(sf.ns);
        const V3 wo_l = frame.to_local(wo);
        const V3 origin = offset_ray_origin(sf.p, sf.ng, sf.offset);
        const LI vertex_direct = s.depth == 0;

        // Next-event estimation: one light sample per lane.
        Shadow shadow;
        if (!c_.lights.empty()) {
          const Group u = group<4>(s, 1 + 2 * s.depth);
          const LightSamples ls = sample_lights(cont, sf.p, u);
          const LI use = ls.delta | (rs.estimator != Estimator::BsdfOnly ? -1 : 0);
          LI lit = cont & use & (ls.pdf > 0.0f) & (dot(ls.wi, sf.ng) > 0.0f) & nonzero(ls.radiance);
          const Eval e = evaluate(lit, sf, wo_l, frame.to_local(ls.wi));
          lit &= nonzero(e.f);
          if (any(lit)) {
            const LI unweighted = ls.delta | (rs.estimator == Estimator::LightOnly ? -1 : 0);
            const LF w = select(unweighted, LF(1.0f), power_heuristic(ls.pdf, e.pdf));
            const LF cos_s = dot(ls.wi, sf.ns);
            shadow.value = ((s.beta * e.f) * ls.radiance) * ((w * cos_s) / ls.pdf);
            for (int l = 0; l < kWidth; ++l) s.rays[l] += lit[l] != 0;
            // An area light's shadow ray ends just off the light's surface, on this side.
            const V3 v = offset_ray_origin(ls.point, ls.normal, ls.offset) - origin;
            const LF len = sqrt(dot(v, v));
            const LI at_light = ls.area & ~(len > 0.0f);  // nothing between: unshadowed
            add(s, lit & at_light, vertex_direct, shadow.value);
            shadow.rays = lit & ~at_light;
            shadow.dir = select(ls.area, v / len, ls.wi);
            shadow.tfar = select(ls.area, len, ls.distance);
          }
        }

        // BSDF sampling continues the path.
        const Group u = group<has(F, kSpecular) ? 4 : 2>(s, 2 + 2 * s.depth);  // Lambert: no lobe to choose
        V3 wi_l;
        LI next;
        if constexpr (has(F, kSpecular)) {
          const lanes::Sample b = lanes::bsdf_sample(sf.bsdf, wo_l, u.u[2], u.u[0], u.u[1]);
          wi_l = b.wi;
          next = cont & b.ok;
        } else {
          wi_l = cosine_hemisphere(u.u[0], u.u[1]);
          next = cont & ~(wo_l.z <= 0.0f) & (wi_l.z > 0.0f);
        }
        const V3 wi = frame.to_world(wi_l);
        // Reflection only: a direction below the geometric surface would leak through it.
        next &= ~(dot(wi, sf.ng) <= 0.0f);
        const Eval e = evaluate(next, sf, wo_l, wi_l);
        next &= e.pdf > 0.0f;
        V3 beta = s.beta * (e.f * (wi_l.z / e.pdf));
        // Unbiased Russian roulette: survive with q, divide by q.
        const LI roulette = s.depth >= 3;
        const LF q = min(LF(1.0f), kRouletteScale * max_component(beta));
        next &= ~roulette | (u.u[3] < q);
        beta = select(roulette, beta / q, beta);
        s.beta = select(next, beta, s.beta);
        s.prev_pdf = select(next, e.pdf, s.prev_pdf);
        s.origin = select(next, origin, s.origin);
        s.dir = select(next, wi, s.dir);
        s.depth -= next;  // masks are -1
        done |= cont & ~next;

        if (any(shadow.rays)) {
          for (int l = 0; l < kWidth; ++l) {
            valid[l] = shadow.rays[l];
            r.org_x[l] = origin.x[l], r.org_y[l] = origin.y[l], r.org_z[l] = origin.z[l];
            r.dir_x[l] = shadow.dir.x[l], r.dir_y[l] = shadow.dir.y[l], r.dir_z[l] = shadow.dir.z[l];
            r.tfar[l] = shadow.rays[l] != 0 ? shadow.tfar[l] : 0.0f;
          }
          c_.bvh.occluded(valid, r);
          LI unblocked{};
          for (int l = 0; l < kWidth; ++l) unblocked[l] = shadow.rays[l] != 0 && !(r.tfar[l] < 0.0f) ? -1 : 0;
          add(s, unblocked, vertex_direct, shadow.value);
        }
      }

      // Finished paths go to their pixels; their lanes take the next sample.
      for (int l = 0; l < kWidth; ++l) {
        if (done[l] == 0) continue;
        stats.rays += s.rays[l];
        ++stats.samples;
        add_sample(*s.pixel[l], get(s.direct, l), get(s.indirect, l));
        start(tile, s, l);
      }
    }
    return stats;
  }

 private:
  using Group = lanes::Group;

  // The tile's pixels, handed to the lanes in scanline order.
  struct Tile {
    Film& film;
    int x0, x1, y1;
    uint32_t target_spp;
    int x, y;  // the next pixel to hand out
    // The next pixel that needs samples, or null.
    PixelAccumulator* next(int& px, int& py) {
      for (; y < y1; ++y, x = x0) {
        for (; x < x1; ++x) {
          PixelAccumulator& acc = film.pixels[size_t(y) * size_t(film.width) + size_t(x)];
          if (acc.samples < target_spp) {
            px = x++, py = y;
            return &acc;
          }
        }
      }
      return nullptr;
    }
  };

  // The eight paths in flight, lane by lane.
  struct Paths {
    LI live{};  // the lane holds a path
    V3 origin, dir;  // the ray to trace next
    V3 beta, direct, indirect;
    LF prev_pdf{};  // BSDF pdf of the direction that led to the current hit
    LI depth{};     // of the hit the ray will find
    LU index{};     // the sample's index in its Sobol block
    PathSampler sampler[kWidth];
    PixelAccumulator* pixel[kWidth] = {};  // the pixel each lane's path belongs to
    int x[kWidth] = {}, y[kWidth] = {};
    uint32_t rays[kWidth] = {};
  };

  struct Surfaces {
    V3 p, ng, ns, base, emission;
    LF metallic{}, t{}, area{}, cos_ray{}, light_pmf{}, offset{};
    LI black{};
    lanes::Bsdf bsdf;  // with a GGX lobe in the scene
  };

  struct LightSamples {
    V3 wi, radiance, point, normal;
    LF distance{}, pdf{}, offset{};
    LI delta{}, area{};
  };

  // The emissive triangles picked by the lanes in `on`.
  struct Emitters {
    LI on{};
    V3 p0, p1, p2, n, radiance;
    LF area{}, pmf{}, offset{};
    LI double_sided{};
  };

  struct Shadow {
    LI rays{};  // lanes with a shadow ray to trace
    V3 value, dir;
    LF tfar{};
  };

  // Starts lane l's next path: the next sample of its pixel, or of the next pixel that needs
  // any; the lane goes idle when the tile has none left.
  void start(Tile& tile, Paths& s, int l) const {
    if (s.live[l] == 0 || s.pixel[l]->samples >= tile.target_spp) {
      s.pixel[l] = tile.next(s.x[l], s.y[l]);
      s.live[l] = 0;
      if (s.pixel[l] == nullptr) return;
    }
    const RenderSettings& rs = c_.settings;
    const int x = s.x[l], y = s.y[l];
    const PathSampler sampler(uint32_t(y) * uint32_t(rs.width) + uint32_t(x), s.pixel[l]->samples, rs.seed, rs.block());
    const PathSampler::Group j = sampler.get(SampleDimensions::kPixel);
    const float fx = float(x) + (rs.pixel_centre ? 0.5f : j[0]), fy = float(y) + (rs.pixel_centre ? 0.5f : j[1]);
    lanes::set(s.dir, l, c_.rays.direction(fx, fy));
    lanes::set(s.origin, l, c_.eye + c_.rays.origin_offset(fx, fy));
    lanes::set(s.beta, l, glm::vec3(1.0f));
    lanes::set(s.direct, l, glm::vec3(0.0f));
    lanes::set(s.indirect, l, glm::vec3(0.0f));
    s.prev_pdf[l] = 0.0f;
    s.depth[l] = 0;
    s.index[l] = sampler.index_in_block();
    s.sampler[l] = sampler;
    s.rays[l] = 0;
    s.live[l] = -1;
  }

  // make_surface for the lanes in `hit`: the triangle's vertices and material are gathered
  // lane by lane, the rest is computed for all lanes at once.
  Surfaces surfaces(LI hit, const RTCRayHit8& rh, const Paths& s) const {
    using namespace lanes;
    Surfaces sf;
    if constexpr (kPerLane) {
      for (int l = 0; l < kWidth; ++l) {
        if (hit[l] == 0) continue;
        Hit h;
        h.t = rh.ray.tfar[l], h.mesh = rh.hit.geomID[l], h.triangle = rh.hit.primID[l];
        h.b1 = rh.hit.u[l], h.b2 = rh.hit.v[l];
        const Surface one = make_surface<F>(c_, h, get(s.dir, l));
        set(sf.p, l, one.p), set(sf.ng, l, one.ng), set(sf.ns, l, one.ns), set(sf.base, l, one.bsdf.base);
        set(sf.emission, l, one.emission);
        sf.metallic[l] = one.bsdf.metallic, sf.offset[l] = one.offset, sf.black[l] = one.black ? -1 : 0;
        sf.t[l] = h.t, sf.area[l] = one.area, sf.cos_ray[l] = one.cos_ray;
        if constexpr (has(F, kEmissive))
          if (one.emission != glm::vec3(0.0f) && s.depth[l] > 0) sf.light_pmf[l] = c_.lights.triangle_pmf(h.mesh, h.triangle);
        if constexpr (has(F, kSpecular)) set(sf.bsdf, l, one.bsdf);
      }
      return sf;
    }
    V3 p0, p1, p2, ng, n0, n1, n2;
    LI normals{}, double_sided{};
    for (int l = 0; l < kWidth; ++l) {
      if (hit[l] == 0) continue;
      const uint32_t mesh_index = rh.hit.geomID[l], triangle = rh.hit.primID[l];
      const scenes::Mesh& mesh = c_.scene.meshes[mesh_index];
      const glm::uvec3 tri = mesh.triangles[triangle];
      const std::vector<glm::vec3>& pos = c_.bvh.positions()[mesh_index];
      set(p0, l, pos[tri.x]), set(p1, l, pos[tri.y]), set(p2, l, pos[tri.z]);
      const TriangleShape& shape = c_.bvh.shapes()[mesh_index][triangle];
      set(ng, l, shape.normal);
      sf.offset[l] = shape.offset;
      if (!mesh.normals.empty()) {
        normals[l] = -1;
        set(n0, l, mesh.normals[tri.x]), set(n1, l, mesh.normals[tri.y]), set(n2, l, mesh.normals[tri.z]);
      }
      const scenes::Material& m = c_.scene.materials[size_t(mesh.material)];
      double_sided[l] = m.double_sided ? -1 : 0;
      set(sf.base, l, glm::vec3(m.base_color));
      sf.metallic[l] = m.metallic;
      if constexpr (has(F, kSpecular)) set(sf.bsdf, l, c_.material_bsdf[size_t(mesh.material)]);
      if constexpr (has(F, kEmissive)) {
        sf.t[l] = rh.ray.tfar[l], sf.area[l] = shape.area;
        if (m.is_emissive()) {
          set(sf.emission, l, emitted_radiance<F>(c_.scene, m, glm::vec2(0.0f)));
          if (s.depth[l] > 0) sf.light_pmf[l] = c_.lights.triangle_pmf(mesh_index, triangle);
        }
      }
    }
    const LF b1 = load(rh.hit.u), b2 = load(rh.hit.v), b0 = 1.0f - b1 - b2;
    sf.p = b0 * p0 + b1 * p1 + b2 * p2;
    const LF cos_ray = dot(ng, s.dir);
    sf.cos_ray = abs(cos_ray);
    const LI back = ~(cos_ray < 0.0f);
    // The back of a one-sided material absorbs and emits nothing.
    sf.black = back & ~double_sided;
    sf.emission = select(sf.black, V3{}, sf.emission);
    V3 ns = select(normals, b0 * n0 + b1 * n1 + b2 * n2, ng);
    ng = select(back, -ng, ng), ns = select(back, -ns, ns);
    const LF nl = sqrt(dot(ns, ns));
    ns = select((nl > 0.0f) & is_finite(nl), ns / nl, ng);
    // Shading normals facing away from the viewer fall back to the geometric normal.
    ns = select(dot(ns, -s.dir) <= 1e-4f, ng, ns);
    sf.ng = ng, sf.ns = ns;
    sf.metallic = select(sf.metallic < 0.0f, LF(0.0f), select(1.0f < sf.metallic, LF(1.0f), sf.metallic));
    return sf;
  }

  // The BSDF's value and pdf for the lanes in `m` (the others: zero): bsdf_evaluate<true>, or
  // without a GGX lobe in the scene the Lambertian lobe alone.
  [[gnu::always_inline]] lanes::Eval evaluate(LI m, const Surfaces& sf, const V3& wo_l, const V3& wi_l) const {
    using namespace lanes;
    if constexpr (has(F, kSpecular)) {
      const Eval e = bsdf_evaluate(sf.bsdf, wo_l, wi_l);
      return {select(m, e.f, V3{}), select(m, e.pdf, LF{})};
    } else {
      return lambert(sf.base, sf.metallic, wo_l.z, wi_l.z);
    }
  }

  // LightSampler::sample for each lane in `m`, at the points p. Lights are picked lane by
  // lane; points on emissive triangles are then placed for all lanes at once.
  LightSamples sample_lights(LI m, const V3& p, const Group& u) const {
    using namespace lanes;
    LightSamples ls;
    [[maybe_unused]] Emitters em;
    for (int l = 0; l < kWidth; ++l) {
      if (m[l] == 0) continue;
      if constexpr (has(F, kEmissive) && !has(F, kTextures)) {
        const LightSampler::Pick pick = c_.lights.pick(u.u[2][l], u.u[3][l]);
        if (pick.emitter != nullptr) {
          const LightSampler::Emitter& e = *pick.emitter;
          em.on[l] = -1;
          set(em.p0, l, e.p0), set(em.p1, l, e.p1), set(em.p2, l, e.p2), set(em.n, l, e.n);
          glm::vec3 radiance = emitted_radiance<F>(c_.scene, *e.material, glm::vec2(0.0f));
          // LightSampler::sample's coverage; without textures and vertex colours (no lanes
          // otherwise) it is the material's.
          if (e.material->alpha_mode != scenes::AlphaMode::Opaque) radiance *= e.material->coverage(e.material->base_color.a);
          set(em.radiance, l, radiance);
          em.area[l] = e.area, em.pmf[l] = pick.pmf, em.offset[l] = e.offset;
          em.double_sided[l] = e.material->double_sided ? -1 : 0;
          continue;
        }
      }
      const LightSample one = c_.lights.sample<F>(get(p, l), std::array<float, 4>{u.u[0][l], u.u[1][l], u.u[2][l], u.u[3][l]});
      set(ls.wi, l, one.wi), set(ls.radiance, l, one.radiance), set(ls.point, l, one.point), set(ls.normal, l, one.normal);
      ls.distance[l] = one.distance, ls.pdf[l] = one.pdf, ls.offset[l] = one.offset;
      ls.delta[l] = one.delta ? -1 : 0, ls.area[l] = one.area ? -1 : 0;
    }
    if constexpr (has(F, kEmissive) && !has(F, kTextures)) {
      if (any(em.on)) {
        // LightSampler::sample's emissive triangle: a uniform point, its direction and
        // distance, and the pdf converted from area to solid angle.
        const LF su = sqrt(u.u[0]);
        const LF b1 = su * (1.0f - u.u[1]), b2 = su * u.u[1];
        const V3 point = (1.0f - b1 - b2) * em.p0 + b1 * em.p1 + b2 * em.p2;
        const V3 d = point - p;
        const LF d2 = dot(d, d);
        const LF distance = sqrt(d2);
        const V3 wi = d / distance;
        const LF cos_n = -dot(em.n, wi);
        const LI flip = cos_n <= 0.0f;  // the back: emits only when double-sided
        const LI ok = (d2 > 0.0f) & (em.area > 0.0f) & (~flip | em.double_sided);
        const LF cos_l = select(flip, -cos_n, cos_n);
        LF pdf = em.pmf * d2 / (em.area * cos_l);
        pdf = select(ok & is_finite(pdf), pdf, LF{});
        ls.wi = select(em.on, wi, ls.wi);
        ls.distance = select(em.on, distance, ls.distance);
        ls.radiance = select(em.on, em.radiance, ls.radiance);
        ls.pdf = select(em.on, pdf, ls.pdf);
        ls.delta &= ~em.on;
        ls.area = select(em.on, ok, ls.area);
        ls.point = select(em.on, point, ls.point);
        ls.offset = select(em.on, em.offset, ls.offset);
        ls.normal = select(em.on, select(flip, -em.n, em.n), ls.normal);
      }
    }
    return ls;
  }

  // Each lane's numbers of its group `g`.
  template <int skip>
  [[gnu::always_inline]] Group group(const Paths& s, LI g) const {
    LU scramble{};
    for (int l = 0; l < kWidth; ++l) scramble[l] = s.sampler[l].scramble(uint32_t(g[l]));
    return lanes::sobol_group<skip>(s.index, scramble, std::countr_zero(c_.settings.block()));
  }

  // Adds `v` to the direct or the indirect part of the lanes in `m`.
  static void add(Paths& s, LI m, LI to_direct, V3 v) {
    s.direct = lanes::select(m & to_direct, s.direct + v, s.direct);
    s.indirect = lanes::select(m & ~to_direct, s.indirect + v, s.indirect);
  }

  // PathIntegrator::bsdf_hit_weight.
  LF bsdf_hit_weight(LF pdf_bsdf, LF pdf_light) const {
    switch (c_.settings.estimator) {
      case Estimator::Mis: return lanes::power_heuristic(pdf_bsdf, pdf_light);
      case Estimator::LightOnly: return LF{};
      case Estimator::BsdfOnly: return LF(1.0f);
    }
    return LF{};
  }

  const RenderContext& c_;
};

}  // namespace giq::reference
