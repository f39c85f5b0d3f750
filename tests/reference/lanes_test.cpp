// The integrator that traces eight paths at a time (reference/src/lane_integrator.h) against
// the one that traces one path at a time: the same estimator, the same random numbers and the
// same floating-point operations, so every pixel's accumulator must have the same bits, on
// every kind of scene: Lambertian, glossy, textured, alpha-masked, under an environment map.

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <utility>

#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

struct Rendered {
  Film film;
  RenderStats stats;
  bool lanes = false;
};

Rendered render(const scenes::Scene& s, RenderSettings rs, bool lanes, uint32_t spp) {
  rs.lanes = lanes ? RenderSettings::Lanes::Always : RenderSettings::Lanes::Never;
  const Renderer r(s, s.views[0].camera, rs);
  Rendered out{r.make_film(), {}, r.lanes()};
  r.render(out.film, spp, nullptr, &out.stats);
  return out;
}

void expect_same_bits(const scenes::Scene& s, const RenderSettings& rs, const std::string& what, uint32_t spp = 8) {
  const Rendered one = render(s, rs, false, spp), eight = render(s, rs, true, spp);
  ASSERT_FALSE(one.lanes) << what;
  ASSERT_TRUE(eight.lanes) << what;
  EXPECT_EQ(one.stats.rays, eight.stats.rays) << what;
  EXPECT_EQ(one.stats.samples, eight.stats.samples) << what;
  size_t differing = 0;
  for (size_t i = 0; i < one.film.pixels.size(); ++i)
    differing += std::memcmp(&one.film.pixels[i], &eight.film.pixels[i], sizeof(PixelAccumulator)) != 0;
  EXPECT_EQ(differing, 0u) << what << ": pixels whose accumulators differ";
  // The scene is lit: the comparison is not between two black images.
  EXPECT_GT(eight.film.relative_standard_error(), 0.0) << what;
}

// expect_same_bits for MIS, light sampling alone and BSDF sampling alone.
void expect_same_bits_for_each_estimator(const scenes::Scene& s, RenderSettings rs, const std::string& what) {
  for (const auto& [e, name] : {std::pair{Estimator::Mis, "mis"}, std::pair{Estimator::LightOnly, "light sampling only"},
                                std::pair{Estimator::BsdfOnly, "BSDF sampling only"}}) {
    rs.estimator = e;
    expect_same_bits(s, rs, what + ", " + name);
  }
}

// The Cornell box plus every light and surface kind the lanes handle: point, spot and
// directional lights, a constant environment, a double-sided emitter, a double-sided block,
// vertex normals bent far enough that some face away from the viewer (the geometric normal
// takes over there), and a wall that sits on the room's edge.
scenes::Scene everything() {
  scenes::Scene s = test::cornell();
  scenes::Light point;
  point.type = scenes::LightType::Point;
  point.intensity = 2.0f;
  point.position = {0.5f, 0.5f, 0.3f};
  point.range = 3.0f;
  scenes::Light spot = point;
  spot.type = scenes::LightType::Spot;
  spot.position = {-0.5f, 0.8f, 0.5f};
  spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.3f));
  spot.inner_cone = 0.2f, spot.outer_cone = 0.6f;
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.intensity = 1.5f;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -0.2f, -1.0f));
  s.lights = {point, spot, sun};
  s.environment = glm::vec3(0.3f, 0.35f, 0.4f);
  const int glow = test::add_material(s, test::diffuse({0.5f, 0.5f, 0.5f}, {3.0f, 2.0f, 1.0f}, true));
  test::add_quad(s, glow, {0.3f, -0.8f, 0.6f}, {0.8f, -0.8f, 0.6f}, {0.8f, -0.3f, 0.5f}, {0.3f, -0.3f, 0.5f}, 9);
  const int two_sided = test::add_material(s, test::diffuse({0.4f, 0.6f, 0.8f}, glm::vec3(0.0f), true));
  test::add_box(s, two_sided, {0.2f, -1.0f, -0.6f}, {0.7f, -0.4f, -0.1f}, false, 10);
  scenes::Mesh& bent = s.meshes.back();
  bent.normals = {glm::normalize(glm::vec3(1, 1, 1)), glm::normalize(glm::vec3(-1, 0.2f, 0)), glm::vec3(0, 0, -1),
                  glm::normalize(glm::vec3(0.3f, -1, 0.2f))};
  s.derive();
  return s;
}

TEST(Lanes, SameBitsAsOnePathAtATimeOnTheCornellBox) {
  RenderSettings rs;
  rs.width = 40, rs.height = 24, rs.seed = 5;  // not multiples of the tile size
  expect_same_bits(test::cornell(), rs, "cornell");
}

TEST(Lanes, SameBitsWithEveryLightKindAndSurfaceKind) {
  const scenes::Scene s = everything();
  ASSERT_TRUE(s.features.point_lights && s.features.spot_lights && s.features.directional_lights && s.features.environment &&
              s.features.emissive_meshes);
  RenderSettings rs;
  rs.width = 33, rs.height = 21, rs.seed = 11;
  expect_same_bits_for_each_estimator(s, rs, "everything");
}

TEST(Lanes, SameBitsForOtherSettings) {
  const scenes::Scene s = everything();
  RenderSettings rs;
  rs.width = 24, rs.height = 24, rs.seed = 2;
  rs.max_bounces = 2;  // paths cut at a fixed depth as well as by roulette
  expect_same_bits(s, rs, "max bounces 2");
  rs.max_bounces = 0;
  expect_same_bits(s, rs, "max bounces 0");
  rs.max_bounces = 64;
  rs.sobol_block = 2;
  expect_same_bits(s, rs, "blocks of 2", 6);  // an incomplete block at the end
  rs.sobol_block = 256;
  expect_same_bits(s, rs, "blocks of 256", 3);
}

TEST(Lanes, SameBitsFarFromTheOriginAndAtExtremeScales) {
  // The ray offsets switch from their absolute to their relative form with the coordinates'
  // magnitude; both forms run here.
  RenderSettings rs;
  rs.width = 24, rs.height = 16, rs.seed = 9;
  expect_same_bits(test::cornell(1e-3f), rs, "millimetre box");
  expect_same_bits(test::cornell(1e4f), rs, "10 km box");
  expect_same_bits(test::cornell(1.0f, glm::vec3(1e5f, -1e5f, 3e4f)), rs, "box 1e5 from the origin");
  expect_same_bits(test::cornell(1.0f, glm::vec3(0.0f), 1e8f), rs, "light x 1e8");
}

TEST(Lanes, SameBitsWithGgxLobes) {
  // A metal and a KHR_materials_specular plastic under an area light and an environment: the
  // GGX lobe's sampling, evaluation and lobe choice, with MIS and with each strategy alone.
  scenes::Scene s = test::glossy_scene();
  s.views.push_back({"glossy", test::glossy_scene_camera(), -1});
  ASSERT_TRUE(s.features.specular);
  RenderSettings rs;
  rs.width = 30, rs.height = 22, rs.seed = 3;
  expect_same_bits_for_each_estimator(s, rs, "glossy");
  // And with every light kind of everything() added.
  scenes::Scene both = everything();
  both.materials[0].metallic = 1.0f, both.materials[0].roughness = 0.3f;  // the white walls turn to metal
  both.materials[1].specular = 1.0f, both.materials[1].roughness = 0.05f;   // a near-mirror red wall
  both.derive();
  ASSERT_TRUE(both.features.specular);
  expect_same_bits(both, rs, "everything, glossy");
}

TEST(Lanes, SameBitsWithTexturesNormalMapsVertexColoursAndAlphaMasks) {
  // Glossy and textured glTF rooms: base colour, metallic-roughness, normal and emissive
  // textures, vertex colours, a second UV set and alpha-masked cut-outs.
  for (const char* name : {"textured_room.gltf", "materials.gltf", "two_uv_sets.gltf"}) {
    scenes::Scene s = scenes::load(std::string(GIQ_TEST_DATA) + "/scenes/" + name);
    ASSERT_TRUE(s.features.textures) << name;
    if (s.views.empty()) {  // a view of the whole scene, from the front and above
      const glm::vec3 c = s.bounds.centre(), e = s.bounds.extent();
      const float r = glm::length(e);
      s.views.push_back({"all", scenes::Camera::look_at(c + glm::vec3(0.3f, 0.5f, 1.0f) * r, c, {0, 1, 0}, 0.8f), -1});
    }
    RenderSettings rs;
    rs.width = 28, rs.height = 20, rs.seed = 4;
    expect_same_bits(s, rs, name);
  }
}

TEST(Lanes, SameBitsUnderAnEnvironmentMap) {
  // An environment map is a texture lookup per escaped ray and per light sample.
  scenes::Scene s = test::cornell();
  std::vector<glm::vec3> map(32 * 16);
  for (size_t i = 0; i < map.size(); ++i) map[i] = glm::vec3(0.1f + 0.02f * float(i % 32), 0.3f, 0.05f * float(i / 32));
  map[3 * 32 + 11] = glm::vec3(500.0f);  // a sun-like texel
  s.set_environment_map(32, 16, map, "test map");
  s.meshes.erase(s.meshes.begin() + 2);  // the back wall opens to the sky
  s.derive();
  ASSERT_TRUE(s.features.environment_map);
  RenderSettings rs;
  rs.width = 26, rs.height = 18, rs.seed = 8;
  expect_same_bits(s, rs, "environment map");
  rs.estimator = Estimator::BsdfOnly;
  expect_same_bits(s, rs, "environment map, BSDF sampling only");
}

TEST(Lanes, ByDefaultWhereEveryStepRunsOnTheLanesAndOnlyWithSobol) {
  RenderSettings rs;
  rs.width = 8, rs.height = 8;
  const scenes::Scene glossy = test::glossy_scene(), box = test::cornell();
  EXPECT_FALSE(Renderer(glossy, test::glossy_scene_camera(), rs).lanes()) << "GGX: measured no faster in lanes";
  EXPECT_TRUE(Renderer(box, box.views[0].camera, rs).lanes());
  rs.lanes = RenderSettings::Lanes::Always;
  EXPECT_TRUE(Renderer(glossy, test::glossy_scene_camera(), rs).lanes());
  rs.sampler = Sampler::Independent;
  EXPECT_FALSE(Renderer(box, box.views[0].camera, rs).lanes()) << "the independent sampler stays with one path at a time";
}

}  // namespace
}  // namespace giq::reference
