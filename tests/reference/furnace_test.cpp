// White furnace tests: closed scenes whose radiance is known exactly for any albedo.
//
// Inside a closed box whose walls have albedo rho and emit Le, every point sees radiance
// L = Le + rho L, so L = Le / (1 - rho) (the Neumann series of the rendering equation).
// A Lambertian object of albedo 1 under a constant environment L reflects exactly L.

#include <gtest/gtest.h>

#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

void expect_uniform(const Film& f, double expected, const char* what) {
  // Each 4x4 block against the analytic value, within 4 standard errors.
  for (int y = 0; y < f.height; y += 4)
    for (int x = 0; x < f.width; x += 4) {
      const test::BlockStat b = test::block_luminance(f, x, y, 4, 4);
      const double tol = 4.0 * std::sqrt(b.variance) + 1e-5 * expected;
      ASSERT_NEAR(b.mean, expected, tol) << what << " block (" << x << ", " << y << ")";
    }
  EXPECT_EQ(f.nonfinite_samples(), 0u);
}

class BoxFurnace : public ::testing::TestWithParam<float> {};

TEST_P(BoxFurnace, RadianceIsEmissionOverOneMinusAlbedo) {
  const float rho = GetParam();
  const float le = 0.5f;
  scenes::Scene s;
  const int m = test::add_material(s, test::diffuse(glm::vec3(rho), glm::vec3(le)));
  test::add_box(s, m, glm::vec3(-1.0f), glm::vec3(1.0f), true);
  s.derive();
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.max_bounces = 100000;  // rho^100000 of the energy is left at the cut-off
  const scenes::Camera cam = scenes::Camera::look_at({0.2f, 0.1f, 0.3f}, {1.0f, -0.3f, -0.6f}, {0, 1, 0}, 1.2f);
  Renderer r(s, cam, rs);
  Film f = r.make_film();
  r.render(f, rho > 0.99f ? 24 : 16);
  expect_uniform(f, le / (1.0 - rho), "box furnace");
}

INSTANTIATE_TEST_SUITE_P(Albedo, BoxFurnace, ::testing::Values(0.0f, 0.3f, 0.8f, 0.95f, 0.999f));

TEST(EnvironmentFurnace, WhiteLambertianBoxReflectsTheEnvironment) {
  scenes::Scene s;
  const int m = test::add_material(s, test::diffuse(glm::vec3(1.0f)));
  test::add_box(s, m, glm::vec3(-1.0f, -0.5f, -1.0f), glm::vec3(1.0f, 0.5f, 1.0f), false);
  test::add_box(s, m, glm::vec3(-0.3f, 0.5f, -0.3f), glm::vec3(0.3f, 1.2f, 0.3f), false);  // concave arrangement
  s.environment = glm::vec3(0.7f);
  s.derive();
  RenderSettings rs;
  rs.width = rs.height = 16;
  rs.max_bounces = 100000;
  Renderer r(s, scenes::Camera::look_at({0.5f, 2.0f, 3.0f}, {0.0f, 0.3f, 0.0f}, {0, 1, 0}, 0.9f), rs);
  Film f = r.make_film();
  r.render(f, 32);
  expect_uniform(f, 0.7, "environment furnace");
}

}  // namespace
}  // namespace giq::reference
