// Every built-in scene loads through the scene library with the counts, features, lights and
// views it was built with; the numbers are worked out by hand from the scene definitions
// (docs/builtin-scenes.md), not read back from the loader.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>

#include "giq/scenes/scene.h"

namespace fs = std::filesystem;
using giq::scenes::FeatureSet;
using giq::scenes::LightType;
using giq::scenes::Scene;

namespace {

Scene load(const std::string& name) {
  return giq::scenes::load(fs::path(GIQ_SCENES_DIR) / (name + ".gltf"));
}

glm::dvec3 world(const Scene& s, glm::vec3 local) {
  return glm::dvec3(local) + s.origin;
}

// Positions are floats relative to Scene::origin, a few metres at most: ~1e-6 m precision.
constexpr double kPositionTolerance = 1e-5;

struct Expected {
  const char* name;
  size_t triangles;
  size_t punctual_lights;
  size_t views;
  const char* default_view;
  size_t leak_regions;
  int frames;
  FeatureSet features;
};

FeatureSet features(std::initializer_list<bool FeatureSet::*> flags) {
  FeatureSet f;
  for (auto flag : flags) f.*flag = true;
  return f;
}

// Triangles: 2 per quad. cornell: 5 walls + light + 2 blocks of 5 faces = 16 quads;
// leak: 2 rooms of 5 quads + the thin wall's 6 faces = 16 quads; sunroom: 5 inner walls, the
// window wall (4 quads around the opening), the reveal (4), the exterior (5 + 4 around the
// opening) and the copper box (6) = 28 quads; movinglight: cornell without its light.
// Every material is one-sided; only the copper box has a specular lobe. atrium
// (AtriumDetail::builtin()): floor and walls 5 x 2^2 quads, ceiling 4, sacristy 6 x 1, 12
// columns of 16 x 2 quads, 10 arches of 4 grids of 12 x 2, 3 curtains of 2 sheets of 48 x 2:
// 1950 quads; every surface textured and normal-mapped, its materials with a specular lobe
// (dielectric, textured roughness), the curtains' double-sided. dynamic: 2 rooms of 5 quads,
// the thin wall's 6, the lamp 1, the basin 6 and the nozzle 1 = 24 quads; the walker's
// tubes of 4 sides with 2 caps (torso 7 levels, neck 2, legs 12, arms 7) and boxes (head, 2
// feet): 52 + 12 + 2 x 92 + 2 x 52 + 3 x 12 = 388 triangles; at t = 0 one particle (8
// triangles) is alive, born at t = 0. The tiles are glossy, the lamp and the particles emit.
const Expected kExpected[] = {
    {"cornell", 32, 0, 2, "front", 0, 1,
     features({&FeatureSet::emissive_meshes, &FeatureSet::one_sided})},
    {"leak", 32, 1, 3, "roomB", 6, 1,
     features({&FeatureSet::point_lights, &FeatureSet::one_sided})},
    {"sunroom", 56, 1, 3, "interior", 0, 1,
     features({&FeatureSet::directional_lights, &FeatureSet::specular, &FeatureSet::one_sided})},
    {"movinglight", 30, 1, 2, "front", 0, 60,
     features({&FeatureSet::point_lights, &FeatureSet::animation, &FeatureSet::one_sided})},
    {"atrium", 3900, 1, 4, "nave", 6, 1,
     features({&FeatureSet::directional_lights, &FeatureSet::specular, &FeatureSet::textures, &FeatureSet::normal_maps,
               &FeatureSet::double_sided, &FeatureSet::one_sided})},
    {"dynamic", 48 + 388 + 8, 0, 3, "room", 6, 120,
     features({&FeatureSet::emissive_meshes, &FeatureSet::specular, &FeatureSet::one_sided, &FeatureSet::animation,
               &FeatureSet::skinning, &FeatureSet::particles})},
};

class BuiltinScene : public testing::TestWithParam<Expected> {};

}  // namespace

TEST_P(BuiltinScene, LoadsWithTheExpectedCountsAndFeatures) {
  const Expected& e = GetParam();
  const Scene s = load(e.name);
  EXPECT_EQ(s.stats.triangles, e.triangles);
  EXPECT_EQ(s.stats.degenerate_triangles_dropped, 0u);
  EXPECT_EQ(s.lights.size(), e.punctual_lights);
  ASSERT_EQ(s.views.size(), e.views);
  EXPECT_EQ(s.views.front().name, e.default_view);
  EXPECT_EQ(s.leak_regions.size(), e.leak_regions);
  EXPECT_EQ(s.leak_object_ids.size(), e.leak_regions);  // each region is one leaf node
  EXPECT_EQ(s.sequence.frames, e.frames);
  EXPECT_EQ(s.features, e.features) << "got: " << testing::PrintToString(s.features.names());
}

INSTANTIATE_TEST_SUITE_P(All, BuiltinScene, testing::ValuesIn(kExpected),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(CornellScene, EmissivePowerIsPiTimesAreaTimesLuminance) {
  const Scene s = load("cornell");
  ASSERT_EQ(s.emissive_triangles.size(), 2u);
  // Published light: (343 - 213) mm x (332 - 227) mm, radiance (17, 12, 4), one-sided.
  const double area = 0.130 * 0.105;
  const glm::dvec3 radiance(17.0, 12.0, 4.0);
  const double luminance =
      0.2126 * radiance.r + 0.7152 * radiance.g + 0.0722 * radiance.b;  // BT.709
  double total_area = 0.0, total_power = 0.0;
  for (const auto& t : s.emissive_triangles) {
    total_area += t.area;
    total_power += t.power;
    EXPECT_NEAR(t.radiance.r, radiance.r, 1e-4);
    EXPECT_NEAR(t.radiance.g, radiance.g, 1e-4);
    EXPECT_NEAR(t.radiance.b, radiance.b, 1e-4);
  }
  // Float areas of 0.5 m-scale coordinates: relative error ~1e-6.
  EXPECT_NEAR(total_area, area, area * 1e-5);
  const double power = std::numbers::pi * area * luminance;  // = 0.5354 W (luminance-weighted)
  EXPECT_NEAR(total_power, power, power * 1e-5);
}

TEST(CornellScene, FrontViewIsThePublishedCamera) {
  const Scene s = load("cornell");
  const auto& cam = s.view("front").camera;
  const glm::dvec3 eye = world(s, cam.position);
  EXPECT_NEAR(eye.x, 0.278, kPositionTolerance);
  EXPECT_NEAR(eye.y, 0.273, kPositionTolerance);
  EXPECT_NEAR(eye.z, -0.800, kPositionTolerance);
  EXPECT_NEAR(glm::length(cam.forward - glm::vec3(0, 0, 1)), 0.0, 1e-6);
  // Image right is world -x: the red wall (x = 552.8 mm) is on the left.
  EXPECT_NEAR(glm::length(cam.right - glm::vec3(-1, 0, 0)), 0.0, 1e-6);
  EXPECT_NEAR(cam.yfov, 2.0 * std::atan(12.5 / 35.0), 1e-6);
  EXPECT_NO_THROW(s.view("corner"));
}

TEST(LeakScene, LightInRoomACameraInRoomB) {
  const Scene s = load("leak");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Point);
  EXPECT_LT(world(s, s.lights[0].position).x, -0.005);  // room A: x < -5 mm
  EXPECT_GT(world(s, s.view("roomB").camera.position).x, 0.005);
  EXPECT_LT(world(s, s.view("roomA").camera.position).x, -0.005);
  const std::set<std::string> regions(s.leak_regions.begin(), s.leak_regions.end());
  EXPECT_TRUE(regions.count("thin_wall_B"));
  EXPECT_TRUE(regions.count("roomB_floor"));
}

TEST(SunroomScene, SunShinesDownThroughTheWindow) {
  const Scene s = load("sunroom");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, LightType::Directional);
  const glm::dvec3 expected = glm::normalize(glm::dvec3(0.3, -0.7, 1.0));
  EXPECT_NEAR(glm::length(glm::dvec3(s.lights[0].direction) - expected), 0.0, 1e-6);
  EXPECT_NEAR(glm::length(glm::dvec3(s.lights[0].radiant()) - glm::dvec3(10.0)), 0.0, 1e-5);
}

TEST(MovingLightScene, LightFollowsThePath) {
  const Scene s = load("movinglight");
  EXPECT_EQ(s.sequence.frames, 60);
  EXPECT_EQ(s.sequence.fps, 30.0);
  EXPECT_EQ(s.sequence.animation, 0);
  // The step the metrics measure is the jump below; lag over every frame after it (nothing
  // moves then), flicker while the light circles.
  EXPECT_EQ(s.sequence.step_frame, 30);
  EXPECT_EQ(s.sequence.flicker_frames, std::pair(12, 27));
  EXPECT_EQ(s.sequence.lag_frames, std::pair(28, 59));
  EXPECT_NEAR(s.duration(), 1.0, 1e-6);  // last key: the circle closes at frame 30
  // Circle of radius 0.15 m around (0.278, 0.45, 0.2796) m, angle 2 pi f / 30 from +x; the
  // light jumps to (0.47, 0.12, 0.15) m between frames 29 and 30 and stays.
  const glm::dvec3 centre(0.278, 0.45, 0.2796);
  auto circle = [&](int f) {
    const double a = 2.0 * std::numbers::pi * f / 30.0;
    return centre + 0.15 * glm::dvec3(std::cos(a), 0.0, std::sin(a));
  };
  const std::pair<int, glm::dvec3> keys[] = {{0, {0.428, 0.45, 0.2796}},
                                             {15, {0.128, 0.45, 0.2796}},
                                             {29, circle(29)},
                                             {30, {0.47, 0.12, 0.15}},
                                             {59, {0.47, 0.12, 0.15}}};
  for (const auto& [frame, position] : keys) {
    const Scene posed = s.at_frame(frame);
    ASSERT_EQ(posed.lights.size(), 1u);
    EXPECT_NEAR(glm::length(world(posed, posed.lights[0].position) - position), 0.0,
                kPositionTolerance)
        << "frame " << frame;
  }
  // Between keys the path is linear: frame 7.5 lies half-way between frames 7 and 8.
  const Scene mid = s.at(7.5 / 30.0);
  EXPECT_NEAR(glm::length(world(mid, mid.lights[0].position) - 0.5 * (circle(7) + circle(8))), 0.0,
              kPositionTolerance);
  // Same power as the cornell light: I = A L / 4.
  const glm::dvec3 radiant = 0.130 * 0.105 * glm::dvec3(17.0, 12.0, 4.0) / 4.0;
  EXPECT_NEAR(glm::length(glm::dvec3(s.lights[0].radiant()) - radiant), 0.0, 1e-6);
}

namespace {

const giq::scenes::Mesh& mesh(const Scene& s, const std::string& name) {
  for (const auto& m : s.meshes)
    if (m.name == name) return m;
  throw std::runtime_error("no mesh " + name);
}

}  // namespace

// The walker goes once round its circle (radius 0.8 m about (4.5, 0, 4) m, counter-clockwise
// from +x, 4 s a lap) on the floor: the middle of its posed skin follows the circle within
// the spread of its swinging limbs, its head stays up and its feet on the floor.
TEST(DynamicScene, WalkerGoesRoundTheCircleOnTheFloor) {
  const Scene s = load("dynamic");
  for (int frame = 0; frame < 120; frame += 10) {
    const Scene posed = s.at_frame(frame);
    const auto& walker = mesh(posed, "walker");
    ASSERT_TRUE(walker.deformation.has_value());
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (glm::vec3 p : walker.positions) lo = glm::min(lo, world(posed, p)), hi = glm::max(hi, world(posed, p));
    const double phi = 2.0 * std::numbers::pi * frame / 120.0;
    const glm::dvec3 on_circle = glm::dvec3(4.5, 0.0, 4.0) + 0.8 * glm::dvec3(std::cos(phi), 0.0, std::sin(phi));
    // Bounds of a body 0.58 m across the shoulders whose feet and arms swing by up to
    // 0.92 sin(20 deg) = 0.31 m (the hip swing, docs/builtin-scenes.md): their middle is
    // within 0.3 m of the root.
    const glm::dvec3 middle = (lo + hi) * 0.5;
    EXPECT_LT(glm::length(glm::dvec2(middle.x - on_circle.x, middle.z - on_circle.z)), 0.3) << "frame " << frame;
    // The head's top is 1.8 m at rest; the pelvis dips by at most 15 mm.
    EXPECT_NEAR(hi.y, 1.8, 0.016) << "frame " << frame;
    // The feet: the standing sole at most 0.92 (1 - cos 20 deg) = 5.5 cm up. The swinging
    // foot's toe, turned about the bent knee, dips into the floor by up to 2.3 cm mid-swing
    // (measured; the figure is not foot-planted): it must stay within 5 cm, or the figure
    // has sunk or floats.
    EXPECT_GT(lo.y, -0.05) << "frame " << frame;
    EXPECT_LT(lo.y, 0.08) << "frame " << frame;
  }
}

// The lamp is a declared rectangle over the floor at (3.6, 2.4, 3) m until frame 29 and at
// (5.4, 2.4, 2.4) m from frame 30; the fountain's particles glow from frame 1 on.
TEST(DynamicScene, LampJumpsAtFrame30AndTheFountainGlows) {
  const Scene s = load("dynamic");
  ASSERT_EQ(s.emitters.size(), 1u);
  // The declared step is the lamp's jump; lag over 13 frames after it, flicker before it.
  EXPECT_EQ(s.sequence.step_frame, 30);
  EXPECT_EQ(s.sequence.flicker_frames, std::pair(12, 27));
  EXPECT_EQ(s.sequence.lag_frames, std::pair(28, 43));
  for (const auto& [frame, where] : {std::pair{0, glm::dvec3(3.6, 2.4, 3.0)}, {29, {3.6, 2.4, 3.0}}, {30, {5.4, 2.4, 2.4}},
                                     {119, {5.4, 2.4, 2.4}}}) {
    const Scene posed = s.at_frame(frame);
    int lamps = 0, stages = 0;
    for (const auto& l : posed.area_lights) {
      const auto& m = posed.meshes[l.mesh];
      if (m.name == "lamp") {
        ++lamps;
        EXPECT_EQ(m.area_shape, giq::scenes::AreaShape::Rectangle);
        EXPECT_NEAR(glm::length(world(posed, l.centroid) - where), 0.0, kPositionTolerance) << "frame " << frame;
        EXPECT_NEAR(l.area, 1.2 * 0.6, 1e-6);
      } else {
        EXPECT_EQ(m.emitter, 0);
        ++stages;
      }
    }
    EXPECT_EQ(lamps, 1);
    EXPECT_EQ(stages, 4) << "every glowing stage is a light in every frame";
  }
  // At t = 2 s, particle i is alive when born (i / 300 s) no later and less than 0.7 s
  // before: i = 391 .. 600.
  const Scene steady = s.at_frame(60);
  size_t particle_triangles = 0;
  for (const auto& m : steady.meshes)
    if (m.emitter == 0) particle_triangles += m.triangles.size();
  EXPECT_EQ(particle_triangles, 8u * 210u);
}
