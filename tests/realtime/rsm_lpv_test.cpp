// `rsm` and `lpv`: every built-in scene renders finite; energy sanity (a dark light gives exactly
// no indirect light, intensity scales it linearly far beyond float16's range); `rsm` against
// the one-bounce path tracer on a sunlit room; `lpv` with 0 propagation steps is the injected
// light only; the ray-traced reflective shadow maps hold the rasterised ones' texels. The
// comparisons with the CPU reference are in rsm_lpv_reference_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <glm/gtc/packing.hpp>
#include <string>

#include "giq/realtime/renderer.h"
#include "giq/realtime/scene_gpu.h"
#include "giq/realtime/timer.h"
#include "passes/rsm.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

// Places a view's camera at `position` looking along `forward` (normalised here), y up.
void aim(scenes::Camera& c, glm::vec3 position, glm::vec3 forward) {
  c.position = position;
  c.forward = glm::normalize(forward);
  c.right = glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0)));
  c.up = glm::cross(c.right, c.forward);
}

class RsmLpvTest : public test::VulkanTest {
 protected:
  image::Image render(const scenes::Scene& s, const std::string& technique, uint32_t size,
                      std::vector<std::string> params = {}, int frames = 1) {
    RenderOptions o;
    o.technique = technique;
    o.width = o.height = size;
    o.frames = frames;
    o.parameters = std::move(params);
    return render_last(s, o);
  }
};

// Small maps and grids keep lavapipe fast; the algorithms are the same at any size.
std::vector<std::string> small(const std::string& technique) {
  std::vector<std::string> p = {"shadow_map_size=256", "rsm_size=256", "rsm_cube_size=64"};
  if (technique == "rsm") p.push_back("samples=64");
  if (technique == "lpv") {
    p.push_back("lpv_grid=16");
    p.push_back("propagation_steps=16");
  }
  return p;
}

using test::mean;

TEST_F(RsmLpvTest, EveryBuiltInSceneRendersFinite) {
  // The built-in scenes, and the textured room (textures, a normal map, an alpha mask: the RSM
  // texels and the receivers take their material from the textures).
  const std::filesystem::path textured =
      std::filesystem::path(GIQ_TEST_DATA) / "scenes/textured_room.gltf";
  for (const std::string name : {"cornell", "leak", "sunroom", "movinglight", "textured_room"}) {
    const scenes::Scene s = scenes::load(
        name == "textured_room" ? textured
                                : std::filesystem::path(GIQ_SCENES_DIR) / (name + ".gltf"));
    for (const char* t : {"rsm", "lpv"}) {
      // Two frames of the moving light: the second re-renders the RSM for the moved light.
      const image::Image img = render(s, t, 24, small(t), s.features.animation ? 2 : 1);
      double indirect = 0.0;
      for (const char* c : {"R", "G", "B"}) {
        const std::string ind = std::string("indirect.") + c, dir = std::string("direct.") + c;
        for (size_t i = 0; i < img.pixel_count(); ++i) {
          const float b = img.channel(c)[i], d = img.channel(dir)[i], n = img.channel(ind)[i];
          ASSERT_TRUE(std::isfinite(b) && std::isfinite(d) && std::isfinite(n))
              << name << " " << t << " " << i;
          EXPECT_GE(n, 0.0f) << name << " " << t << " " << i;
          // beauty = direct + indirect, one float addition.
          EXPECT_NEAR(b, d + n, 1e-6f * (d + n)) << name << " " << t;
          indirect += n;
        }
      }
      // Every built-in scene has bounced light where the camera looks (leak's room B has
      // none in truth; both techniques leak into it through the 1 cm wall: no visibility).
      EXPECT_GT(indirect, 0.0) << name << " " << t;
    }
  }
}

TEST_F(RsmLpvTest, ADarkLightGivesExactlyNoIndirectLight) {
  // The Cornell box with its emitter black (no area light) and a point light and a sun of
  // intensity 0: their RSMs exist but store zero flux, so the gather and the injection add
  // exact zeros.
  scenes::Scene s = test::cornell_box(glm::vec3(0.0f));
  scenes::Light point;
  point.type = scenes::LightType::Point;
  point.position = {0.0f, 0.5f, 0.0f};
  point.intensity = 0.0f;
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.intensity = 0.0f;
  s.lights = {point, sun};
  s.derive();
  // And a scene with no light at all: no RSM layer, nothing to gather or inject.
  const scenes::Scene unlit = test::lambert_plane(0.5f);
  for (const char* t : {"rsm", "lpv"})
    for (const char* builder : {"rsm_ray_traced=0", "rsm_ray_traced=1"})
      for (const scenes::Scene* scene : {static_cast<const scenes::Scene*>(&s), &unlit}) {
        std::vector<std::string> p = small(t);
        p.push_back(builder);
        const image::Image img = render(*scene, t, 16, p);
        for (const char* c : {"indirect.R", "indirect.G", "indirect.B"})
          for (size_t i = 0; i < img.pixel_count(); ++i)
            ASSERT_EQ(img.channel(c)[i], 0.0f) << t << " " << builder << " " << c << " " << i;
      }
}

TEST_F(RsmLpvTest, IndirectLightScalesLinearlyBeyondHalfFloatRange) {
  // 1e12 W/sr: VPL flux densities near 1e11, far beyond float16's 65504. The RSM stores flux
  // divided by the light's brightest channel and LPV's fixed point is scaled by the same bound,
  // so both store the same values for the dim and the bright light; the result scales by 1e12
  // up to float32 rounding of the final products (a few ulps).
  scenes::Scene dim = test::cornell_box(glm::vec3(0.0f));
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.2f, 0.6f, 0.1f};
  l.intensity = 1.0f;
  dim.lights.push_back(l);
  dim.derive();
  scenes::Scene bright = dim;
  bright.lights[0].intensity = 1e12f;
  bright.derive();
  for (const char* t : {"rsm", "lpv"}) {
    const image::Image a = render(dim, t, 16, small(t)), b = render(bright, t, 16, small(t));
    double sum = 0.0;
    for (size_t i = 0; i < a.pixel_count(); ++i) {
      const double x = a.channel("indirect.G")[i], y = b.channel("indirect.G")[i];
      ASSERT_TRUE(std::isfinite(y)) << t;
      EXPECT_NEAR(y, 1e12 * x, 1e-5 * 1e12 * x + 1e-30) << t << " " << i;
      sum += x;
    }
    EXPECT_GT(sum, 0.0) << t;
  }
}

TEST_F(RsmLpvTest, RsmMatchesTheOneBouncePathTracerUnderTheSun) {
  // A sunlit floor and a sunlit wall standing on it, nothing else: no VPL is hidden from a
  // receiver, so RSM's only approximation left is the finite sampling, and rsm's indirect
  // layer approaches pt's with one bounce (max_bounces = 2) as the samples grow. It does so
  // from below: each sample's near-field term d^2 + a/pi (a = the area a sample stands for)
  // removes part of the light from VPLs next to the receiver (the floor-wall corner).
  // Measured (r_max 0.75): 0.87 of pt at 512 samples, 0.91 at 2048 (0.48 at r_max 0.25,
  // where the disc misses most of the floor). pt's standard error of the mean is under 1%.
  // At 2048 samples: within [0.85, 1.02].
  scenes::Scene s = test::lambert_plane(0.8f, 2.0f, 3.0f);
  const int wall = test::add_material(s, glm::vec3(0.6f));
  test::add_quad(s, {-2.0f, 0.0f, -1.0f}, {2.0f, 0.0f, -1.0f}, {2.0f, 2.0f, -1.0f},
                 {-2.0f, 2.0f, -1.0f}, wall);
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction =
      glm::normalize(glm::vec3(0.0f, -1.0f, -0.6f));  // lights the floor, not the wall's front
  sun.intensity = 3.0f;
  s.lights.push_back(sun);
  aim(s.views[0].camera, {0.0f, 1.2f, 2.5f}, {0.0f, -0.1f, -1.0f});
  s.derive();
  const int size = 32;
  const image::Image p = render(s, "pt", size, {"samples_per_frame=512", "max_bounces=2"});
  const double b = mean(p, "indirect.G");
  ASSERT_GT(b, 0.0);
  for (const char* builder : {"rsm_ray_traced=0", "rsm_ray_traced=1"}) {
    const image::Image r =
        render(s, "rsm", size, {"rsm_size=512", "samples=2048", "downsample=1", "blur=0", builder});
    const double a = mean(r, "indirect.G");
    EXPECT_GT(a / b, 0.85) << builder << ": rsm " << a << " pt " << b;
    EXPECT_LT(a / b, 1.02) << builder << ": rsm " << a << " pt " << b;
  }
}

TEST_F(RsmLpvTest, RsmAreaLightAsAPointEmitterAgainstTheOneBouncePathTracer) {
  // An emissive quad above a floor beside a wall, nothing hidden: what remains between rsm and
  // pt's one bounce is the finite sampling (as under the sun, from below) and the area light
  // as a cosine-weighted point emitter at its representative point (which gathers the light's
  // flux at its centre and ignores the extent a near surface sees).
  scenes::Scene s = test::lambert_plane(0.8f, 2.0f, 3.0f);
  const int wall = test::add_material(s, glm::vec3(0.6f));
  test::add_quad(s, {-2.0f, 0.0f, -1.0f}, {2.0f, 0.0f, -1.0f}, {2.0f, 2.0f, -1.0f},
                 {-2.0f, 2.0f, -1.0f}, wall);
  const int light = test::add_material(s, glm::vec3(0.0f), glm::vec3(8.0f));
  test::add_quad(s, {-0.4f, 1.2f, -0.2f}, {0.4f, 1.2f, -0.2f}, {0.4f, 1.2f, 0.4f},
                 {-0.4f, 1.2f, 0.4f}, light);
  aim(s.views[0].camera, {0.0f, 1.0f, 2.5f}, {0.0f, -0.1f, -1.0f});
  s.derive();
  const int size = 32;
  const image::Image p = render(s, "pt", size, {"samples_per_frame=512", "max_bounces=2"});
  const double b = mean(p, "indirect.G");
  ASSERT_GT(b, 0.0);
  // Measured at r_max 1: 0.977 (512 samples), 1.009 (2048), 1.018 (4096): the sampling
  // converges from below towards ~1.02, the point emitter's excess for a 0.8 x 0.6 m light
  // 1.2 m above the floor. pt's standard error of the mean is under 1%. The light's own quad
  // is left out of its maps by either builder.
  for (const char* builder : {"rsm_ray_traced=0", "rsm_ray_traced=1"}) {
    const image::Image r = render(s, "rsm", size,
                                  {"rsm_cube_size=256", "samples=2048", "r_max=1", "downsample=1", "blur=0", builder});
    const double a = mean(r, "indirect.G");
    EXPECT_GT(a / b, 0.95) << builder << ": rsm " << a << " pt " << b;
    EXPECT_LT(a / b, 1.08) << builder << ": rsm " << a << " pt " << b;
  }
}

TEST_F(RsmLpvTest, ClosedEmitterAgainstTheOneBouncePathTracer) {
  // The same floor and wall lit by a closed emissive cube (one mesh, faces outwards): its
  // maps sit at its centre, inside it, and leave the cube out; it emits as an isotropic
  // point of a quarter of its L x A (Cauchy: a convex body's mean projected area is a quarter
  // of its surface). A cube's projected area is 1 to sqrt(3) times a face's, against the
  // model's 1.5, so the one bounce may be off by -13 % to +50 % in any one direction.
  scenes::Scene s = test::lambert_plane(0.8f, 2.0f, 3.0f);
  const int wall = test::add_material(s, glm::vec3(0.6f));
  test::add_quad(s, {-2.0f, 0.0f, -1.0f}, {2.0f, 0.0f, -1.0f}, {2.0f, 2.0f, -1.0f}, {-2.0f, 2.0f, -1.0f}, wall);
  const int light = test::add_material(s, glm::vec3(0.0f), glm::vec3(8.0f));
  const glm::vec3 lo(-0.2f, 1.0f, -0.1f), hi(0.2f, 1.4f, 0.3f);
  auto corner = [&](int i) { return glm::vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z); };
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  scenes::Mesh cube;
  cube.name = "cube";
  cube.object_id = 99;
  cube.material = light;
  for (const auto& f : faces) {
    const uint32_t base = uint32_t(cube.positions.size());
    const glm::vec3 n = glm::normalize(glm::cross(corner(f[1]) - corner(f[0]), corner(f[2]) - corner(f[0])));
    for (int k = 0; k < 4; ++k) cube.positions.push_back(corner(f[k])), cube.normals.push_back(n);
    cube.triangles.push_back({base, base + 1, base + 2});
    cube.triangles.push_back({base, base + 2, base + 3});
  }
  s.meshes.push_back(cube);
  aim(s.views[0].camera, {0.0f, 1.0f, 2.5f}, {0.0f, -0.1f, -1.0f});
  s.derive();
  ASSERT_EQ(s.area_lights.size(), 1u);
  ASSERT_FALSE(s.area_lights[0].flat);
  const int size = 32;
  const image::Image p = render(s, "pt", size, {"samples_per_frame=512", "max_bounces=2"});
  const double b = mean(p, "indirect.G");
  ASSERT_GT(b, 0.0);
  const image::Image r = render(s, "rsm", size, {"rsm_cube_size=256", "samples=2048", "r_max=1", "downsample=1", "blur=0"});
  const double a = mean(r, "indirect.G");
  std::printf("closed emitter: rsm / pt one bounce = %.3f\n", a / b);
  EXPECT_GT(a / b, 0.8) << "rsm " << a << " pt " << b;
  EXPECT_LT(a / b, 1.5) << "rsm " << a << " pt " << b;
  // The other techniques that shadow an area light from its representative point: `ddgi`
  // (BVH rays stopping at the sphere that holds the emitter) within the same model bounds;
  // `vct` and `lpv` with default parameters overshoot this small scene's bounce several times
  // for a flat emitter too (3.1 and 7.4 against pt, measured), so for them only that the
  // closed emitter lights it at all (before, its own faces shadowed it: exactly 0).
  for (const char* t : {"ddgi", "vct", "lpv"}) {
    const double x = mean(render(s, t, size, {}), "indirect.G") / b;
    std::printf("closed emitter: %s / pt one bounce = %.3f\n", t, x);
    EXPECT_GT(x, std::string(t) == "ddgi" ? 0.8 : 0.5) << t;
    if (std::string(t) == "ddgi") EXPECT_LT(x, 1.5) << t;
  }
}

TEST_F(RsmLpvTest, RsmSpotLightAgainstTheOneBouncePathTracer) {
  // A spot light's cube faces carry its cone falloff: the same floor and wall, lit by a spot
  // aimed at the floor in front of the wall; nothing hidden, so only the finite sampling
  // remains (converging from below, as under the sun).
  scenes::Scene s = test::lambert_plane(0.8f, 2.0f, 3.0f);
  const int wall = test::add_material(s, glm::vec3(0.6f));
  test::add_quad(s, {-2.0f, 0.0f, -1.0f}, {2.0f, 0.0f, -1.0f}, {2.0f, 2.0f, -1.0f},
                 {-2.0f, 2.0f, -1.0f}, wall);
  scenes::Light spot;
  spot.type = scenes::LightType::Spot;
  spot.position = {0.3f, 1.5f, 0.8f};
  spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, -0.7f));
  spot.inner_cone = 0.3f;
  spot.outer_cone = 0.6f;
  spot.intensity = 10.0f;
  s.lights.push_back(spot);
  aim(s.views[0].camera, {0.0f, 1.0f, 2.5f}, {0.0f, -0.1f, -1.0f});
  s.derive();
  const int size = 32;
  const image::Image p = render(s, "pt", size, {"samples_per_frame=512", "max_bounces=2"});
  const double b = mean(p, "indirect.G");
  ASSERT_GT(b, 0.0);
  const image::Image r = render(
      s, "rsm", size, {"rsm_cube_size=256", "samples=2048", "r_max=1", "downsample=1", "blur=0"});
  // Measured: 0.90 (512 samples), 0.956 (2048), 0.971 (4096); pt's standard error < 1%.
  const double a = mean(r, "indirect.G");
  EXPECT_GT(a / b, 0.92) << "rsm " << a << " pt " << b;
  EXPECT_LT(a / b, 1.02) << "rsm " << a << " pt " << b;
}

TEST_F(RsmLpvTest, LpvWithoutPropagationIsTheInjectedLightOnly) {
  // A spot lights a small patch of a floor; a wall stands far from it. Injected light stays in
  // the cells of the VPLs (lit floor, half a cell above it); the lookup reads the 8 cells
  // around a point, so without propagation a wall pixel more than 2 cells from the lit patch
  // gets exactly 0, and with propagation light reaches it.
  scenes::Scene s = test::lambert_plane(0.8f, 2.0f, 3.0f);
  const int wall = test::add_material(s, glm::vec3(0.6f));
  test::add_quad(s, {-2.0f, 0.0f, -2.0f}, {2.0f, 0.0f, -2.0f}, {2.0f, 4.0f, -2.0f},
                 {-2.0f, 4.0f, -2.0f}, wall);
  scenes::Light spot;
  spot.type = scenes::LightType::Spot;
  spot.position = {0.0f, 2.0f, 1.5f};
  spot.direction = {0.0f, -1.0f, 0.0f};
  spot.inner_cone = 0.1f;
  spot.outer_cone = 0.15f;  // a patch of radius ~0.3 around (0, 0, 1.5)
  spot.intensity = 50.0f;
  s.lights.push_back(spot);
  aim(s.views[0].camera, {0.0f, 2.0f, 3.5f}, {0.0f, -0.2f, -1.0f});
  s.derive();
  const int size = 24;
  const std::vector<std::string> base = {"shadow_map_size=256", "rsm_cube_size=128", "lpv_grid=16"};
  auto with = [&](const std::string& steps) {
    auto p = base;
    p.push_back("propagation_steps=" + steps);
    return p;
  };
  const image::Image none = render(s, "lpv", size, with("0")),
                     some = render(s, "lpv", size, with("16"));
  // The grid: 16 cells over the scene's 4 m extent (14 + a margin cell per side): 0.286 m.
  // Wall pixels (z = -2) lie >= 3.5 m = 12 cells from the patch.
  const float cell = 4.0f / 14.0f;
  int wall_pixels = 0;
  double propagated = 0.0;
  const auto& cam = s.views[0].camera;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec3 d = cam.ray_direction(x + 0.5f, y + 0.5f, size, size);
      const float t = (-2.0f - cam.position.z) / d.z;
      const glm::vec3 p = cam.position + t * d;
      if (!(t > 0.0f) || p.y < 0.05f || p.y > 4.0f || std::abs(p.x) > 2.0f)
        continue;  // not the wall
      const float ground = (0.0f - cam.position.y) / d.y;
      if (ground > 0.0f && ground < t) continue;  // the floor is in front
      if (glm::length(p - glm::vec3(0.0f, 0.0f, 1.5f)) < 3.0f * cell) continue;
      ++wall_pixels;
      EXPECT_EQ(none.at("indirect.G", x, y), 0.0f) << x << "," << y;
      propagated += some.at("indirect.G", x, y);
    }
  EXPECT_GT(wall_pixels, size * size / 4);
  EXPECT_GT(propagated, 0.0);
  // The floor cannot see its own injected lobe (it points away from it); in the Cornell box,
  // where walls meet within a cell, the injected light alone does reach surfaces.
  const image::Image box = render(test::cornell_box(), "lpv", 16, with("0"));
  EXPECT_GT(mean(box, "indirect.G"), 0.0);
}

TEST_F(RsmLpvTest, LpvGridsThatFollowTheCamera) {
  // The sunroom's camera is inside the room: a scene-sized grid centred on it (1) or half a
  // grid ahead of it (2) holds the room, so there is indirect light, finite; the grid moved,
  // so the result differs from the grid fitted to the scene (0).
  const scenes::Scene s = scenes::load(std::filesystem::path(GIQ_SCENES_DIR) / "sunroom.gltf");
  auto with = [&](int placement) {
    auto p = small("lpv");
    p.push_back("lpv_placement=" + std::to_string(placement));
    return render(s, "lpv", 16, p);
  };
  const double fit = mean(with(0), "indirect.G");
  for (int placement : {1, 2}) {
    const image::Image img = with(placement);
    for (size_t i = 0; i < img.pixel_count(); ++i)
      ASSERT_TRUE(std::isfinite(img.channel("indirect.G")[i]));
    const double m = mean(img, "indirect.G");
    EXPECT_GT(m, 0.0) << placement;
    EXPECT_NE(m, fit) << placement;
  }
}

TEST_F(RsmLpvTest, LpvInjectionIsDeterministic) {
  // Fixed-point atomics make the injected sums independent of the order threads add them in:
  // two renders are bit-identical.
  const scenes::Scene s = test::cornell_box();
  const image::Image a = render(s, "lpv", 16, small("lpv")), b = render(s, "lpv", 16, small("lpv"));
  for (size_t i = 0; i < a.pixel_count(); ++i)
    ASSERT_EQ(a.channel("indirect.G")[i], b.channel("indirect.G")[i]);
}

// A scene's reflective shadow maps from one builder, read back.
struct Maps {
  std::vector<glm::uvec4> surface;  // layer by layer, row by row
  std::vector<glm::vec4> flux;
  std::vector<gpu::GpuRsmLayer> layers;
  uint32_t extent = 0;
};

Maps reflective_shadow_maps(Context& ctx, ShaderCompiler& compiler, const scenes::Scene& s, const char* builder) {
  SceneGpu gpu(ctx, compiler, s);
  const ParameterValues values(ReflectiveShadowMaps::parameters(), {"rsm_size=96", "rsm_cube_size=64", builder});
  const TechniqueCreateInfo ci{ctx, compiler, s, gpu, 16, 16, values};
  ReflectiveShadowMaps rsm(ci);
  EXPECT_EQ(rsm.ray_traced(), std::string(builder) == "rsm_ray_traced=1") << builder;
  GpuTimer timer(ctx);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    rsm.record({cmd, 0, s.views[0].camera, timer, s});
  });
  Maps m;
  m.extent = rsm.extent();
  m.layers = rsm.layers();
  const size_t texels = size_t(m.extent) * m.extent;
  for (uint32_t l = 0; l < rsm.layer_count(); ++l) {
    const std::vector<float> surface = rsm.surface().read_floats(l), flux = rsm.flux().read_floats(l);
    EXPECT_EQ(surface.size(), 4 * texels);
    EXPECT_EQ(flux.size(), 2 * texels);  // four halves a texel
    for (size_t i = 0; i < texels; ++i) {
      glm::uvec4 bits;
      std::memcpy(&bits, &surface[4 * i], sizeof bits);
      uint32_t halves[2];
      std::memcpy(halves, &flux[2 * i], sizeof halves);
      m.surface.push_back(bits);
      m.flux.push_back(glm::vec4(glm::unpackHalf2x16(halves[0]), glm::unpackHalf2x16(halves[1])));
    }
  }
  return m;
}

// The ray through the centre of texel (x, y) of layer l, as shaders/texel_ray.glsl casts it (in double).
struct TexelRay {
  glm::dvec3 o, d;
  double tmax;
};
TexelRay texel_ray(const gpu::GpuRsmLayer& l, double x, double y) {
  const glm::dmat4 m(l.clip_to_world);
  const double size = l.params.y;
  const glm::dvec2 ndc = glm::dvec2(x, y) * (2.0 / size) - 1.0;
  const glm::dvec4 n = m * glm::dvec4(ndc, 0.0, 1.0), f = m * glm::dvec4(ndc, 1.0, 1.0);
  TexelRay r{glm::dvec3(n) / n.w, glm::dvec3(f) / f.w - glm::dvec3(n) / n.w, 0.0};
  r.tmax = glm::length(r.d);
  r.d /= r.tmax;
  return r;
}

// How near the ray through texel (x, y)'s centre passes to an edge of a triangle (not left out
// of the layer), in texels: the distance between the ray and the edge, over the distance
// between neighbouring texels' rays there.
double texels_to_nearest_edge(const FlatGeometry& g, const gpu::GpuRsmLayer& l, glm::uvec2 skip, int x, int y) {
  const TexelRay r = texel_ray(l, x + 0.5, y + 0.5), next = texel_ray(l, x + 1.5, y + 0.5);
  double best = 1e300;
  for (size_t t = 0; t < g.triangles.size(); ++t) {
    if (t - skip.x < skip.y) continue;
    for (int e = 0; e < 3; ++e) {
      const glm::dvec3 a(g.positions[g.triangles[t][e]]), b(g.positions[g.triangles[t][(e + 1) % 3]]);
      // Closest points of the segments o + s d (s in [0, tmax]) and a + u (b - a) (u in [0, 1]).
      const glm::dvec3 ab = b - a, w = r.o - a;
      const double bb = glm::dot(ab, ab), db = glm::dot(r.d, ab), dw = glm::dot(r.d, w), bw = glm::dot(ab, w);
      const double den = bb - db * db;
      double u = den > 1e-30 ? std::clamp((bw - db * dw) / den, 0.0, 1.0) : 0.0;
      const double s = std::clamp(glm::dot(a + u * ab - r.o, r.d), 0.0, r.tmax);
      u = bb > 0.0 ? std::clamp(glm::dot(r.o + s * r.d - a, ab) / bb, 0.0, 1.0) : 0.0;
      const double gap = glm::length(r.o + s * r.d - (a + u * ab));
      const double texel = glm::length(next.o + s * next.d - (r.o + s * r.d));
      best = std::min(best, gap / texel);
    }
  }
  return best;
}

// Both builders take, per texel, the closest surface along the ray through the texel's centre,
// its point where that ray meets the triangle's plane, and shade it with the same code
// (passes/rsm_texel.glsl). So every texel holds the same bits, except where the ray passes
// within the rasteriser's subpixel precision (2^-8 texel on lavapipe) of a triangle's edge:
// the rasteriser snaps vertices to that grid and breaks ties by its own rule, the watertight
// test takes both triangles' edges as inside. Measured: 71, 13, 73 and 55 such texels (the
// scenes below, in order), all within 1e-3 texel of an edge. Every kind of layer: a spot light's cube, the sun's window, the
// Cornell box's area light's cube without the light's own quad; textures, a normal map and an
// alpha mask's cut-outs; scenes from millimetres to a kilometre.
TEST_F(RsmLpvTest, RayTracedMapsHoldTheRasterisedTexels) {
  const scenes::Scene cornell = test::cornell_box_every_light(), textured = test::lit_textured_box();
  ASSERT_EQ(cornell.area_lights.size(), 1u);
  ASSERT_TRUE(textured.features.textures && textured.features.normal_maps && textured.features.alpha_mask);
  // And the Cornell box a thousand times smaller and larger (a millimetre box, a kilometre
  // hall): the edges' distance is measured in texels, so the same bound holds.
  const std::vector<scenes::Scene> scaled = {test::scaled(cornell, 1e-3f), test::scaled(cornell, 1e3f)};
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(ctx->physical_device(), &properties);
  const double snap = std::ldexp(1.0, -int(properties.limits.subPixelPrecisionBits));
  for (const scenes::Scene* s : {&cornell, &textured, &scaled[0], &scaled[1]}) {
    SCOPED_TRACE(s == &cornell    ? "Cornell box, spot, sun, area light"
                 : s == &textured ? "textured box"
                                  : "Cornell box scaled by " + std::to_string(s->bounds.diagonal() / cornell.bounds.diagonal()));
    const Maps a = reflective_shadow_maps(*ctx, *compiler, *s, "rsm_ray_traced=0");
    const Maps b = reflective_shadow_maps(*ctx, *compiler, *s, "rsm_ray_traced=1");
    ASSERT_EQ(a.surface.size(), b.surface.size());
    const FlatGeometry g = flatten(*s);
    const size_t texels = size_t(a.extent) * a.extent;
    size_t hits = 0, differ = 0;
    for (size_t l = 0; l < a.layers.size(); ++l) {
      // An area light's layers leave its own triangles out (emitters: the lights, then the
      // area lights).
      const uint32_t emitter = uint32_t(a.layers[l].params.w);
      glm::uvec2 skip(0u);
      if (emitter >= s->lights.size()) {
        const glm::uvec4 own = own_geometry(*s, g, s->area_lights[emitter - s->lights.size()].mesh);
        skip = glm::uvec2(own.z, own.w);
      }
      for (uint32_t y = 0; y < a.extent; ++y)
        for (uint32_t x = 0; x < a.extent; ++x) {
          const size_t i = l * texels + size_t(y) * a.extent + x;
          for (const glm::vec4& f : {a.flux[i], b.flux[i]}) ASSERT_TRUE(std::isfinite(f.x + f.y + f.z)) << i;
          hits += a.surface[i] != glm::uvec4(0u);
          if (a.surface[i] == b.surface[i] && a.flux[i] == b.flux[i]) continue;
          ++differ;
          EXPECT_LE(texels_to_nearest_edge(g, a.layers[l], skip, int(x), int(y)), snap)
              << "layer " << l << " texel (" << x << ", " << y << ") differs away from every edge";
        }
    }
    EXPECT_GT(hits, a.surface.size() / 4) << "the maps see the scene";
    EXPECT_GT(hits - differ, hits * 99 / 100) << differ << " of " << hits << " texels differ";
  }
}

}  // namespace
}  // namespace giq::realtime
