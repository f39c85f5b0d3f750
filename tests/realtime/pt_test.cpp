// `pt` against closed forms: a white furnace (a closed emitting and reflecting box), and a
// Lambertian plane under a point and a directional light.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "giq/realtime/renderer.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

class PtTest : public test::VulkanTest {
 protected:
  image::Image render(const scenes::Scene& s, const std::string& view, uint32_t size, int spp, int max_bounces = 64) {
    RenderOptions o;
    o.technique = "pt";
    o.view = view;
    o.width = o.height = size;
    o.parameters = {"samples_per_frame=" + std::to_string(spp), "max_bounces=" + std::to_string(max_bounces)};
    return render_last(s, o);
  }
};

// A closed cube whose inner faces all emit Le and reflect with albedo rho: the radiance
// everywhere is Le / (1 - rho) (the Neumann series Le (1 + rho + rho^2 + ...)). Direct light
// is what the camera sees directly plus one reflection: Le (1 + rho).
scenes::Scene furnace(float rho, float le) {
  scenes::Scene s;
  const int m = test::add_material(s, glm::vec3(rho), glm::vec3(le));
  test::add_quad(s, {-1, -1, 1}, {1, -1, 1}, {1, -1, -1}, {-1, -1, -1}, m);
  test::add_quad(s, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1}, m);
  test::add_quad(s, {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, m);
  test::add_quad(s, {-1, -1, 1}, {-1, -1, -1}, {-1, 1, -1}, {-1, 1, 1}, m);
  test::add_quad(s, {1, -1, -1}, {1, -1, 1}, {1, 1, 1}, {1, 1, -1}, m);
  test::add_quad(s, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, m);
  s.views.push_back({"in", scenes::Camera::look_at({0.1f, 0.2f, 0.3f}, {-0.5f, -0.2f, -1.0f}, {0, 1, 0}, 1.4f), -1});
  s.derive();
  return s;
}

// Mean over the image against `expected`, within 4 standard errors of that mean (pixels are
// independent, so the variance of the image mean is the sum of the per-pixel variances of
// the mean over n^2). Per pixel, every pixel has the same expected value and distribution
// here, so each is compared with the pooled standard deviation: a per-pixel sample variance
// from few paths underestimates the spread of Russian roulette's skewed estimator.
void expect_within_noise(const image::Image& img, const std::string& layer, double expected, double rel_floor = 1e-5) {
  const auto ch = img.layer_channels(layer);
  const auto var = img.layer_channels("variance");
  double sum = 0.0, var_sum = 0.0;
  const size_t n = img.pixel_count();
  for (size_t i = 0; i < n; ++i) {
    const double v = img.channel(ch[1])[i];
    ASSERT_TRUE(std::isfinite(v));
    sum += v;
    var_sum += img.channel(var[1])[i];
  }
  const double mean = sum / double(n), se = std::sqrt(var_sum) / double(n);
  EXPECT_NEAR(mean, expected, 4.0 * se + rel_floor * expected) << layer << " mean over the image, se " << se;
  const double pooled_sigma = std::sqrt(var_sum / double(n));
  size_t outliers = 0;
  for (size_t i = 0; i < n; ++i) outliers += std::abs(img.channel(ch[1])[i] - expected) > 4.0 * pooled_sigma;
  // Beyond 4 sigma: 6e-5 of a normal population; Chebyshev's bound for any distribution, 1/16.
  EXPECT_LE(double(outliers), 0.01 * double(n)) << outliers << " pixels beyond 4 pooled sigma";
}

TEST_F(PtTest, WhiteFurnaceMatchesTheNeumannSeries) {
  const float rho = 0.5f, le = 1.0f;
  const image::Image img = render(furnace(rho, le), "in", 32, 64);
  expect_within_noise(img, "", le / (1.0 - rho));
  // The split: direct = Le (1 + rho). Its noise is at most the beauty's (it is part of the
  // same paths), so the beauty's variance bounds it.
  double sum = 0.0, var = 0.0;
  for (size_t i = 0; i < img.pixel_count(); ++i) sum += img.channel("direct.G")[i], var += img.channel("variance.G")[i];
  const double n = double(img.pixel_count());
  EXPECT_NEAR(sum / n, le * (1.0 + rho), 4.0 * std::sqrt(var) / n + 1e-5);
}

TEST_F(PtTest, DarkFurnaceIsPureEmission) {
  const image::Image img = render(furnace(0.0f, 3.0f), "in", 16, 4);
  for (size_t i = 0; i < img.pixel_count(); ++i) {
    EXPECT_FLOAT_EQ(img.channel("R")[i], 3.0f);
    EXPECT_FLOAT_EQ(img.channel("indirect.R")[i], 0.0f);
  }
}

// Lambertian plane y = 0 under a point light of intensity I at height h: radiance
// rho / pi * I * cos(theta) / d^2 = rho / pi * I * h / d^3, with no indirect light (nothing
// else in the scene). The pixel value is the average over the pixel, so the comparison is
// at pixel centres with the second-order change of the function across a pixel as tolerance.
TEST_F(PtTest, PointLightOnALambertianPlane) {
  const float rho = 0.8f, h = 2.0f, intensity = 10.0f;
  scenes::Scene s = test::lambert_plane(rho);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.3f, h, -0.2f};
  l.intensity = intensity;
  s.lights.push_back(l);
  s.derive();
  const int size = 32;
  const image::Image img = render(s, "top", size, 16);
  const auto& cam = s.views[0].camera;
  auto radiance = [&](float px, float py) {
    const glm::vec3 d = cam.ray_direction(px, py, size, size);
    const glm::vec3 p = cam.position + (-cam.position.y / d.y) * d;
    const double dist = glm::length(l.position - p);
    return rho / M_PI * intensity * h / (dist * dist * dist);
  };
  size_t outliers = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // The pixel's exact value is the box-filtered radiance: a 16 x 16 midpoint quadrature,
      // whose error on this smooth function is far below the path tracer's noise.
      double expected = 0.0;
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) expected += radiance(x + (i + 0.5f) / 16.0f, y + (j + 0.5f) / 16.0f);
      expected /= 256.0;
      const double v = img.at("R", x, y), sigma = std::sqrt(img.at("variance.R", x, y));
      outliers += std::abs(v - expected) > 4.0 * sigma + 1e-4 * expected;
      EXPECT_EQ(img.at("indirect.R", x, y), 0.0f);
    }
  EXPECT_LE(double(outliers), 0.005 * size * size) << outliers << " pixels beyond 4 sigma";
}

TEST_F(PtTest, DirectionalLightIsUniformIrradiance) {
  const float rho = 0.5f, e = 3.0f;
  scenes::Scene s = test::lambert_plane(rho);
  scenes::Light l;
  l.type = scenes::LightType::Directional;
  l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.1f));
  l.intensity = e;
  s.lights.push_back(l);
  s.derive();
  const image::Image img = render(s, "top", 16, 2);
  const double expected = rho / M_PI * e * (-l.direction.y);
  for (size_t i = 0; i < img.pixel_count(); ++i) EXPECT_NEAR(img.channel("G")[i], expected, 1e-5 * expected);
}

}  // namespace
}  // namespace giq::realtime
