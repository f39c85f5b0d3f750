// Extremes: scaling the scene (millimetres to kilometres), moving it far from the origin and
// scaling its lights must scale the image accordingly (geometry: unchanged; light: by the
// same factor), with no non-finite samples, no self-intersection acne and no light leaks.

#include <gtest/gtest.h>

#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

constexpr int kSize = 24;
constexpr std::pair<float, float> kPoses[] = {{1e-3f, 0.0f}, {1.0f, 0.0f}, {1e4f, 0.0f}, {1e3f, 1e5f}, {1e4f, 1e5f}};

Film render(const scenes::Scene& s, uint32_t spp = 32) {
  RenderSettings rs;
  rs.width = rs.height = kSize;
  rs.seed = 9;
  Renderer r(s, s.views[0].camera, rs);
  Film f = r.make_film();
  r.render(f, spp);
  return f;
}

// Every 4x4 block of `f` equals `factor` times the same block of `base` within noise (the
// renders share their random numbers, so most paths are identical and the test is strict).
void expect_scaled(const Film& base, const Film& f, double factor, const char* what) {
  EXPECT_EQ(f.nonfinite_samples(), 0u) << what;
  for (int y = 0; y < kSize; y += 4)
    for (int x = 0; x < kSize; x += 4) {
      const test::BlockStat a = test::block_luminance(base, x, y, 4, 4), b = test::block_luminance(f, x, y, 4, 4);
      const double tol = 4.0 * std::sqrt(a.variance * factor * factor + b.variance) + 1e-4 * a.mean * factor;
      EXPECT_NEAR(b.mean, a.mean * factor, tol) << what << ", block " << x << "," << y;
    }
}

TEST(Extremes, ScaleTranslationAndIntensity) {
  const Film base = render(test::cornell());
  EXPECT_EQ(base.nonfinite_samples(), 0u);
  expect_scaled(base, render(test::cornell(1e-3f)), 1.0, "scale 1e-3");
  expect_scaled(base, render(test::cornell(1e4f)), 1.0, "scale 1e4");
  // 1e5 from the origin in float coordinates (the scene not re-centred by a loader): a 2-unit
  // room there has coordinates with 1/128 of resolution, so the room is made 1000 times larger.
  expect_scaled(render(test::cornell(1e3f)), render(test::cornell(1e3f, glm::vec3(1e5f, -1e5f, 1e5f))), 1.0, "translate 1e5");
  expect_scaled(base, render(test::cornell(1.0f, glm::vec3(0.0f), 1e-6f)), 1e-6, "light x 1e-6");
  expect_scaled(base, render(test::cornell(1.0f, glm::vec3(0.0f), 1e8f)), 1e8, "light x 1e8");
}

TEST(Extremes, NoAcneOnALitWall) {
  // A wall facing a directional light straight on, seen at grazing and normal angles at
  // several scales and distances: direct lighting is exactly (rho / pi) E at every pixel, so
  // any self-shadowed (acne) pixel shows as an exact mismatch.
  // 1e5 from the origin a float resolves 1/128: rooms there are made large enough to exist.
  for (auto [scale, offset] : kPoses) {
      scenes::Scene s;
      const int m = test::add_material(s, test::diffuse(glm::vec3(0.5f)));
      const glm::vec3 o(offset, offset, -offset);
      test::add_quad(s, m, o + scale * glm::vec3(-1, -1, 0), o + scale * glm::vec3(1, -1, 0), o + scale * glm::vec3(1, 1, 0),
                     o + scale * glm::vec3(-1, 1, 0));
      scenes::Light l;
      l.type = scenes::LightType::Directional;
      l.direction = glm::normalize(glm::vec3(0.3f, 0.2f, -1.0f));
      l.intensity = 3.0f;
      s.lights.push_back(l);
      scenes::View v;
      v.camera = scenes::Camera::look_at(o + scale * glm::vec3(0.2f, 0.1f, 1.5f), o, {0, 1, 0}, 0.8f);
      s.views.push_back(v);
      s.derive();
      const Film f = render(s, 4);
      const double expected = 0.5 / 3.14159265358979 * 3.0 * double(-l.direction.z);
      int acne = 0;
      for (const PixelAccumulator& p : f.pixels) acne += std::abs(p.mean[1] - expected) > 1e-5 * expected;
      EXPECT_EQ(acne, 0) << "scale " << scale << " offset " << offset;
    }
}

TEST(Extremes, ClosedRoomDoesNotLeakLight) {
  // A closed room (thin, one-sided walls facing in) next to a very bright light outside: the
  // inside must be exactly black at every scale and distance from the origin.
  // 1e5 from the origin a float resolves 1/128: rooms there are made large enough to exist.
  for (auto [scale, offset] : kPoses) {
      scenes::Scene s;
      const int m = test::add_material(s, test::diffuse(glm::vec3(0.8f)));
      const glm::vec3 o(offset, -offset, offset);
      test::add_box(s, m, o - scale * glm::vec3(1.0f), o + scale * glm::vec3(1.0f), true);
      scenes::Light l;
      l.type = scenes::LightType::Point;
      l.position = o + scale * glm::vec3(1.0001f, 0.5f, 0.2f);  // a hair outside a wall
      l.intensity = 1e8f * scale * scale;
      s.lights.push_back(l);
      const int lamp = test::add_material(s, test::diffuse(glm::vec3(0.0f), glm::vec3(1e6f), true));
      test::add_quad(s, lamp, o + scale * glm::vec3(-1, 1.0001f, -1), o + scale * glm::vec3(1, 1.0001f, -1),
                     o + scale * glm::vec3(1, 1.0001f, 1), o + scale * glm::vec3(-1, 1.0001f, 1));  // on the ceiling, outside
      s.environment = glm::vec3(1e3f);
      scenes::View v;
      v.camera = scenes::Camera::look_at(o + scale * glm::vec3(-0.5f, -0.3f, 0.6f), o + scale * glm::vec3(1.0f, 0.7f, -0.2f), {0, 1, 0}, 1.4f);
      s.views.push_back(v);
      s.derive();
      const Film f = render(s, 8);
      double sum = 0.0;
      for (const PixelAccumulator& p : f.pixels) sum += p.mean[0] + p.mean[1] + p.mean[2];
      EXPECT_EQ(sum, 0.0) << "scale " << scale << " offset " << offset;
      EXPECT_EQ(f.nonfinite_samples(), 0u);
    }
}

}  // namespace
}  // namespace giq::reference
