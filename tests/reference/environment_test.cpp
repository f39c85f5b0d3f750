// Environment maps in the reference: the equirectangular mapping (scenes/environment.h), the
// importance-sampling distribution (a density over the sphere that the samples follow), and a
// Lambertian plane under a map against its closed-form radiance.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "environment_distribution.h"
#include "giq/reference/renderer.h"
#include "giq/reference/sampling.h"
#include "giq/scenes/environment.h"
#include "giq/scenes/light.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

constexpr double kPi = std::numbers::pi;

// A map with a bright band, a dim hemisphere, colour varying round the horizon and one hot
// texel (a sun), W x H.
std::vector<glm::vec3> test_map(int w, int h) {
  std::vector<glm::vec3> m(size_t(w) * size_t(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float az = float(x) / float(w), el = float(y) / float(h);
      glm::vec3 c(0.2f + 0.8f * az, 0.5f, 1.0f - 0.7f * az);
      c *= el < 0.5f ? 1.0f + 3.0f * el : 0.05f;
      m[size_t(y) * size_t(w) + size_t(x)] = c;
    }
  m[size_t(h / 5) * size_t(w) + size_t(w / 3)] = glm::vec3(4000.0f, 3800.0f, 3500.0f);
  return m;
}

scenes::Scene with_map(scenes::Scene s, int w, int h) {
  s.set_environment_map(w, h, test_map(w, h), "test map");
  return s;
}

TEST(EnvironmentMap, MappingIsTheDocumentedOne) {
  // -Z at the centre, +X a quarter turn on, the zenith on the top row.
  EXPECT_NEAR(scenes::equirect_uv({0, 0, -1}).x, 0.5f, 1e-6f);
  EXPECT_NEAR(scenes::equirect_uv({1, 0, 0}).x, 0.75f, 1e-6f);
  EXPECT_NEAR(scenes::equirect_uv({0, 0, -1}).y, 0.5f, 1e-6f);
  EXPECT_NEAR(scenes::equirect_uv({0, 1, 0}).y, 0.0f, 1e-6f);
  EXPECT_NEAR(scenes::equirect_uv({0, -1, 0}).y, 1.0f, 1e-6f);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec2 uv(u01(rng), 0.01f + 0.98f * u01(rng));
    const glm::vec3 d = scenes::equirect_direction(uv);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    const glm::vec2 back = scenes::equirect_uv(d);
    EXPECT_NEAR(std::remainder(back.x - uv.x, 1.0f), 0.0f, 2e-5f);
    EXPECT_NEAR(back.y, uv.y, 2e-5f);
  }
  // The scene reads the texel the mapping names.
  scenes::Scene s = with_map(test::cornell(), 64, 32);
  EXPECT_EQ(s.environment_radiance({0, 0, -1}), test_map(64, 32)[size_t(16) * 64 + 32]);
  EXPECT_TRUE(s.features.environment && s.features.environment_map);
}

// The density integrates to 1 over the sphere (uniform directions), and sampling follows it:
// the integral of the map's luminance estimated from its own samples matches the texels'
// exact sum of luminance times solid angle. Both within 4 standard errors.
TEST(EnvironmentMap, SamplesFollowTheirDensity) {
  const int w = 64, h = 32;
  const scenes::Scene s = with_map(test::cornell(), w, h);
  const scenes::Texture& map = s.textures[size_t(s.environment_map)];
  const EnvironmentDistribution dist(map);
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  const int n = 400000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 d = square_to_uniform_sphere({u01(rng), u01(rng)});
    const double x = double(dist.pdf(d)) * 4.0 * kPi;
    sum += x, sum2 += x * x;
  }
  double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, 1.0, 4.0 * se) << "se " << se;

  double exact = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      exact += scenes::luminance(glm::vec3(map.texel(x, y))) * (2.0 * kPi / w) * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
  sum = sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    float pdf = 0.0f;
    const glm::vec3 d = dist.sample({u01(rng), u01(rng)}, pdf);
    ASSERT_GT(pdf, 0.0f);
    const double x = scenes::luminance(s.environment_radiance(d)) / pdf;
    sum += x, sum2 += x * x;
  }
  mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  EXPECT_NEAR(mean, exact, 4.0 * se + 1e-6 * exact) << "se " << se;
  // Importance sampling: luminance / pdf varies little (only sin(theta) within a row).
  EXPECT_LT(se / exact, 0.002);
}

// A white Lambertian plane facing +y under the map: every point sees the upper hemisphere, so
// its radiance is rho / pi x E with E = sum over the upper rows' texels of L x (2 pi / W) x
// (sin^2 theta1 - sin^2 theta0) / 2, exactly. Rendered with the map's importance sampling
// (and MIS with the BSDF), compared within 4 standard errors of the image mean.
TEST(EnvironmentMap, LambertianPlaneGetsTheClosedFormIrradiance) {
  const int w = 64, h = 32;
  const float rho = 0.8f;
  scenes::Scene s;
  const int m = test::add_material(s, test::diffuse(glm::vec3(rho)));
  const float half = 1000.0f;
  test::add_quad(s, m, {-half, 0, half}, {half, 0, half}, {half, 0, -half}, {-half, 0, -half});
  s.views.push_back({"down", scenes::Camera::look_at({0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, -1}, 0.2f), -1});
  s.derive();
  s = with_map(std::move(s), w, h);
  const std::vector<glm::vec3> map = test_map(w, h);
  glm::dvec3 e(0.0);
  for (int y = 0; y < h / 2; ++y) {
    const double s0 = std::sin(kPi * y / h), s1 = std::sin(kPi * (y + 1) / h);
    for (int x = 0; x < w; ++x) e += glm::dvec3(map[size_t(y) * size_t(w) + size_t(x)]) * (2.0 * kPi / w) * (s1 * s1 - s0 * s0) / 2.0;
  }
  const glm::dvec3 expected = double(rho) / kPi * e;

  RenderSettings rs;
  rs.width = rs.height = 32;
  const Renderer r(s, s.views[0].camera, rs);
  Film film = r.make_film();
  r.render(film, 64);
  const image::Image img = film.to_image();
  for (int c = 0; c < 3; ++c) {
    const float* p = img.channel(std::string(1, "RGB"[c]));
    double sum = 0.0, sum2 = 0.0;
    const size_t n = img.pixel_count();
    for (size_t i = 0; i < n; ++i) sum += p[i], sum2 += double(p[i]) * p[i];
    const double mean = sum / double(n), se = std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean) / double(n));
    EXPECT_NEAR(mean, expected[c], 4.0 * se + 1e-5 * expected[c]) << "channel " << c << " se " << se;
  }
}

}  // namespace
}  // namespace giq::reference
