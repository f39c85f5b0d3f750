// Extremes: values beyond float16 range, scenes far from the world origin, degenerate lights,
// black materials and lights buried inside geometry must give finite, correct output.
#include <gtest/gtest.h>

#include <cmath>

#include "giq/realtime/renderer.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

class ExtremesTest : public test::VulkanTest {
 protected:
  // `direct` gets small shadow maps (the scenes are tiny), `pt` its defaults.
  image::Image render(const scenes::Scene& s, const std::string& technique, uint32_t size) {
    RenderOptions o;
    o.technique = technique;
    o.width = o.height = size;
    if (technique == "direct") o.parameters = {"shadow_map_size=256"};
    return render_last(s, o);
  }
  static void expect_finite(const image::Image& img) {
    for (const auto& name : img.channel_names())
      for (size_t i = 0; i < img.pixel_count(); ++i) ASSERT_TRUE(std::isfinite(img.channel(name)[i])) << name << " " << i;
  }
};

TEST_F(ExtremesTest, ABrightLightStaysFiniteAndScalesLinearly) {
  // 1e12 W/sr: radiances around 1e11, far beyond float16's 65504. Every target is float32,
  // so the image is the dim one scaled by 1e12.
  scenes::Scene dim = test::lambert_plane(0.5f);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.0f, 1.0f, 0.0f};
  l.intensity = 1.0f;
  dim.lights.push_back(l);
  dim.derive();
  scenes::Scene bright = dim;
  bright.lights[0].intensity = 1e12f;
  bright.derive();
  for (const char* t : {"direct", "pt"}) {
    const image::Image a = render(dim, t, 16), b = render(bright, t, 16);
    expect_finite(b);
    for (size_t i = 0; i < a.pixel_count(); ++i)
      EXPECT_NEAR(b.channel("R")[i], 1e12 * a.channel("R")[i], 1e-5 * 1e12 * a.channel("R")[i]) << t;
  }
}

TEST_F(ExtremesTest, FarFromTheWorldOriginRendersLikeAtTheOrigin) {
  // Positions live in a local frame around Scene::origin, so a scene 1e5 units away renders
  // exactly as the same scene at the origin: no precision is lost, nothing jitters.
  scenes::Scene near = test::cornell_box();
  scenes::Scene far = near;
  far.origin = glm::dvec3(1e5, -2e5, 1e5);
  far.derive();
  for (const char* t : {"direct", "pt"}) {
    const image::Image a = render(near, t, 16), b = render(far, t, 16);
    for (size_t i = 0; i < a.pixel_count(); ++i) ASSERT_EQ(a.channel("G")[i], b.channel("G")[i]) << t;
  }
}

TEST_F(ExtremesTest, CameraMotionOfAMillimetreMovesTheImageSmoothly) {
  // A camera sliding in 1 mm steps over a lit plane that fills the view (no edges): the image
  // must change by nearly the same amount at every step, not stand still and then jump as a
  // quantised projection would.
  scenes::Scene s = test::lambert_plane(0.5f);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.3f, 1.0f, 0.2f};
  l.intensity = 5.0f;
  s.lights.push_back(l);
  s.derive();
  std::vector<double> change;
  image::Image prev;
  for (int k = 0; k < 4; ++k) {
    s.views[0].camera.position.x = 0.001f * float(k);
    image::Image img = render(s, "direct", 32);
    if (k > 0) {
      double sum = 0.0;
      for (size_t i = 0; i < img.pixel_count(); ++i) sum += std::abs(img.channel("G")[i] - prev.channel("G")[i]);
      change.push_back(sum);
    }
    prev = std::move(img);
  }
  for (double c : change) {
    EXPECT_GT(c, 0.5 * change[0]);
    EXPECT_LT(c, 2.0 * change[0]);
  }
}

TEST_F(ExtremesTest, ZeroAreaLightsBlackMaterialsAndBuriedLightsAreFinite) {
  scenes::Scene s = test::cornell_box();
  // A zero-area emissive triangle (three collinear points).
  const int emitter = test::add_material(s, glm::vec3(0.5f), glm::vec3(10.0f));
  scenes::Mesh m;
  m.name = "degenerate_light";
  m.material = emitter;
  m.positions = {{0, 0, 0}, {0.1f, 0, 0}, {0.2f, 0, 0}};
  m.normals = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 2}};
  s.meshes.push_back(m);
  // A black material on the floor.
  s.materials[s.meshes[0].material].base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  // A point light inside the tall block, and one exactly on the back wall.
  scenes::Light inside;
  inside.type = scenes::LightType::Point;
  inside.position = {-0.35f, -0.4f, -0.25f};
  inside.intensity = 100.0f;
  scenes::Light on_wall = inside;
  on_wall.position = {0.0f, 0.0f, -1.0f};
  s.lights = {inside, on_wall};
  s.derive();
  for (const char* t : {"direct", "pt"}) expect_finite(render(s, t, 24));
}

TEST_F(ExtremesTest, ALightInsideAClosedBoxLeavesTheOutsideDark) {
  // A closed box (outward faces) with a point light inside, on a plane: nothing outside the
  // box receives light.
  scenes::Scene s = test::lambert_plane(0.8f);
  const int m = test::add_material(s, glm::vec3(0.8f));
  const glm::vec3 lo(-0.5f, 0.01f, -0.5f), hi(0.5f, 1.0f, 0.5f);
  const glm::vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                          {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  test::add_quad(s, p[4], p[5], p[6], p[7], m);
  test::add_quad(s, p[1], p[0], p[3], p[2], m);
  test::add_quad(s, p[5], p[1], p[2], p[6], m);
  test::add_quad(s, p[0], p[4], p[7], p[3], m);
  test::add_quad(s, p[7], p[6], p[2], p[3], m);
  test::add_quad(s, p[0], p[1], p[5], p[4], m);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.0f, 0.5f, 0.0f};
  l.intensity = 50.0f;
  s.lights.push_back(l);
  s.derive();
  for (const char* t : {"direct", "pt"}) {
    const image::Image img = render(s, t, 24);
    expect_finite(img);
    for (size_t i = 0; i < img.pixel_count(); ++i) EXPECT_EQ(img.channel("G")[i], 0.0f) << t << " pixel " << i;
  }
}

}  // namespace
}  // namespace giq::realtime
