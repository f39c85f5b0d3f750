// Material behaviour the glTF specification fixes: alpha-mask cut-outs are transparent to
// every ray, a one-sided surface's back is black (reflects and emits nothing) while a
// double-sided one shades both sides, and shading normals never bring light from below the
// geometric surface.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

constexpr int kSize = 16;

Film render(const scenes::Scene& s, const scenes::Camera& cam, uint32_t spp = 8) {
  RenderSettings rs;
  rs.width = rs.height = kSize;
  Renderer r(s, cam, rs);
  Film f = r.make_film();
  r.render(f, spp);
  EXPECT_EQ(f.nonfinite_samples(), 0u);
  return f;
}

double total(const Film& f) {
  double t = 0.0;
  for (const PixelAccumulator& p : f.pixels) t += p.mean[0] + p.mean[1] + p.mean[2];
  return t;
}

scenes::Light sun(glm::vec3 direction) {
  scenes::Light l;
  l.type = scenes::LightType::Directional;
  l.direction = glm::normalize(direction);
  l.intensity = 2.0f;
  return l;
}

const scenes::Camera kCam = scenes::Camera::look_at({0.3f, 3.0f, 0.5f}, {0, 0, 0}, {0, 0, -1}, 0.9f);

// A lit floor with a square card floating over it (between the floor, the camera and the sun).
scenes::Scene floor_and_card(float card_alpha, bool with_card) {
  scenes::Scene s;
  const int floor = test::add_material(s, test::diffuse(glm::vec3(0.6f)));
  test::add_quad(s, floor, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 1);
  scenes::Material card = test::diffuse({0.9f, 0.1f, 0.1f}, glm::vec3(0.0f), true);
  card.base_color.a = card_alpha;
  card.alpha_mode = scenes::AlphaMode::Mask;
  card.alpha_cutoff = 0.5f;
  const int c = test::add_material(s, card);
  if (with_card) test::add_quad(s, c, {-0.6f, 1, 0.6f}, {0.6f, 1, 0.6f}, {0.6f, 1, -0.6f}, {-0.6f, 1, -0.6f}, 2);
  s.lights.push_back(sun({0.2f, -1.0f, -0.1f}));
  s.derive();
  return s;
}

TEST(Materials, AlphaMaskCutOutIsTransparentToEveryRay) {
  const Film without = render(floor_and_card(1.0f, false), kCam);
  const scenes::Scene cut = floor_and_card(0.3f, true);
  ASSERT_TRUE(cut.features.alpha_mask);
  const Film with_cut = render(cut, kCam);
  // Same random numbers, same paths: a card that is cut out everywhere changes nothing.
  for (size_t i = 0; i < without.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) ASSERT_EQ(with_cut.pixels[i].mean[c], without.pixels[i].mean[c]) << "pixel " << i;
  // Above the cutoff the card is there: it is seen (object id 2) and casts a shadow.
  const Film opaque = render(floor_and_card(0.7f, true), kCam);
  EXPECT_NE(total(opaque), total(without));
}

// BLEND is stochastic transparency: a ray meets the surface with probability alpha. A black
// card of alpha a between a floor, the sun straight above and a camera straight above: where
// the camera looks through the card at its shadow, light passed the card twice, so the
// pixel's expected value is (1 - a)^2 (rho / pi) E, compared within 4 standard errors of the
// mean over those pixels.
TEST(Materials, BlendIsStochasticTransparencyWithTheMaterialsAlpha) {
  const scenes::Camera top = scenes::Camera::look_at({0.0f, 3.0f, 0.0f}, {0, 0, 0}, {0, 0, -1}, 0.9f);
  for (const float a : {0.0f, 0.4f, 1.0f}) {
    scenes::Scene s;
    const int floor = test::add_material(s, test::diffuse(glm::vec3(0.6f)));
    test::add_quad(s, floor, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 1);
    scenes::Material card = test::diffuse(glm::vec3(0.0f), glm::vec3(0.0f), true);
    card.base_color.a = a;
    card.alpha_mode = scenes::AlphaMode::Blend;
    const int c = test::add_material(s, card);
    test::add_quad(s, c, {-0.6f, 1, 0.6f}, {0.6f, 1, 0.6f}, {0.6f, 1, -0.6f}, {-0.6f, 1, -0.6f}, 2);
    s.lights.push_back(sun({0.0f, -1.0f, 0.0f}));
    s.derive();
    ASSERT_TRUE(s.features.alpha_mask);
    const Film f = render(s, top, 256);
    // The central 4 x 4 pixels see the floor within 0.75 tan(0.45) x 3 = 0.36 m of the axis
    // through the card (which spans 0.6 m): in its shadow, through it.
    double mean = 0.0, var = 0.0;
    for (int y = kSize / 2 - 2; y < kSize / 2 + 2; ++y)
      for (int x = kSize / 2 - 2; x < kSize / 2 + 2; ++x) {
        const PixelAccumulator& p = f.pixels[size_t(y) * kSize + size_t(x)];
        mean += p.mean[0] / 16.0, var += p.variance_of_mean(0) / 256.0;
      }
    const double expected = (1.0 - a) * (1.0 - a) * 0.6 / 3.14159265358979 * 2.0;
    EXPECT_NEAR(mean, expected, 4.0 * std::sqrt(var) + 1e-6) << "alpha " << a;
  }
}

// Light found by sampling a BLEND emitter carries its coverage, as light found by a BSDF ray
// that meets it with probability alpha does: the two estimators converge to the same image.
TEST(Materials, BlendEmitterIsLitAlikeByLightAndBsdfSampling) {
  scenes::Scene s;
  const int floor = test::add_material(s, test::diffuse(glm::vec3(0.6f)));
  test::add_quad(s, floor, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 1);
  scenes::Material lamp = test::diffuse(glm::vec3(0.0f), glm::vec3(3.0f));
  lamp.base_color.a = 0.35f;
  lamp.alpha_mode = scenes::AlphaMode::Blend;
  const int l = test::add_material(s, lamp);
  test::add_quad(s, l, {-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}, 2);  // faces down
  s.derive();
  // Both integrators: the eight-lane one (this scene is Lambertian and untextured) and the
  // one-path one.
  for (const bool lanes : {true, false}) {
    double means[2] = {0.0, 0.0}, vars[2] = {0.0, 0.0};
    int k = 0;
    for (Estimator e : {Estimator::LightOnly, Estimator::BsdfOnly}) {
      RenderSettings rs;
      rs.width = rs.height = kSize;
      rs.estimator = e;
      rs.lanes = lanes ? RenderSettings::Lanes::Auto : RenderSettings::Lanes::Never;
      Renderer r(s, kCam, rs);
      EXPECT_EQ(r.lanes(), lanes);
      Film f = r.make_film();
      r.render(f, 128);
      const double n = double(f.pixels.size());
      for (const PixelAccumulator& p : f.pixels) means[k] += p.mean[0] / n, vars[k] += p.variance_of_mean(0) / (n * n);
      ++k;
    }
    EXPECT_GT(means[0], 0.0);
    EXPECT_NEAR(means[0], means[1], 4.0 * std::sqrt(vars[0] + vars[1]))
        << (lanes ? "lanes" : "one path") << ": light " << means[0] << " bsdf " << means[1];
  }
}

// glTF 2.0, 3.9.5: a single-sided surface is culled from behind. A black card between the
// camera and a lit floor, its back to the camera and its shadow out of view: camera rays pass
// it, and light transport meets only its black front (paths end there as they would have
// escaped), so the image is the one without the card, bit for bit, with both integrators. A
// double-sided card is seen: black pixels.
TEST(Materials, CameraRaysPassTheBackOfSingleSidedSurfaces) {
  const scenes::Camera top = scenes::Camera::look_at({0.0f, 3.0f, 0.0f}, {0, 0, 0}, {0, 0, -1}, 0.9f);
  auto scene = [](int card) {  // 0: none, 1: single-sided, 2: double-sided
    scenes::Scene s;
    const int floor = test::add_material(s, test::diffuse(glm::vec3(0.6f)));
    test::add_quad(s, floor, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 1);
    const int c = test::add_material(s, test::diffuse(glm::vec3(0.0f), glm::vec3(0.0f), card == 2));
    // Faces down: its back is to the camera above.
    if (card) test::add_quad(s, c, {-0.6f, 1, -0.6f}, {0.6f, 1, -0.6f}, {0.6f, 1, 0.6f}, {-0.6f, 1, 0.6f}, 2);
    s.lights.push_back(sun({-1.0f, -0.3f, 0.0f}));  // the card's shadow falls at x < -2.7
    s.derive();
    return s;
  };
  for (const bool lanes : {true, false}) {
    RenderSettings rs;
    rs.width = rs.height = kSize;
    rs.lanes = lanes ? RenderSettings::Lanes::Auto : RenderSettings::Lanes::Never;
    auto image = [&](int card) {
      const scenes::Scene s = scene(card);
      Renderer r(s, top, rs);
      Film f = r.make_film();
      r.render(f, 8);
      r.render_aux(f);
      return f;
    };
    const Film none = image(0), single = image(1), both = image(2);
    for (size_t i = 0; i < none.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(single.pixels[i].mean[c], none.pixels[i].mean[c]) << "pixel " << i << (lanes ? " lanes" : "");
    for (size_t i = 0; i < none.aux.size(); ++i) {  // the first-hit layers see the floor too
      ASSERT_EQ(single.aux[i].object_id, none.aux[i].object_id) << "pixel " << i;
      ASSERT_EQ(single.aux[i].depth, none.aux[i].depth) << "pixel " << i;
    }
    const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
    EXPECT_GT(none.pixels[centre].mean[0], 0.0);
    EXPECT_EQ(both.pixels[centre].mean[0], 0.0);
  }
}

TEST(Materials, BackOfOneSidedSurfaceIsBlackDoubleSidedIsShaded) {
  for (bool double_sided : {false, true}) {
    scenes::Scene s;
    const int m = test::add_material(s, test::diffuse(glm::vec3(0.5f), glm::vec3(0.25f), double_sided));
    // Faces down (-y); the sun above lights its back, and the camera above sees that back
    // (double-sided) or, through it, nothing (single-sided: culled).
    test::add_quad(s, m, {-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}, 1);
    s.lights.push_back(sun({0.0f, -1.0f, 0.0f}));
    s.derive();
    const Film f = render(s, kCam, 64);
    if (!double_sided) {
      EXPECT_EQ(total(f), 0.0);
    } else {
      // Emission 0.25 plus (rho / pi) E on every pixel. The emissive quad is also an area
      // light that next-event estimation may pick (uselessly, for points on itself), so the
      // image is noisy: compare its mean within 4 standard errors.
      const double expected = 0.25 + 0.5 / 3.14159265358979 * 2.0;
      double mean = 0.0, var = 0.0;
      const double n = double(f.pixels.size());
      for (const PixelAccumulator& p : f.pixels) mean += p.mean[0] / n, var += p.variance_of_mean(0) / (n * n);
      EXPECT_GT(var, 0.0);
      EXPECT_NEAR(mean, expected, 4.0 * std::sqrt(var) + 1e-6);
    }
  }
}

TEST(Materials, ShadingNormalsDoNotLeakLightFromBelow) {
  // A floor whose vertex normals lean 80 degrees towards a sun that shines from below it:
  // the geometric surface faces away from the sun, so its top must stay black.
  scenes::Scene s;
  const int m = test::add_material(s, test::diffuse(glm::vec3(0.8f)));
  test::add_quad(s, m, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 1);
  const glm::vec3 lean = glm::normalize(glm::vec3(std::sin(1.4f), std::cos(1.4f), 0.0f));
  s.meshes[0].normals.assign(4, lean);
  s.lights.push_back(sun({-1.0f, 0.3f, 0.0f}));  // travels up and to -x: below the floor
  s.derive();
  EXPECT_EQ(total(render(s, kCam)), 0.0);
}

}  // namespace
}  // namespace giq::reference

namespace giq::reference {
namespace {

TEST(Materials, FirstHitLayersAndTextures) {
  // A plane textured with a 2 x 1 red/green texture (nearest filtering), seen straight down
  // from height 4: albedo follows the texels, N is +y, Z is 4, objectId is the mesh's.
  scenes::Scene s;
  scenes::Texture t;
  t.name = "red-green";
  t.assign(2, 1, {{1, 0, 0, 1}, {0, 1, 0, 1}});
  t.wrap_s = t.wrap_t = scenes::Wrap::ClampToEdge;
  t.filter = scenes::Filter::Nearest;
  s.textures.push_back(t);
  scenes::Material m = test::diffuse(glm::vec3(0.5f));
  m.base_color_texture = 0;
  const int mi = test::add_material(s, m);
  test::add_quad(s, mi, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 42);
  s.lights.push_back(sun({0.0f, -1.0f, 0.0f}));
  s.derive();
  ASSERT_TRUE(s.features.textures);
  RenderSettings rs;
  rs.width = rs.height = kSize;
  const scenes::Camera cam = scenes::Camera::look_at({0, 4, 0}, {0, 0, 0}, {0, 0, -1}, 0.9f);
  Renderer r(s, cam, rs);
  EXPECT_NE(r.feature_mask() & 2u, 0u);  // the textured variant runs (FeatureBit kTextures)
  Film f = r.make_film();
  r.render_aux(f);
  r.render(f, 4);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = size_t(y) * kSize + size_t(x);
      const PixelAux& a = f.aux[i];
      const bool left = x < kSize / 2;
      ASSERT_EQ(a.albedo[0], left ? 0.5f : 0.0f) << x << "," << y;
      ASSERT_EQ(a.albedo[1], left ? 0.0f : 0.5f) << x << "," << y;
      ASSERT_NEAR(a.normal[1], 1.0f, 1e-6f);
      ASSERT_NEAR(a.depth, 4.0f, 4e-6f);
      ASSERT_EQ(a.object_id, 42u);
      // Lit straight on with E = 2: radiance (0.5 / pi) * 2 in the texel's channel. Pixels on
      // the seam mix both texels through the jitter, so test the others.
      if (x != kSize / 2 - 1 && x != kSize / 2) ASSERT_NEAR(f.pixels[i].mean[left ? 0 : 1], 1.0 / 3.14159265358979, 1e-5);
    }
}

}  // namespace
}  // namespace giq::reference

namespace giq::reference {
namespace {

TEST(Materials, NonFiniteSamplesAreDiscardedAndCounted) {
  // A material with a NaN base colour makes every sample that reflects off it NaN: those are
  // counted and replaced by zero, and nothing non-finite reaches the image.
  scenes::Scene s = floor_and_card(1.0f, false);
  s.materials[0].base_color = glm::vec4(std::nanf(""), 0.5f, 0.5f, 1.0f);
  s.derive();
  RenderSettings rs;
  rs.width = rs.height = kSize;
  Renderer r(s, kCam, rs);
  Film f = r.make_film();
  r.render_aux(f);
  r.render(f, 4);
  EXPECT_EQ(f.nonfinite_samples(), uint64_t(kSize) * kSize * 4);
  const image::Image img = f.to_image();
  for (const std::string& c : img.channel_names()) {
    const float* p = img.channel(c);
    for (size_t i = 0; i < img.pixel_count(); ++i) ASSERT_TRUE(std::isfinite(p[i])) << c;
  }
}

}  // namespace
}  // namespace giq::reference

namespace giq::reference {
namespace {

TEST(Materials, NormalMapsTiltTowardTheImagesRightAndUp) {
  // glTF 2.0, 3.9.3: a normal texture's +X points to the image's right (+u) and its +Y up the
  // image, which is -v since glTF's v runs down the image. A plane y = 0 seen from above
  // (screen up -z) under a constant normal map tilted right and up: the first-hit normal must
  // lean along +u and -v, with tangents from the UVs (no TANGENT) and with given ones (those
  // MikkTSpace gives this plane, tests/scenes/tangent_space_test.cpp), for a mapping as seen
  // and one mirrored in u.
  const glm::vec3 tilt = glm::normalize(glm::vec3(0.5f, 0.3f, 1.0f));
  scenes::Texture t;
  t.assign(1, 1, {glm::vec4(0.5f * tilt + 0.5f, 1.0f)});
  const scenes::Camera cam = scenes::Camera::look_at({0, 4, 0}, {0, 0, 0}, {0, 0, -1}, 0.9f);
  for (const bool mirrored : {false, true})
    for (const bool given : {false, true}) {
      SCOPED_TRACE(std::string(mirrored ? "mirrored" : "as seen") + (given ? ", given tangents" : ", tangents from the UVs"));
      scenes::Scene s;
      s.textures.push_back(t);
      scenes::Material m = test::diffuse(glm::vec3(0.5f));
      m.normal_texture = 0;
      test::add_quad(s, test::add_material(s, m), {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4});
      scenes::Mesh& quad = s.meshes.back();
      for (size_t i = 0; i < 4; ++i) {
        const glm::vec3 p = quad.positions[i];
        quad.uvs[i] = {mirrored ? (4.0f - p.x) / 8.0f : (p.x + 4.0f) / 8.0f, (p.z + 4.0f) / 8.0f};  // v grows down the screen, +z
      }
      if (given) quad.tangents.assign(4, mirrored ? glm::vec4(-1, 0, 0, -1) : glm::vec4(1, 0, 0, 1));
      s.lights.push_back(sun({0.0f, -1.0f, 0.0f}));
      s.derive();
      RenderSettings rs;
      rs.width = rs.height = kSize;
      Renderer r(s, cam, rs);
      Film f = r.make_film();
      r.render_aux(f);
      const glm::vec3 right(mirrored ? -1.0f : 1.0f, 0.0f, 0.0f), up(0.0f, 0.0f, -1.0f), n(0.0f, 1.0f, 0.0f);
      const glm::vec3 expected = glm::normalize(tilt.x * right + tilt.y * up + tilt.z * n);
      for (const PixelAux& a : f.aux)
        for (int k = 0; k < 3; ++k) ASSERT_NEAR(a.normal[k], expected[k], 1e-6f) << k;  // float rounding of unit vectors
    }
}

}  // namespace
}  // namespace giq::reference
