// Declared area light shapes (extras.giq.area_light) fitted to the emitter's triangles
// (scenes/src/area_shape.cpp): the fitted centre, radius and half vectors are the generating
// shape's, to float rounding where the vertices lie on the shape (sphere, disc circle,
// rectangle corners, capsule cylinder), and a shape that cannot be fitted falls back to the
// triangles.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"
#include "test_paths.h"

namespace giq::scenes {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Scene with_emitter(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles, AreaShape shape) {
  Scene s;
  Material m;
  m.emissive = glm::vec3(1.0f);
  m.double_sided = true;
  s.materials.push_back(m);
  Mesh mesh;
  mesh.positions = positions;
  mesh.triangles = triangles;
  mesh.area_shape = shape;
  s.meshes.push_back(mesh);
  s.derive();
  return s;
}

// A capsule of radius r around the segment c +- (half along `axis`), or a sphere (half 0).
Scene capsule(glm::vec3 c, glm::vec3 axis, float half, float r, AreaShape shape) {
  const glm::vec3 a = glm::normalize(axis), b = glm::normalize(glm::cross(a, glm::vec3(0.3f, 1.0f, 0.2f))), e = glm::cross(a, b);
  std::vector<glm::vec3> p;
  std::vector<glm::uvec3> t;
  const int rings = 16, segments = 24;
  for (int i = 0; i <= rings; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float th = kPi * float(i) / float(rings), ph = 2.0f * kPi * float(j) / float(segments);
      const glm::vec3 n = std::cos(th) * a + std::sin(th) * (std::cos(ph) * b + std::sin(ph) * e);
      p.push_back(c + r * n + a * (2 * i <= rings ? half : -half));
    }
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const uint32_t v = uint32_t(i * (segments + 1) + j), w = v + uint32_t(segments + 1);
      if (i > 0) t.push_back({v, w, v + 1});
      if (i + 1 < rings) t.push_back({v + 1, w, w + 1});
    }
  return with_emitter(p, t, shape);
}

void expect_near(glm::vec3 got, glm::vec3 want, float tol, const char* what) {
  EXPECT_NEAR(glm::length(got - want), 0.0f, tol) << what << ": (" << got.x << ", " << got.y << ", " << got.z << ")";
}

TEST(AreaShape, SphereAndTubeFromTheirTessellation) {
  // The sphere's vertices lie on it: the mean distance from the area-weighted centroid is the
  // radius (the centroid is the centre by symmetry).
  const Scene sphere = capsule({1.0f, 2.0f, 3.0f}, {0, 1, 0}, 0.0f, 0.5f, AreaShape::Sphere);
  const AreaLight& s = sphere.area_lights.at(0);
  EXPECT_EQ(s.shape, AreaShape::Sphere);
  expect_near(s.shape_centre, {1.0f, 2.0f, 3.0f}, 1e-5f, "sphere centre");
  EXPECT_NEAR(s.shape_radius, 0.5f, 1e-5f);
  // A capsule along a tilted axis: its segment is the principal axis, its radius the
  // cylinder's, and the segment ends one radius inside the caps' tips.
  const glm::vec3 axis = glm::normalize(glm::vec3(1.0f, 0.3f, -0.5f));
  const Scene tube = capsule({-2.0f, 0.5f, 1.0f}, axis, 0.8f, 0.1f, AreaShape::Tube);
  const AreaLight& t = tube.area_lights.at(0);
  EXPECT_EQ(t.shape, AreaShape::Tube);
  expect_near(t.shape_centre, {-2.0f, 0.5f, 1.0f}, 1e-5f, "tube centre");
  EXPECT_NEAR(t.shape_radius, 0.1f, 1e-5f);
  EXPECT_NEAR(std::abs(glm::dot(t.shape_u, axis)), 0.8f, 1e-5f);
  EXPECT_NEAR(glm::length(t.shape_u), 0.8f, 1e-5f);
}

TEST(AreaShape, DiscAndRectangleInTheirPlane) {
  std::vector<glm::vec3> p{{0.5f, 1.0f, 0.0f}};
  std::vector<glm::uvec3> t;
  const int n = 32;
  for (int j = 0; j < n; ++j) {
    const float a = 2.0f * kPi * float(j) / float(n);
    p.push_back(glm::vec3(0.5f, 1.0f, 0.0f) + 0.3f * glm::vec3(std::cos(a), 0.0f, std::sin(a)));
    t.push_back({0u, uint32_t(1 + j), uint32_t(1 + (j + 1) % n)});
  }
  const AreaLight disc = with_emitter(p, t, AreaShape::Disc).area_lights.at(0);
  EXPECT_EQ(disc.shape, AreaShape::Disc);
  EXPECT_NEAR(disc.shape_radius, 0.3f, 1e-6f);
  EXPECT_NEAR(std::abs(disc.shape_v.y), 1.0f, 1e-6f);  // the disc's normal
  // A rectangle 1.2 x 0.4 turned 30 degrees in the plane y = 2, as two triangles (whose
  // diagonal is the longest edge: the fit must not take it for a side).
  const glm::vec3 u(std::cos(kPi / 6), 0.0f, std::sin(kPi / 6)), v(-u.z, 0.0f, u.x), c(0.0f, 2.0f, -1.0f);
  const std::vector<glm::vec3> q{c - 0.6f * u - 0.2f * v, c + 0.6f * u - 0.2f * v, c + 0.6f * u + 0.2f * v, c - 0.6f * u + 0.2f * v};
  const AreaLight rect = with_emitter(q, {{0, 1, 2}, {0, 2, 3}}, AreaShape::Rectangle).area_lights.at(0);
  EXPECT_EQ(rect.shape, AreaShape::Rectangle);
  expect_near(rect.shape_centre, c, 1e-6f, "rectangle centre");
  const float lu = glm::length(rect.shape_u), lv = glm::length(rect.shape_v);
  EXPECT_NEAR(std::max(lu, lv), 0.6f, 1e-6f);
  EXPECT_NEAR(std::min(lu, lv), 0.2f, 1e-6f);
  EXPECT_NEAR(std::abs(glm::dot(glm::normalize(lu > lv ? rect.shape_u : rect.shape_v), u)), 1.0f, 1e-6f);
}

TEST(AreaShape, ACurvedDiscFallsBackToItsTriangles) {
  // A sphere declared a disc: its area vectors cancel, so there is no plane to put a disc in,
  // and the triangles stand for themselves.
  const Scene s = capsule({0.0f, 0.0f, 0.0f}, {0, 1, 0}, 0.0f, 0.5f, AreaShape::Disc);
  EXPECT_EQ(s.area_lights.at(0).shape, AreaShape::Mesh);
}

TEST(AreaShape, DeclaredInTheMeshExtras) {
  const Scene s = load(test::data("area_shapes.gltf"));
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].area_shape, AreaShape::Rectangle);
  EXPECT_EQ(s.meshes[1].area_shape, AreaShape::Mesh);
  ASSERT_EQ(s.area_lights.size(), 1u);
  EXPECT_EQ(s.area_lights[0].shape, AreaShape::Rectangle);
}

}  // namespace
}  // namespace giq::scenes
