// A Scene built in code: derive() and the accessors, independent of any file.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "giq/base/error.h"
#include "giq/scenes/scene.h"

namespace giq::scenes {
namespace {

Scene emissive_quad(bool double_sided) {
  Scene s;
  Material lamp;
  lamp.emissive = {1.0f, 2.0f, 3.0f};
  lamp.metallic = 0.0f;
  lamp.specular = 0.0f;  // pure Lambert
  lamp.double_sided = double_sided;
  s.materials.push_back(lamp);
  Mesh m;
  m.name = "lamp";
  m.material = 0;
  // 2 x 1 rectangle in the z = 0 plane: two triangles of area 1.
  m.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  m.normals.assign(4, {0, 0, 1});
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.meshes.push_back(m);
  s.derive();
  return s;
}

TEST(Scene, EmissiveTrianglePowerIsPiAreaLuminance) {
  const double lum = 0.2126 * 1.0 + 0.7152 * 2.0 + 0.0722 * 3.0;  // Rec. 709
  for (bool two : {false, true}) {
    const Scene s = emissive_quad(two);
    ASSERT_EQ(s.emissive_triangles.size(), 2u);
    for (const auto& e : s.emissive_triangles) {
      EXPECT_EQ(e.mesh, 0u);
      EXPECT_FLOAT_EQ(e.area, 1.0f);
      EXPECT_EQ(e.radiance, glm::vec3(1, 2, 3));
      EXPECT_NEAR(e.power, std::numbers::pi * lum * (two ? 2.0 : 1.0), 1e-5);
    }
    EXPECT_NEAR(s.stats.total_light_power, 2 * std::numbers::pi * lum * (two ? 2.0 : 1.0), 1e-4);
    EXPECT_EQ(s.features.double_sided, two);
    EXPECT_EQ(s.features.one_sided, !two);
  }
}

// An emitter's mean radiance carries its coverage: what a ray that finds it meets (BLEND:
// alpha; MASK: 1 or 0; COLOR_0's alpha interpolated, so the mean over a triangle of a linear
// alpha is exact at the sub-triangle centroids). The area light's intensity follows.
TEST(Scene, EmitterRadianceIsWeightedByCoverage) {
  Scene s = emissive_quad(true);
  s.materials[0].alpha_mode = AlphaMode::Blend;
  s.materials[0].base_color.a = 0.4f;
  s.derive();
  ASSERT_EQ(s.emissive_triangles.size(), 2u);
  for (const auto& e : s.emissive_triangles) {
    EXPECT_NEAR(e.radiance.r, 0.4f, 1e-6f);
    EXPECT_NEAR(e.radiance.b, 1.2f, 1e-6f);
  }
  EXPECT_NEAR(s.area_lights[0].intensity.g, 2.0f * 0.4f * 2.0f, 1e-5f);
  // COLOR_0 alpha 0 at x = 0 to 1 at x = 2: each triangle's mean alpha is its centroid's.
  s.meshes[0].colors = {{1, 1, 1, 0}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 0}};
  s.derive();
  const float centroid_alpha[2] = {(0.0f + 1.0f + 1.0f) / 3.0f, (0.0f + 1.0f + 0.0f) / 3.0f};
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(s.emissive_triangles[size_t(k)].radiance.r, 0.4f * centroid_alpha[k], 1e-5f) << k;
  // MASK below the cutoff: no emitter at all, and no light.
  s.meshes[0].colors.clear();
  s.materials[0].alpha_mode = AlphaMode::Mask;
  s.materials[0].alpha_cutoff = 0.5f;
  s.derive();
  EXPECT_TRUE(s.emissive_triangles.empty());
  EXPECT_EQ(s.stats.total_light_power, 0.0);
}

TEST(Scene, EachEmissiveMeshIsOneAreaLight) {
  for (bool two : {false, true}) {
    const Scene s = emissive_quad(two);
    ASSERT_EQ(s.area_lights.size(), 1u);
    const AreaLight& a = s.area_lights[0];
    EXPECT_EQ(a.mesh, 0u);
    EXPECT_EQ(a.triangles, (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(a.two_sided, two);
    EXPECT_FLOAT_EQ(a.area, 2.0f);
    // The rectangle's centre; the triangles' areas weight their centroids equally.
    EXPECT_NEAR(a.centroid.x, 1.0f, 1e-6f);
    EXPECT_NEAR(a.centroid.y, 0.5f, 1e-6f);
    EXPECT_EQ(a.centroid.z, 0.0f);
    EXPECT_TRUE(a.flat);
    EXPECT_EQ(a.extent, 0.0f);
    EXPECT_EQ(a.normal, glm::vec3(0, 0, 1));            // counter-clockwise seen from +z
    EXPECT_EQ(a.intensity, glm::vec3(2.0f, 4.0f, 6.0f));  // radiance x area
    // A one-sided emitter's point sits 1e-4 of the scene's diagonal (sqrt 5) in front of it.
    const float offset = two ? 0.0f : 1e-4f * std::sqrt(5.0f);
    EXPECT_NEAR(a.representative.z, offset, 1e-9f);
    EXPECT_EQ(glm::vec2(a.representative), glm::vec2(a.centroid));
  }
}

TEST(Scene, ClosedEmitterHasNoMeanNormalAndStaysAtItsCentroid) {
  // The six faces of a unit cube, outward: the area vectors cancel.
  Scene s;
  Material lamp;
  lamp.emissive = {1.0f, 1.0f, 1.0f};
  s.materials.push_back(lamp);
  Mesh m;
  m.material = 0;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  m.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                 {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  s.meshes.push_back(m);
  s.derive();
  ASSERT_EQ(s.area_lights.size(), 1u);
  const AreaLight& a = s.area_lights[0];
  EXPECT_FALSE(a.flat);
  EXPECT_EQ(a.normal, glm::vec3(0, -1, 0));
  EXPECT_FLOAT_EQ(a.area, 6.0f);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.centroid[c], 0.5f, 1e-6f);
  EXPECT_EQ(a.representative, a.centroid);
  EXPECT_NEAR(a.extent, std::sqrt(0.75f), 1e-6f);  // from the centre to a corner
}

TEST(Scene, LightPowerIsPhi) {
  Light point;
  point.type = LightType::Point;
  point.color = {1, 1, 1};
  point.intensity = 2.0f;
  EXPECT_DOUBLE_EQ(point.power(10.0), 4.0 * std::numbers::pi * 2.0);
  Light spot = point;
  spot.type = LightType::Spot;
  spot.inner_cone = 0.0f;
  spot.outer_cone = 1.0f;
  EXPECT_NEAR(spot.power(10.0), 2.0 * std::numbers::pi * (1.0 - std::cos(0.5)) * 2.0, 1e-12);
  Light sun = point;
  sun.type = LightType::Directional;
  EXPECT_DOUBLE_EQ(sun.power(3.0), std::numbers::pi * 9.0 * 2.0);  // irradiance over a disc of radius 3
  EXPECT_DOUBLE_EQ(luminance({1, 0, 0}), 0.2126);
}

TEST(Scene, BoundsCentreDiagonalAndEmptyBounds) {
  Bounds b;
  EXPECT_EQ(b.centre(), glm::vec3(0.0f));
  EXPECT_EQ(b.diagonal(), 1e-6f);
  EXPECT_EQ(b.largest_side(), 1e-6f);
  b.extend({-1, 0, 2});
  b.extend({3, 2, 2});
  EXPECT_EQ(b.centre(), glm::vec3(1, 1, 2));
  EXPECT_FLOAT_EQ(b.diagonal(), std::sqrt(20.0f));
  EXPECT_EQ(b.largest_side(), 4.0f);
}

TEST(Scene, DeriveFeaturesBoundsAndCounts) {
  Scene s = emissive_quad(false);
  EXPECT_TRUE(s.features.emissive_meshes);
  EXPECT_FALSE(s.features.specular);  // metallic 0 and specular 0: Lambert only
  EXPECT_FALSE(s.features.textures);
  EXPECT_FALSE(s.features.animation);
  EXPECT_EQ(s.stats.triangles, 2u);
  EXPECT_EQ(s.stats.vertices, 4u);
  EXPECT_EQ(s.bounds.lo, glm::vec3(0, 0, 0));
  EXPECT_EQ(s.bounds.hi, glm::vec3(2, 1, 0));
  EXPECT_EQ(s.features.names(), (std::vector<std::string>{"emissive_meshes", "one_sided"}));

  s.materials[0].metallic = 0.5f;
  Light sun;
  sun.type = LightType::Directional;
  s.lights.push_back(sun);
  s.environment = {0.1f, 0.1f, 0.1f};
  s.derive();
  EXPECT_TRUE(s.features.specular);
  EXPECT_TRUE(s.features.directional_lights);
  EXPECT_FALSE(s.features.point_lights);
  EXPECT_TRUE(s.features.environment);
  EXPECT_EQ(s.features.names(),
            (std::vector<std::string>{"directional_lights", "emissive_meshes", "environment", "specular", "one_sided"}));
}

TEST(Scene, ViewByNameOrIndex) {
  Scene s;
  s.path = "room.gltf";
  s.views.push_back({"front", Camera{}, -1});
  s.views.push_back({"7", Camera{}, -1});
  s.views.push_back({"back", Camera{}, -1});
  EXPECT_EQ(s.view("back").name, "back");
  EXPECT_EQ(s.view("0").name, "front");
  EXPECT_EQ(s.view("7").name, "7");  // a name wins over an index
  try {
    s.view("side");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "room.gltf");
    EXPECT_EQ(e.field(), "view");
    EXPECT_NE(std::string(e.what()).find("front"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("back"), std::string::npos);
  }
  EXPECT_THROW(s.view("3"), InputError);
}

TEST(Scene, CodeBuiltSceneIsStatic) {
  const Scene s = emissive_quad(false);
  EXPECT_EQ(s.duration(), 0.0);
  const Scene t = s.at(1.5);
  EXPECT_EQ(t.time, 1.5);
  EXPECT_EQ(t.meshes[0].positions, s.meshes[0].positions);
}

}  // namespace
}  // namespace giq::scenes
