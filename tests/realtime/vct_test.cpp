// `vct` (realtime/techniques/vct/): every built-in scene renders finite images; its indirect
// light on the Cornell box stays within measured bounds of the CPU reference's; with the light
// off the indirect layer is exactly 0; a wall one voxel thick leaks less than no wall; lights
// far beyond float16's range neither overflow nor lose precision in the 8-bit voxels; rendering
// twice gives the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "giq/base/error.h"
#include "giq/realtime/renderer.h"
#include "giq/reference/renderer.h"
#include "giq/scenes/scene.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

class VctTest : public test::VulkanTest {
 protected:
  // Renders `frames` frames of view 0; returns the last.
  image::Image render(const scenes::Scene& s, uint32_t size, std::vector<std::string> params,
                      int frames = 1) {
    RenderOptions o;
    o.technique = "vct";
    o.view = "0";
    o.width = o.height = size;
    o.frames = frames;
    o.parameters = std::move(params);
    o.parameters.push_back("shadow_map_size=256");
    return render_last(s, o);
  }
};

using test::builtin;
using test::kRgb;
using test::layer;
using test::mean;

class VctSceneTest : public VctTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(VctSceneTest, RendersFiniteIndirectLightAndComposesTheBeauty) {
  const scenes::Scene scene = builtin(GetParam());
  // A small grid keeps lavapipe fast; two frames with the temporal blend and AO on run every
  // code path (the second frame blends with the first).
  const image::Image img = render(scene, 32, {"voxel_resolution=32", "temporal_blend=0.5", "ao=1"},
                                  scene.features.animation ? 2 : 1);
  double indirect = 0.0;
  float max_ao = 0.0f;
  for (const auto& name : img.channel_names())
    for (size_t i = 0; i < img.pixel_count(); ++i)
      ASSERT_TRUE(std::isfinite(img.channel(name)[i])) << name << " " << i;
  for (int c = 0; c < 3; ++c) {
    const float *beauty = img.channel(layer("", c)), *direct = img.channel(layer("direct", c)),
                *ind = img.channel(layer("indirect", c)), *ao = img.channel(layer("ao", c));
    for (size_t i = 0; i < img.pixel_count(); ++i) {
      ASSERT_GE(ind[i], 0.0f) << i;
      // The composite pass adds the two float32 layers: the same IEEE sum.
      ASSERT_EQ(beauty[i], direct[i] + ind[i]) << i;
      ASSERT_GE(ao[i], 0.0f);
      ASSERT_LE(ao[i], 1.0f + 1e-6f);
      max_ao = std::max(max_ao, ao[i]);
      indirect += ind[i];
    }
  }
  // Every built-in scene has lit surfaces facing each other: some light must bounce.
  EXPECT_GT(indirect, 0.0) << GetParam();
  // Every view shows surfaces meeting at a corner or an object on the floor: somewhere the
  // cones are mostly occluded (measured maxima 0.74 to 0.88 at 32^3 voxels; a layer left
  // unwritten reads 0).
  EXPECT_GT(max_ao, 0.5f) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, VctSceneTest,
                         ::testing::Values("cornell", "leak", "movinglight", "sunroom", "atrium"));

TEST_F(VctTest, CornellIndirectLightIsWithinMeasuredBoundsOfTheReference) {
  const scenes::Scene scene = builtin("cornell");
  const int size = 48;
  // The reference with all bounces (what `giq score` compares with) and with as many
  // diffuse bounces as VCT traces (max_bounces counts the camera ray's surface too).
  auto reference = [&](int bounces) {
    reference::RenderSettings rs;
    rs.width = rs.height = size;
    rs.seed = 3;
    rs.max_bounces = bounces;
    reference::Renderer ref(scene, scene.view("0").camera, rs);
    reference::Film film = ref.make_film();
    ref.render(film, 512);
    return film.to_image();
  };
  const image::Image all = reference(64);
  // Measured mean indirect radiance of vct over the reference's, per channel R, G, B
  // (64^3 voxels, 48 x 48, k = 2, default footprint guard; renders are deterministic):
  //   against the reference with the same number of bounces:
  //     1 bounce  0.868 0.903 1.062    2 bounces 0.903 0.966 1.223
  //   against the reference with all bounces:
  //     1 bounce  0.420 0.473 0.652    2 bounces 0.662 0.744 1.041
  // Within 14% of the same-bounce reference (22% for blue with two bounces): the units are right (a
  // factor pi, a missing albedo or a lost cone would be off by far more). What remains is VCT's own
  // error: cones that see the surface's own voxels add light (most in blue, where the white walls
  // that see themselves dominate), coarse samples that step over thin walls lose some. Each bound
  // is the measured ratio +-12%: the reference's means have a relative standard error under 0.5% at
  // 512 paths per pixel over 2304 pixels, so the margin is for legitimate changes of the sampling,
  // not noise.
  const double same_ratio[2][3] = {{0.868, 0.903, 1.062}, {0.903, 0.966, 1.223}};
  const double all_ratio[2][3] = {{0.420, 0.473, 0.652}, {0.662, 0.744, 1.041}};
  for (int bounces = 1; bounces <= 2; ++bounces) {
    const image::Image v =
        render(scene, size, {"voxel_resolution=64", "bounces=" + std::to_string(bounces)});
    const image::Image same = reference(bounces + 1);
    for (int c = 0; c < 3; ++c) {
      const std::string ch = layer("indirect", c);
      const double m = mean(v, ch), m_same = mean(same, ch), m_all = mean(all, ch);
      EXPECT_NEAR(m / m_same, same_ratio[bounces - 1][c], 0.12 * same_ratio[bounces - 1][c])
          << bounces << " bounce(s), " << kRgb[c] << ": vct " << m << ", reference " << m_same;
      EXPECT_NEAR(m / m_all, all_ratio[bounces - 1][c], 0.12 * all_ratio[bounces - 1][c])
          << bounces << " bounce(s), " << kRgb[c] << ": vct " << m << ", reference (all bounces) "
          << m_all;
    }
  }
}

TEST_F(VctTest, WithTheLightOffIndirectLightIsExactlyZero) {
  const image::Image img = render(test::cornell_with_every_light_off(), 24, {"voxel_resolution=32"});
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < img.pixel_count(); ++i)
      ASSERT_EQ(img.channel(layer("indirect", c))[i], 0.0f) << i;
}

TEST_F(VctTest, AWallOneVoxelThickLeaksLessThanNoWall) {
  // A room [-4, 4] x [0, 2] x [-4, 4] without a ceiling, seen from above, lit by a point light
  // in its left half. Without the dividing wall the right half is lit directly and its walls
  // and floor light each other; with a wall x in [0, t], exactly one voxel thick and as high
  // as the room, the right half is in shadow and receives only what leaks through the
  // voxels. Voxels are isotropic and filtered trilinearly, so the wall's lit face does leak
  // (the technique's known artefact): the test bounds how much.
  const uint32_t res = 32;
  scenes::Scene open = test::lambert_plane(0.8f, 4.0f, 7.0f);
  const int white = test::add_material(open, glm::vec3(0.8f));
  open.materials[size_t(white)].double_sided = true;
  test::add_quad(open, {-4, 0, -4}, {-4, 0, 4}, {-4, 2, 4}, {-4, 2, -4}, white);
  test::add_quad(open, {4, 0, -4}, {4, 0, 4}, {4, 2, 4}, {4, 2, -4}, white);
  test::add_quad(open, {-4, 0, -4}, {4, 0, -4}, {4, 2, -4}, {-4, 2, -4}, white);
  test::add_quad(open, {-4, 0, 4}, {4, 0, 4}, {4, 2, 4}, {-4, 2, 4}, white);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {-2.0f, 1.0f, 0.0f};
  l.intensity = 20.0f;
  open.lights.push_back(l);
  open.derive();
  // The voxel cube's side is the scene's largest extent (8) over res - 2 voxels, centred on
  // the scene, so x = 0 is a voxel boundary and [0, t] exactly one column of voxels.
  const float t = 8.0f / float(res - 2);
  scenes::Scene walled = open;
  test::add_quad(walled, {0, 0, -4}, {0, 0, 4}, {0, 2, 4}, {0, 2, -4}, white);
  test::add_quad(walled, {t, 0, -4}, {t, 0, 4}, {t, 2, 4}, {t, 2, -4}, white);
  walled.derive();
  ASSERT_EQ(walled.bounds.extent(), open.bounds.extent());  // the same voxel grid
  const int size = 48;
  const std::string res_param = "voxel_resolution=" + std::to_string(res);
  const image::Image a = render(open, size, {res_param}), b = render(walled, size, {res_param});
  // Receiver pixels: the floor at x > 1 (two voxels clear of the wall).
  const auto& cam = open.views[0].camera;
  double sum_open = 0.0, sum_walled = 0.0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec3 d = cam.ray_direction(x + 0.5f, y + 0.5f, size, size);
      const glm::vec3 p = cam.position + (-cam.position.y / d.y) * d;
      if (p.x < 1.0f) continue;
      const size_t i = size_t(y) * size + size_t(x);
      sum_open += a.channel("indirect.G")[i];
      sum_walled += b.channel("indirect.G")[i];
    }
  ASSERT_GT(sum_open, 0.0);
  // The truth with the wall is 0 (nothing in the right half is lit and the sky is black).
  // Measured: the wall lets through 0.28 of the open room's indirect light (32^3 voxels,
  // 48 x 48; renders are deterministic). The bound 0.4 keeps a margin over it and fails any
  // change that makes the one-voxel wall markedly more transparent.
  EXPECT_LT(sum_walled, 0.4 * sum_open) << "walled " << sum_walled << " open " << sum_open;
}

TEST_F(VctTest, LightsBeyondFloat16RangeScaleLinearly) {
  // Voxels store radiance times a power-of-two scale below 1 / (a bound on it) (voxel_scale.h),
  // so a light 2^20 (about 1e6) times brighter -- radiances near 1e7, far beyond float16's
  // 65504 -- neither clips nor overflows: every radiance and the scale change by exactly 2^20,
  // the 8-bit codes are the same, and the indirect light is exactly 2^20 times the dim one's.
  scenes::Scene dim = builtin("cornell");
  scenes::Scene bright = dim;
  const float k = 1048576.0f;
  for (auto& m : bright.materials) m.emissive *= k;
  bright.derive();
  const image::Image a = render(dim, 24, {"voxel_resolution=32"});
  const image::Image b = render(bright, 24, {"voxel_resolution=32"});
  double sum = 0.0;
  for (int c = 0; c < 3; ++c) {
    const std::string ch = layer("indirect", c);
    for (size_t i = 0; i < a.pixel_count(); ++i) {
      ASSERT_TRUE(std::isfinite(b.channel(ch)[i]));
      ASSERT_EQ(b.channel(ch)[i], k * a.channel(ch)[i]) << ch << " " << i;
      sum += a.channel(ch)[i];
    }
  }
  EXPECT_GT(sum, 0.0);
}

// A faint point light a millionth of a voxel above the Cornell box's floor: bounded by its
// distance to the floor, its irradiance would be millions of times the ceiling light's bound,
// and the scale as many times smaller: every voxel but those beside the light below 8-bit
// sRGB's smallest code, the indirect light black. Bounded at half a voxel instead
// (voxel_scale.h), it leaves the scale to the ceiling light; the voxels beside it clip, and
// the indirect light changes only there: the mean keeps within 5 % of the box's without it.
TEST_F(VctTest, ALightOnASurfaceDoesNotDarkenTheOtherVoxels) {
  const scenes::Scene box = builtin("cornell");
  scenes::Scene lamp = box;
  scenes::Light l;
  l.intensity = 1e-6f;
  const float voxel = box.bounds.largest_side() / 32.0f;
  // Near the left wall, clear of the blocks.
  l.position = glm::vec3(box.bounds.lo.x + 3.0f * voxel, box.bounds.lo.y + 1e-6f * voxel, 0.5f * (box.bounds.lo.z + box.bounds.hi.z));
  lamp.add_light(l, "a faint lamp on the floor");
  auto indirect = [&](const scenes::Scene& s) {
    const image::Image img = render(s, 24, {"voxel_resolution=32"});
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) sum += mean(img, layer("indirect", c));
    return sum;
  };
  const double without = indirect(box), with = indirect(lamp);
  ASSERT_GT(without, 0.0);
  EXPECT_NEAR(with / without, 1.0, 0.05);
}

TEST_F(VctTest, APersistentInstanceFollowsTheMovingLight) {
  // One vct instance through three frames of `movinglight` (re-voxelised every frame, no
  // temporal blend) gives at every frame the bits of an instance created for that pose alone:
  // nothing derived from the light (voxel lighting, radiance scale) is kept stale.
  RenderOptions o;
  o.technique = "vct";
  o.width = o.height = 32;
  o.frames = 3;
  o.parameters = {"shadow_map_size=256", "voxel_resolution=32"};
  expect_persistent_matches_fresh(builtin("movinglight"), o, "indirect.R");
}

// A shelf under the lamp, cut out entirely by its alpha mask (MASK, alpha 0): the G-buffer and
// the shadow maps cut it out, and so does the voxelisation, so vct's indirect light is that of
// the box without the shelf. The same shelf opaque changes it by half (it is lit close to
// the lamp and shades the room: measured 0.0234 against 0.0154). Without the shelf
// the shaders are compiled without alpha masking, so the tolerance allows the other shader
// variant's rounding (1e-4 relative; measured 0).
TEST_F(VctTest, ACutOutShelfIsNotVoxelised) {
  auto box = [](int shelf) {  // 0 none, 1 opaque, 2 cut out
    scenes::Scene s = test::cornell_box();
    if (shelf) {
      const int m = test::add_material(s, glm::vec3(0.7f));
      s.materials[size_t(m)].double_sided = true;
      if (shelf == 2) {
        s.materials[size_t(m)].alpha_mode = scenes::AlphaMode::Mask;
        s.materials[size_t(m)].base_color.a = 0.0f;
      }
      test::add_quad(s, {-0.9f, 0.7f, 0.9f}, {0.9f, 0.7f, 0.9f}, {0.9f, 0.7f, -0.9f}, {-0.9f, 0.7f, -0.9f}, m);
      s.derive();
    }
    return s;
  };
  const std::vector<std::string> params = {"voxel_resolution=32"};
  const double none = mean(render(box(0), 32, params), "indirect.G");
  const double opaque = mean(render(box(1), 32, params), "indirect.G");
  const double cut = mean(render(box(2), 32, params), "indirect.G");
  ASSERT_GT(none, 0.0);
  EXPECT_GT(std::abs(opaque - none), 0.2 * none);
  EXPECT_NEAR(cut, none, 1e-4 * none) << "opaque " << opaque;
}

TEST_F(VctTest, RenderingIsDeterministic) {
  // Voxelisation keeps the smallest triangle index per voxel (an atomic minimum): no voxel
  // depends on the order in which the GPU runs the triangles, so two renders agree bit for bit.
  const scenes::Scene scene = builtin("cornell");
  const image::Image a = render(scene, 24, {"voxel_resolution=32"}),
                     b = render(scene, 24, {"voxel_resolution=32"});
  for (size_t i = 0; i < a.pixel_count(); ++i)
    ASSERT_EQ(a.channel("indirect.G")[i], b.channel("indirect.G")[i]);
}

TEST_F(VctTest, InvalidParameterCombinationsAreInputErrors) {
  const scenes::Scene scene = builtin("cornell");
  EXPECT_THROW(render(scene, 8, {"voxel_resolution=48"}), InputError);
  // The temporal blend needs the mips rebuilt once per frame.
  EXPECT_THROW(render(scene, 8, {"voxel_resolution=16", "bounces=2", "temporal_blend=0.5"}),
               InputError);
}

}  // namespace
}  // namespace giq::realtime
