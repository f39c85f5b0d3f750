// animated.gltf: one clip "move" with a LINEAR translation (node "mover", keys at 0, 1, 2 s:
// (0,0,0), (1,0,0), (1,2,0)), a LINEAR rotation (node "turner", 0 -> 90 degrees about +Y over
// 2 s), a STEP scale (node "grower", 1 -> 2 at 1 s) and a CUBICSPLINE translation (node
// "glider", keys at 0 and 2 s: value 0 with out-tangent (3,0,0), then value (1,0,0) with
// zero tangents).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

using test::world;

constexpr double kTol = 1e-6;

class Animation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new Scene(load(test::data("animated.gltf"))); }
  static void TearDownTestSuite() { delete scene_; }
  static const Scene& scene() { return *scene_; }
  static glm::dvec3 bulb(const Scene& s) { return world(s, s.lights[0].position); }
  static glm::vec3 sun(const Scene& s) { return s.lights[1].direction; }
  static glm::dvec3 glider(const Scene& s) { return world(s, s.view("glider").camera.position); }
  static glm::dvec3 grower_vertex(const Scene& s) { return world(s, s.meshes[1].positions[1]); }  // (1,0,0) scaled

 private:
  static inline Scene* scene_ = nullptr;
};

TEST_F(Animation, SequenceFromExtras) {
  const Scene& s = scene();
  EXPECT_EQ(s.sequence.animation, 0);
  EXPECT_EQ(s.sequence.frames, 61);
  EXPECT_EQ(s.sequence.fps, 30.0);
  EXPECT_EQ(s.duration(), 2.0);
  EXPECT_TRUE(s.features.animation);
  EXPECT_EQ(s.origin, glm::dvec3(0.5, 0.5, 0.0));  // both triangles at rest, t = 0
}

TEST_F(Animation, LinearTranslationAtKeysBetweenAndOutside) {
  const struct { double t; glm::dvec3 p; } cases[] = {
      {0.0, {0, 0, 0}}, {0.5, {0.5, 0, 0}}, {1.0, {1, 0, 0}}, {1.5, {1, 1, 0}}, {2.0, {1, 2, 0}},
      {-1.0, {0, 0, 0}}, {5.0, {1, 2, 0}}};  // outside the clip: clamped to the end keys
  for (const auto& c : cases) {
    const Scene s = scene().at(c.t);
    EXPECT_EQ(s.time, c.t);
    const glm::dvec3 p = bulb(s);
    EXPECT_NEAR(p.x, c.p.x, kTol) << "t = " << c.t;
    EXPECT_NEAR(p.y, c.p.y, kTol) << "t = " << c.t;
    // The mesh on the same node moves with the light; the origin stays fixed.
    const glm::dvec3 v = world(s, s.meshes[0].positions[0]);
    EXPECT_NEAR(v.x, c.p.x, kTol);
    EXPECT_EQ(s.origin, scene().origin);
  }
}

TEST_F(Animation, LinearRotationIsSlerp) {
  // Spherical interpolation turns at constant angular speed: 45 degrees/s about +Y, so the
  // node's -Z axis is (-sin a, 0, -cos a). (A normalised lerp would give 21.6 degrees at
  // t = 0.5 instead of 22.5.)
  for (double t : {0.0, 0.5, 1.0, 1.7, 2.0}) {
    const double a = std::numbers::pi / 4 * t;
    const glm::vec3 d = sun(scene().at(t));
    EXPECT_NEAR(d.x, -std::sin(a), kTol) << "t = " << t;
    EXPECT_NEAR(d.y, 0.0, kTol);
    EXPECT_NEAR(d.z, -std::cos(a), kTol) << "t = " << t;
  }
}

TEST_F(Animation, StepHoldsUntilTheNextKey) {
  EXPECT_NEAR(grower_vertex(scene().at(0.0)).x, 1.0, kTol);
  EXPECT_NEAR(grower_vertex(scene().at(0.999)).x, 1.0, kTol);
  EXPECT_NEAR(grower_vertex(scene().at(1.0)).x, 2.0, kTol);
  EXPECT_NEAR(grower_vertex(scene().at(1.5)).x, 2.0, kTol);
}

TEST_F(Animation, CubicSplineHermite) {
  // glTF 2.0 Appendix C with t_d = 2, v0 = 0, b0 = 3, v1 = 1, a1 = 0:
  // p(s) = (-2s^3 + 3s^2) * 1 + 2 (s^3 - 2s^2 + s) * 3.
  auto p = [](double s) { return (-2 * s * s * s + 3 * s * s) + 6 * (s * s * s - 2 * s * s + s); };
  EXPECT_NEAR(p(0.5), 1.25, 1e-12);  // hand check of the formula itself
  for (double t : {0.0, 0.5, 1.0, 1.5, 2.0}) EXPECT_NEAR(glider(scene().at(t)).x, p(t / 2), kTol) << "t = " << t;
}

TEST_F(Animation, FramesAreTimesOverFps) {
  const Scene f = scene().at_frame(15);  // 15 / 30 = 0.5 s
  EXPECT_EQ(f.time, 0.5);
  EXPECT_NEAR(bulb(f).x, 0.5, kTol);
  // Materials and textures are shared, not re-read.
  EXPECT_EQ(f.materials.size(), scene().materials.size());
  EXPECT_EQ(f.meshes.size(), scene().meshes.size());
}

}  // namespace
}  // namespace giq::scenes

namespace giq::scenes {
namespace {

TEST(SceneAdditions, LightsAndViewsAddedAfterLoadingStayThroughTime) {
  Scene s = load(test::data("animated.gltf"));
  const size_t lights = s.lights.size(), views = s.views.size();
  const std::string file_hash = s.content_hash;
  Light sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.direction = {0.0f, -1.0f, 0.0f};
  s.add_light(sun, "sun dir=0,-1,0 illuminance=1");
  View v;
  v.name = "camera";
  v.camera = Camera::look_at({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 0.8f);
  s.add_view(v);
  EXPECT_NE(s.content_hash, file_hash);  // the scene as rendered is not the file alone
  EXPECT_THROW(s.add_view(v), InputError);  // view names stay unique
  const Scene later = s.at(1.5);
  ASSERT_EQ(later.lights.size(), lights + 1);
  EXPECT_EQ(later.lights.back().name, "sun");
  EXPECT_EQ(later.lights.back().direction, glm::vec3(0.0f, -1.0f, 0.0f));  // posed as given, not by a node
  ASSERT_EQ(later.views.size(), views + 1);
  EXPECT_EQ(later.view("camera").camera.position, v.camera.position);
  EXPECT_EQ(later.content_hash, s.content_hash);
  EXPECT_TRUE(later.features.directional_lights);
}

}  // namespace
}  // namespace giq::scenes
