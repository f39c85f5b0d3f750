// The glTF BRDF: GGX is normalised, the visible-normal sampler draws directions with the pdf
// the evaluator reports, and the BRDF never reflects more than it receives.

#include <gtest/gtest.h>

#include "giq/reference/bsdf.h"

namespace giq::reference {
namespace {

glm::vec2 u2(uint32_t i, uint32_t d, uint64_t seed) { return {sample_1d(i, 0, d, seed), sample_1d(i, 0, d + 1, seed)}; }

TEST(Bsdf, GgxProjectedAreaIsOne) {
  // Integral of D(h) cos(theta_h) over the hemisphere is 1 (Walter et al. 2007, eq. 4);
  // estimated with cosine-weighted samples: E[D cos / (cos / pi)] = E[pi D].
  for (float alpha : {0.05f, 0.3f, 1.0f}) {
    const int n = 400000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
      const glm::vec3 h = square_to_cosine_hemisphere(u2(uint32_t(i), 0, 11));
      const double x = kPi * ggx_d(h, alpha);
      sum += x, sum2 += x * x;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0, 5.0 * se + 1e-3) << "alpha " << alpha;
  }
}

TEST(Bsdf, SamplingMatchesReportedPdf) {
  // For any function g, E_sampled[g / pdf] = integral of g over the hemisphere. With g = 1 on
  // a cap around the reflection direction, compare with the same integral by uniform sampling.
  BsdfParams p;
  p.base = {0.8f, 0.6f, 0.3f};
  p.metallic = 0.4f;
  p.alpha = 0.2f;
  const glm::vec3 wo = glm::normalize(glm::vec3(0.4f, -0.2f, 0.7f));
  const glm::vec3 r = glm::reflect(-wo, glm::vec3(0, 0, 1));
  const auto cap = [&](glm::vec3 w) { return glm::dot(w, r) > 0.9f ? 1.0 : 0.0; };
  const int n = 400000;
  double a = 0.0, a2 = 0.0, b = 0.0;
  for (int i = 0; i < n; ++i) {
    glm::vec3 wi;
    if (bsdf_sample<true>(p, wo, sample_1d(uint32_t(i), 0, 0, 3), u2(uint32_t(i), 1, 3), wi)) {
      const BsdfEval e = bsdf_evaluate<true>(p, wo, wi);
      ASSERT_GT(e.pdf, 0.0f);
      const double x = cap(wi) / e.pdf;
      a += x, a2 += x * x;
    }
    const glm::vec3 w = square_to_uniform_sphere(u2(uint32_t(i), 3, 3));
    if (w.z > 0.0f) b += cap(w) / kUniformSpherePdf;
  }
  a /= n, b /= n;
  const double se = std::sqrt((a2 / n - a * a) / n);
  const double exact = 2.0 * kPi * (1.0 - 0.9);  // the cap lies above the horizon
  EXPECT_NEAR(a, exact, 5.0 * se);
  EXPECT_NEAR(b, exact, 0.02 * exact);
}

TEST(Bsdf, ReflectsNoMoreThanItReceives) {
  // Directional albedo (integral of f cos over wi, importance sampled) stays <= 1 for a white
  // metal at every roughness and angle (single-scattering GGX only loses energy). glTF's
  // dielectric fresnel_mix weighs the diffuse lobe by 1 - F(v.h) rather than by the specular
  // lobe's albedo, so it can exceed 1 towards grazing view (glTF 2.0, Appendix B); it is held
  // to the bound at normal incidence only. Lambert gives its albedo.
  for (float metallic : {0.0f, 1.0f})
    for (float alpha : {0.01f, 0.25f, 1.0f})
      for (float cos_o : {0.1f, 0.5f, 1.0f}) {
        if (metallic == 0.0f && cos_o < 1.0f) continue;
        BsdfParams p;
        p.base = glm::vec3(1.0f);
        p.metallic = metallic;
        p.alpha = alpha;
        const glm::vec3 wo(std::sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
        const int n = 100000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
          glm::vec3 wi;
          if (!bsdf_sample<true>(p, wo, sample_1d(uint32_t(i), 0, 0, 8), u2(uint32_t(i), 1, 8), wi)) continue;
          const BsdfEval e = bsdf_evaluate<true>(p, wo, wi);
          sum += e.f.x * wi.z / e.pdf;
        }
        EXPECT_LE(sum / n, 1.0 + 0.01) << "metallic " << metallic << " alpha " << alpha << " cos " << cos_o;
        EXPECT_GT(sum / n, 0.3) << "metallic " << metallic << " alpha " << alpha << " cos " << cos_o;
      }
  BsdfParams lambert;
  lambert.base = glm::vec3(0.5f);
  lambert.specular_lobe = false;
  const BsdfEval e = bsdf_evaluate<true>(lambert, {0, 0, 1}, glm::normalize(glm::vec3(1, 0, 1)));
  EXPECT_FLOAT_EQ(e.f.x, 0.5f / kPi);
}

TEST(Bsdf, HeightCorrelatedSmithIsBoundedBySeparable) {
  // G2 >= G1(wo) G1(wi) (Heitz 2014, section 6: correlation can only reduce the shadowing).
  const glm::vec3 wo = glm::normalize(glm::vec3(0.8f, 0.1f, 0.3f)), wi = glm::normalize(glm::vec3(-0.5f, 0.4f, 0.2f));
  for (float alpha : {0.1f, 0.5f, 1.0f}) {
    EXPECT_GE(ggx_g2(wo, wi, alpha), ggx_g1(wo, alpha) * ggx_g1(wi, alpha) - 1e-6f);
    EXPECT_LE(ggx_g2(wo, wi, alpha), 1.0f);
  }
}

}  // namespace
}  // namespace giq::reference
