#pragma once
// bsdf.h's BRDF on eight lanes: the glTF metallic-roughness BRDF with KHR_materials_specular,
// evaluated and sampled for eight paths with each instruction. Every function does, lane by
// lane, the IEEE operations of its namesake in bsdf.h in the same order (glm's normalize is
// v * (1 / sqrt(v.v)), its reflect i - (n (n.i)) 2; std::clamp is the select below, std::max
// lanes.h's), and computes both sides of a branch where bsdf.h takes one: a path gives the
// same bits here as in PathIntegrator (tests/reference/lanes_test.cpp). A change to bsdf.h is
// a change here.
//
// The visible-normal sampling needs the sine and cosine of an angle: bsdf.h draws its disk
// point with the concentric map, whose quarter-range polynomials (sampling.h's
// sincos_quarter) both integrators share, instead of libm's sin and cos.

#include "giq/reference/bsdf.h"
#include "lanes.h"

namespace giq::reference::lanes {

// BsdfParams across the lanes.
struct Bsdf {
  V3 base, f0_dielectric;
  F metallic{}, alpha{}, f90_dielectric{};
  I specular_lobe{};  // -1: the GGX lobe; 0: pure Lambert
};
[[gnu::always_inline]] inline void set(Bsdf& b, int l, const BsdfParams& p) {
  set(b.base, l, p.base), set(b.f0_dielectric, l, p.f0_dielectric);
  b.metallic[l] = p.metallic, b.alpha[l] = p.alpha, b.f90_dielectric[l] = p.f90_dielectric;
  b.specular_lobe[l] = p.specular_lobe ? -1 : 0;
}

[[gnu::always_inline]] inline V3 cross(V3 a, V3 b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
[[gnu::always_inline]] inline V3 normalize(V3 v) { return v * (1.0f / sqrt(dot(v, v))); }
[[gnu::always_inline]] inline V3 reflect(V3 i, V3 n) { return i - n * dot(n, i) * F(2.0f); }
// std::clamp(v, lo, hi): v < lo ? lo : hi < v ? hi : v.
[[gnu::always_inline]] inline F clamp(F v, F lo, F hi) { return select(v < lo, lo, select(hi < v, hi, v)); }

// sampling.h's square_to_concentric_disk.
struct Disk {
  F x, y;
};
[[gnu::always_inline]] inline Disk concentric_disk(F ux, F uy) {
  const F ox = 2.0f * ux - 1.0f, oy = 2.0f * uy - 1.0f;
  const I x_wedge = abs(ox) > abs(oy);
  const F r = select(x_wedge, ox, oy), q = select(x_wedge, oy, ox);
  const SinCosOf<F> a = sincos_quarter(select(r != 0.0f, (kPi / 4.0f) * (q / r), F{}));
  return {r * select(x_wedge, a.cos, a.sin), r * select(x_wedge, a.sin, a.cos)};
}
// sampling.h's square_to_cosine_hemisphere.
[[gnu::always_inline]] inline V3 cosine_hemisphere(F ux, F uy) {
  const Disk d = concentric_disk(ux, uy);
  return {d.x, d.y, sqrt(max(F{}, 1.0f - d.x * d.x - d.y * d.y))};
}
// sampling.h's cosine_hemisphere_pdf.
[[gnu::always_inline]] inline F cosine_hemisphere_pdf(F cos_theta) { return select(cos_theta > 0.0f, cos_theta * kInvPi, F{}); }

[[gnu::always_inline]] inline V3 fresnel_schlick(V3 f0, V3 f90, F cos_theta) {
  const F m = clamp(1.0f - cos_theta, F(0.0f), F(1.0f));
  const F m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

[[gnu::always_inline]] inline F ggx_d(V3 h, F alpha) {
  const F a2 = alpha * alpha;
  const F t = h.z * h.z * (a2 - 1.0f) + 1.0f;
  return select(h.z <= 0.0f, F{}, a2 / (kPi * t * t));
}

[[gnu::always_inline]] inline F ggx_lambda(V3 w, F alpha) {
  const F c2 = w.z * w.z;
  const F tan2 = max(F{}, 1.0f - c2) / c2;
  return select(c2 <= 0.0f, F{}, 0.5f * (-1.0f + sqrt(1.0f + alpha * alpha * tan2)));
}
[[gnu::always_inline]] inline F ggx_g1(V3 w, F alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
[[gnu::always_inline]] inline F ggx_g2(V3 wo, V3 wi, F alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

[[gnu::always_inline]] inline V3 ggx_sample_visible_normal(V3 wo, F alpha, F ux, F uy) {
  const V3 vh = normalize({alpha * wo.x, alpha * wo.y, wo.z});
  const F lensq = vh.x * vh.x + vh.y * vh.y;
  const V3 t1 = select(lensq > 0.0f, V3{-vh.y, vh.x, F{}} / sqrt(lensq), V3{F(1.0f), F{}, F{}});
  const V3 t2 = cross(vh, t1);
  const Disk d = concentric_disk(ux, uy);
  const F p1 = d.x;
  const F s = 0.5f * (1.0f + vh.z);
  const F p2 = (1.0f - s) * sqrt(max(F{}, 1.0f - p1 * p1)) + s * d.y;
  const V3 nh = p1 * t1 + p2 * t2 + sqrt(max(F{}, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return normalize({alpha * nh.x, alpha * nh.y, max(F(1e-6f), nh.z)});
}

[[gnu::always_inline]] inline F ggx_reflection_pdf(V3 wo, V3 h, F alpha) {
  return select(wo.z <= 0.0f, F{}, ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z));
}

[[gnu::always_inline]] inline F specular_lobe_probability(const Bsdf& p, F cos_o) {
  const F fd = max_component(fresnel_schlick(p.f0_dielectric, splat(p.f90_dielectric), cos_o));
  const F spec = p.metallic + (1.0f - p.metallic) * fd;
  const F diff = (1.0f - p.metallic) * (1.0f - fd) * max_component(p.base);
  const F s = spec / max(spec + diff, F(1e-8f));
  return select(p.specular_lobe, clamp(s, F(0.05f), F(1.0f)), F{});
}

// BsdfEval across the lanes.
struct Eval {
  V3 f;
  F pdf;
};

// bsdf.h's bsdf_evaluate without a specular lobe: the Lambertian value and the cosine pdf.
[[gnu::always_inline]] inline Eval lambert(V3 base, F metallic, F cos_o, F cos_i) {
  const I on = ~((cos_o <= 0.0f) | (cos_i <= 0.0f));  // as bsdf_evaluate tests it, NaN included
  const V3 f = base * ((1.0f - metallic) * kInvPi);
  return {select(on, f, V3{}), select(on & (cos_i > 0.0f), cos_i * kInvPi, F{})};
}

// bsdf_evaluate<true>: f and the sampling pdf; zero on lanes with either direction below the
// surface.
[[gnu::always_inline]] inline Eval bsdf_evaluate(const Bsdf& p, V3 wo, V3 wi) {
  const I on = ~((wo.z <= 0.0f) | (wi.z <= 0.0f));  // as bsdf.h tests it, NaN included
  const F pdf_cos = cosine_hemisphere_pdf(wi.z);
  const Eval diffuse = lambert(p.base, p.metallic, wo.z, wi.z);  // without the GGX lobe
  const V3 h = normalize(wo + wi);
  const F voh = max(F{}, dot(wo, h));
  const F dv = ggx_d(h, p.alpha) * ggx_g2(wo, wi, p.alpha) / (4.0f * wo.z * wi.z);
  const V3 fd = fresnel_schlick(p.f0_dielectric, splat(p.f90_dielectric), voh);
  const V3 fm = fresnel_schlick(p.base, splat(F(1.0f)), voh);
  const V3 dielectric = (1.0f - max_component(fd)) * p.base * F(kInvPi) + fd * dv;
  const V3 ggx = (1.0f - p.metallic) * dielectric + p.metallic * fm * dv;
  const F ps = specular_lobe_probability(p, wo.z);
  const F pdf_ggx = ps * ggx_reflection_pdf(wo, h, p.alpha) + (1.0f - ps) * pdf_cos;
  return {select(p.specular_lobe, select(on, ggx, V3{}), diffuse.f),
          select(p.specular_lobe, select(on, pdf_ggx, F{}), diffuse.pdf)};
}

// bsdf_sample<true>: wi for wo; `ok` is bsdf_sample's result (false: the path ends).
struct Sample {
  V3 wi;
  I ok;
};
[[gnu::always_inline]] inline Sample bsdf_sample(const Bsdf& p, V3 wo, F u_lobe, F ux, F uy) {
  const I specular = p.specular_lobe & (u_lobe < specular_lobe_probability(p, wo.z));
  const V3 wi = select(specular, reflect(-wo, ggx_sample_visible_normal(wo, p.alpha, ux, uy)), cosine_hemisphere(ux, uy));
  return {wi, ~(wo.z <= 0.0f) & (wi.z > 0.0f)};
}

}  // namespace giq::reference::lanes
