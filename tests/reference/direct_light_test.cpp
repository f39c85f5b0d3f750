// Analytic direct lighting: a Lambertian plane of albedo rho under one punctual light has
// radiance (rho / pi) * E, with E the irradiance the light's closed form gives
// (KHR_lights_punctual: I cos(theta) / d^2 times the range window and the spot falloff for
// point and spot lights; E cos(theta) for a directional light). Each pixel is compared with
// the closed form averaged over the pixel's footprint (the render's box filter).

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <vector>

#include "giq/reference/bsdf.h"

#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

constexpr float kRho = 0.6f;
constexpr int kSize = 16;

scenes::Scene plane_with(const scenes::Light& light) {
  scenes::Scene s;
  const int m = test::add_material(s, test::diffuse(glm::vec3(kRho)));
  test::add_quad(s, m, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, {-10, 0, -10});
  s.lights.push_back(light);
  s.derive();
  return s;
}

const scenes::Camera kCamera = scenes::Camera::look_at({0.0f, 4.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 1.0f);

// Closed-form irradiance (per unit radiant intensity colour) at a point q of the plane y = 0.
using Irradiance = std::function<double(glm::dvec3 q)>;

void expect_matches(const scenes::Scene& s, const Irradiance& irradiance, glm::vec3 colour) {
  RenderSettings rs;
  rs.width = rs.height = kSize;
  rs.max_bounces = 1;
  Renderer r(s, kCamera, rs);
  Film f = r.make_film();
  r.render(f, 64);
  EXPECT_EQ(f.nonfinite_samples(), 0u);
  constexpr int kSub = 16;  // quadrature of the pixel footprint
  std::vector<double> irr(kSize * kSize);
  double peak = 0.0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      double e = 0.0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i) {
          const glm::dvec3 d = kCamera.ray_direction(x + (i + 0.5f) / kSub, y + (j + 0.5f) / kSub, kSize, kSize);
          const glm::dvec3 q = glm::dvec3(kCamera.position) + d * (-double(kCamera.position.y) / d.y);
          e += irradiance(q);
        }
      e /= kSub * kSub;
      irr[size_t(y) * kSize + size_t(x)] = e;
      peak = std::max(peak, e * kRho / 3.14159265358979323846 * max_component(colour));
    }
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double e = irr[size_t(y) * kSize + size_t(x)];
      const PixelAccumulator& p = f.pixels[size_t(y) * kSize + size_t(x)];
      for (int c = 0; c < 3; ++c) {
        const double expected = kRho / 3.14159265358979323846 * e * colour[c];
        // 5 standard errors (768 comparisons), plus the quadrature's error on the steepest
        // pixels and, for pixels straddling a cut-off (range, cone) whose 64 jittered samples
        // all fell on one side so that their variance reads 0, a thousandth of the peak.
        const double tol = 5.0 * std::sqrt(p.variance_of_mean(c)) + 2e-3 * expected + 1e-3 * peak;
        ASSERT_NEAR(p.mean[c], expected, tol) << "pixel (" << x << ", " << y << ") channel " << c;
      }
    }
}

TEST(DirectLight, PointLightFollowsInverseSquareAndCosine) {
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.5f, 1.0f, 0.2f};
  l.intensity = 3.0f;
  l.color = {1.0f, 0.5f, 0.25f};
  const glm::dvec3 lp(l.position);
  expect_matches(plane_with(l), [&](glm::dvec3 q) {
    const glm::dvec3 v = lp - q;
    const double d2 = glm::dot(v, v);
    return 3.0 * (v.y / std::sqrt(d2)) / d2;
  }, l.color);
}

TEST(DirectLight, PointLightRangeWindow) {
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.0f, 0.8f, 0.0f};
  l.intensity = 2.0f;
  l.range = 1.5f;
  const glm::dvec3 lp(l.position);
  expect_matches(plane_with(l), [&](glm::dvec3 q) {
    const glm::dvec3 v = lp - q;
    const double d2 = glm::dot(v, v), d = std::sqrt(d2);
    // KHR_lights_punctual, "Range Property": clamp(1 - (d / range)^4, 0, 1).
    const double window = std::clamp(1.0 - std::pow(d / 1.5, 4.0), 0.0, 1.0);
    return 2.0 * window * (v.y / d) / d2;
  }, l.color);
}

TEST(DirectLight, SpotLightConeFalloffMatchesGltf) {
  scenes::Light l;
  l.type = scenes::LightType::Spot;
  l.position = {0.1f, 2.0f, -0.2f};
  l.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  l.inner_cone = 0.2f;
  l.outer_cone = 0.5f;
  l.intensity = 5.0f;
  const glm::dvec3 lp(l.position), axis(l.direction);
  expect_matches(plane_with(l), [&](glm::dvec3 q) {
    const glm::dvec3 v = lp - q;
    const double d2 = glm::dot(v, v), d = std::sqrt(d2);
    // KHR_lights_punctual, "Inner and Outer Cone Angles": a linear ramp in the cosine between
    // cos(outer) and cos(inner), squared.
    const double cd = glm::dot(axis, -v / d);
    const double t = std::clamp((cd - std::cos(0.5)) / (std::cos(0.2) - std::cos(0.5)), 0.0, 1.0);
    return 5.0 * t * t * (v.y / d) / d2;
  }, l.color);
}

TEST(DirectLight, DirectionalLightGivesIrradianceTimesCosine) {
  scenes::Light l;
  l.type = scenes::LightType::Directional;
  l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  l.intensity = 2.0f;
  l.color = {0.2f, 1.0f, 0.6f};
  const double cos_theta = -double(l.direction.y);
  expect_matches(plane_with(l), [&](glm::dvec3) { return 2.0 * cos_theta; }, l.color);
}

}  // namespace
}  // namespace giq::reference
