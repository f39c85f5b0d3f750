#pragma once
// The glTF 2.0 metallic-roughness BRDF (glTF 2.0 specification, Appendix B, "BRDF
// Implementation") with KHR_materials_specular, in a local shading frame where the normal is
// +z. All functions are pure; the integrator composes them. reference/src/lane_bsdf.h computes
// the same on eight lanes with the same bits: a change here is a change there.
//
//   f = (1 - metallic) * dielectric + metallic * metal
//   dielectric = (1 - specular * max(F_d)) * base / pi + F_d * D * V   (KHR_materials_specular)
//   metal      = F_m * D * V
//   F_d = Schlick(F0 = min(0.04 * specular_color, 1) * specular, F90 = specular)
//   F_m = Schlick(F0 = base colour, F90 = 1)
//   D   = GGX / Trowbridge-Reitz with alpha = roughness^2
//   V   = G2 / (4 |n.l| |n.v|), G2 the height-correlated Smith term (Heitz 2014, "Understanding
//         the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 99)
//
// Sampling mixes a cosine-weighted diffuse lobe with the GGX distribution of visible normals
// (Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)); the pdf of a
// direction is the mixture's, so evaluation and sampling agree for MIS.

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

#include "giq/reference/sampling.h"

namespace giq::reference {

// Roughness below this is clamped: alpha = 1e-3 is a near-mirror whose D still fits a float.
inline constexpr float kMinAlpha = 1e-3f;

struct BsdfParams {
  glm::vec3 base{1.0f};  // base colour (linear RGB)
  float metallic = 0.0f;
  float alpha = 1.0f;    // GGX alpha = roughness^2, >= kMinAlpha
  glm::vec3 f0_dielectric{0.04f};  // min(0.04 * specular_color, 1) * specular
  float f90_dielectric = 1.0f;     // specular
  bool specular_lobe = true;       // false: pure Lambert (Material::has_specular_lobe)
};

inline float max_component(glm::vec3 v) { return std::max(v.x, std::max(v.y, v.z)); }

// Schlick's approximation (Schlick 1994, "An Inexpensive BRDF Model for Physically-based
// Rendering", eq. 15) with an explicit F90 as in KHR_materials_specular.
inline glm::vec3 fresnel_schlick(glm::vec3 f0, glm::vec3 f90, float cos_theta) {
  const float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
  const float m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

// GGX normal distribution (Walter et al. 2007, "Microfacet Models for Refraction through Rough
// Surfaces", eq. 33), for a microfacet normal h in the local frame.
inline float ggx_d(glm::vec3 h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float t = h.z * h.z * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * t * t);
}

// Smith's Lambda for GGX (Heitz 2014, eq. 72): (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2.
inline float ggx_lambda(glm::vec3 w, float alpha) {
  const float c2 = w.z * w.z;
  if (c2 <= 0.0f) return 0.0f;
  const float tan2 = std::max(0.0f, 1.0f - c2) / c2;
  return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}
inline float ggx_g1(glm::vec3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
// Height-correlated masking-shadowing (Heitz 2014, eq. 99).
inline float ggx_g2(glm::vec3 wo, glm::vec3 wi, float alpha) {
  return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// Visible normal for view wo (wo.z > 0) from two uniform numbers (Heitz 2018, listing 1).
inline glm::vec3 ggx_sample_visible_normal(glm::vec3 wo, float alpha, glm::vec2 u) {
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 = lensq > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lensq) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(vh, t1);
  // A uniform point on the unit disk: Heitz's listing draws it in polar coordinates; the
  // concentric map draws the same distribution with sincos_quarter's polynomials instead of
  // libm's sin and cos, which the eight-lane integrator can then compute with the same bits
  // (lane_bsdf.h).
  const glm::vec2 d = square_to_concentric_disk(u);
  const float p1 = d.x;
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * d.y;
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(1e-6f, nh.z)));
}

// pdf of the reflected direction wi when h is drawn from the visible normals of wo:
// D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z) (Heitz 2018, eq. 3 and the reflection Jacobian).
inline float ggx_reflection_pdf(glm::vec3 wo, glm::vec3 h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z);
}

// Probability of sampling the specular lobe: its share of the reflectance at normal-ish
// incidence (a heuristic; any value in (0, 1) keeps the estimator unbiased).
inline float specular_lobe_probability(const BsdfParams& p, float cos_o) {
  if (!p.specular_lobe) return 0.0f;
  const float fd = max_component(fresnel_schlick(p.f0_dielectric, glm::vec3(p.f90_dielectric), cos_o));
  const float spec = p.metallic + (1.0f - p.metallic) * fd;
  const float diff = (1.0f - p.metallic) * (1.0f - fd) * max_component(p.base);
  const float s = spec / std::max(spec + diff, 1e-8f);
  return std::clamp(s, 0.05f, 1.0f);
}

struct BsdfEval {
  glm::vec3 f{0.0f};  // BRDF value (not multiplied by the cosine)
  float pdf = 0.0f;   // solid-angle pdf of sampling wi given wo
};

// f(wo, wi) and the sampling pdf; both in the local frame, both directions above the surface.
template <bool kSpecular>
BsdfEval bsdf_evaluate(const BsdfParams& p, glm::vec3 wo, glm::vec3 wi) {
  BsdfEval e;
  if (wo.z <= 0.0f || wi.z <= 0.0f) return e;
  if (!kSpecular || !p.specular_lobe) {
    e.f = p.base * ((1.0f - p.metallic) * kInvPi);
    e.pdf = cosine_hemisphere_pdf(wi.z);
    return e;
  }
  const glm::vec3 h = glm::normalize(wo + wi);
  const float voh = std::max(0.0f, glm::dot(wo, h));
  const float dv = ggx_d(h, p.alpha) * ggx_g2(wo, wi, p.alpha) / (4.0f * wo.z * wi.z);
  const glm::vec3 fd = fresnel_schlick(p.f0_dielectric, glm::vec3(p.f90_dielectric), voh);
  const glm::vec3 fm = fresnel_schlick(p.base, glm::vec3(1.0f), voh);
  const glm::vec3 dielectric = (1.0f - max_component(fd)) * p.base * kInvPi + fd * dv;
  e.f = (1.0f - p.metallic) * dielectric + p.metallic * fm * dv;
  const float ps = specular_lobe_probability(p, wo.z);
  e.pdf = ps * ggx_reflection_pdf(wo, h, p.alpha) + (1.0f - ps) * cosine_hemisphere_pdf(wi.z);
  return e;
}

// Samples wi for wo: u_lobe picks the lobe, u the direction. Returns false when the sampled
// direction falls below the surface (the path ends: that energy is absorbed by the model).
template <bool kSpecular>
bool bsdf_sample(const BsdfParams& p, glm::vec3 wo, float u_lobe, glm::vec2 u, glm::vec3& wi) {
  if (wo.z <= 0.0f) return false;
  if (kSpecular && p.specular_lobe && u_lobe < specular_lobe_probability(p, wo.z)) {
    const glm::vec3 h = ggx_sample_visible_normal(wo, p.alpha, u);
    wi = glm::reflect(-wo, h);
  } else {
    wi = square_to_cosine_hemisphere(u);
  }
  return wi.z > 0.0f;
}

}  // namespace giq::reference
