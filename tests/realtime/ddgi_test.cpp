// `ddgi` (realtime/techniques/ddgi/): the octahedral maps agree with an independent CPU version
// (round trip, and every border texel repeats the texel across its folded edge); probes under
// a uniform environment give the receiver exactly albedo x radiance at every scale and
// brightness (the white furnace); with every light off the indirect layer is exactly 0;
// Chebyshev visibility stops the light leaking through the `leak` scene's wall; relocation
// moves a probe that sits in a wall out through the wall's nearest face, and classification
// switches off probes inside geometry or far from every surface; every built-in scene renders
// finite layers; rendering twice gives the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "giq/realtime/context.h"
#include "giq/realtime/pipeline.h"
#include "giq/realtime/renderer.h"
#include "giq/realtime/resources.h"
#include "giq/scenes/scene.h"
#include "techniques/ddgi/ddgi_shared.h"
#include "octahedral_map.h"
#include "test_scenes.h"

namespace giq::realtime {
namespace {

using test::builtin;
using test::layer;
using test::mean;

using test::oct_decode;
using test::oct_encode;

// Folds a point of the plane outside [-1, 1]^2 back into it: across the edge x = +-1 the map
// continues mirrored in y, across y = +-1 mirrored in x.
glm::vec2 fold(glm::vec2 e) {
  if (e.x > 1.0f) e = {2.0f - e.x, -e.y};
  if (e.x < -1.0f) e = {-2.0f - e.x, -e.y};
  if (e.y > 1.0f) e = {-e.x, 2.0f - e.y};
  if (e.y < -1.0f) e = {-e.x, -2.0f - e.y};
  return e;
}

std::vector<glm::vec3> test_directions() {
  std::vector<glm::vec3> d = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  uint32_t state = 12345u;
  auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
  };
  while (d.size() < 1000) {
    const glm::vec3 v(next(), next(), next());
    const float l = glm::length(v);
    if (l > 0.1f && l <= 1.0f) d.push_back(v / l);
  }
  return d;
}

class DdgiTest : public test::VulkanTest {
 protected:
  image::Image render(const scenes::Scene& s, uint32_t size, std::vector<std::string> params, int frames = 1,
                      const std::string& view = "0") {
    RenderOptions o;
    o.technique = "ddgi";
    o.view = view;
    o.width = o.height = size;
    o.frames = frames;
    o.parameters = std::move(params);
    o.parameters.push_back("shadow_map_size=256");
    return render_last(s, o);
  }
};

TEST_F(DdgiTest, OctahedralMapsAgreeWithTheCpuAndBordersRepeatTheFoldedTexel) {
  const std::vector<glm::vec3> dirs = test_directions();
  const uint32_t n = 6, tile = n + 2;
  const std::string src = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/octahedral.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer In { vec4 dirs[]; };
layout(std430, binding = 1) writeonly buffer Out { vec4 result[]; };
layout(std430, binding = 2) writeonly buffer Border { uvec2 border[]; };
layout(push_constant) uniform Push { uint count; uint n; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < count) {
    vec2 e = oct_encode(dirs[i].xyz);
    result[2 * i] = vec4(e, 0.0, 0.0);
    result[2 * i + 1] = vec4(oct_decode(e), 0.0);
  }
  uint m = n + 2u;
  if (i < m * m) border[i] = oct_border_source(uvec2(i % m, i / m), n);
}
)";
  std::vector<glm::vec4> in;
  for (const auto& d : dirs) in.emplace_back(d, 0.0f);
  Buffer input = Buffer::storage(*ctx, in);
  Buffer output(*ctx, dirs.size() * 2 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  Buffer border(*ctx, tile * tile * 8, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  Pipeline p = Pipeline::compute(*ctx, compiler->compile_source("tests/octahedral.comp", src), {s, s, s}, 8);
  ctx->submit_and_wait([&](VkCommandBuffer cmd) {
    p.bind(cmd);
    p.push_descriptors(cmd, {Descriptor::storage(input), Descriptor::storage(output), Descriptor::storage(border)});
    const uint32_t pc[2] = {uint32_t(dirs.size()), n};
    p.push_constants(cmd, pc, sizeof(pc));
    vkCmdDispatch(cmd, uint32_t((dirs.size() + 63) / 64), 1, 1);
  });
  const auto out = output.download();
  const auto* r = reinterpret_cast<const glm::vec4*>(out.data());
  for (size_t i = 0; i < dirs.size(); ++i) {
    SCOPED_TRACE(i);
    const glm::vec2 e = oct_encode(dirs[i]);
    // A few float roundings of values in [-1, 1]: 1e-6 is ~8 ulps.
    EXPECT_NEAR(r[2 * i].x, e.x, 1e-6f);
    EXPECT_NEAR(r[2 * i].y, e.y, 1e-6f);
    ASSERT_LE(std::max(std::abs(e.x), std::abs(e.y)), 1.0f);
    // The round trip: the map is a bijection of the sphere onto the square.
    EXPECT_LT(glm::length(glm::vec3(r[2 * i + 1]) - dirs[i]), 2e-6f);
    EXPECT_LT(glm::length(oct_decode(e) - dirs[i]), 2e-6f);
  }
  // Each border texel repeats the interior texel at its centre's folded position.
  const auto b = border.download();
  const auto* src_texel = reinterpret_cast<const glm::uvec2*>(b.data());
  int borders = 0;
  for (uint32_t y = 0; y < tile; ++y)
    for (uint32_t x = 0; x < tile; ++x) {
      const glm::uvec2 got = src_texel[y * tile + x];
      const bool interior = x > 0 && y > 0 && x <= n && y <= n;
      if (interior) {
        EXPECT_EQ(got, glm::uvec2(x, y));
        continue;
      }
      ++borders;
      const glm::vec2 centre = (glm::vec2(float(x), float(y)) - 0.5f) / float(n) * 2.0f - 1.0f;
      const glm::vec2 folded = fold(centre);
      const glm::uvec2 want = glm::uvec2(glm::round((folded + 1.0f) * 0.5f * float(n) + 0.5f));
      EXPECT_EQ(got, want) << x << "," << y;
      // And that texel's direction is the folded point's.
      const glm::vec2 source_centre = (glm::vec2(got) - 0.5f) / float(n) * 2.0f - 1.0f;
      EXPECT_LT(glm::length(oct_decode(source_centre) - oct_decode(folded)), 1e-6f);
    }
  EXPECT_EQ(borders, int(4 * n + 4));
}

// The white furnace in the open: a constant environment of radiance L and, to give the scene
// bounds and the camera a receiver, two quads so small that no probe ray hits them. Every ray
// sees L, so every texel of every probe holds E = pi L (the cosine-weighted mean times pi),
// through the gamma encoding, the border copies, the bilinear taps and the weighted mean of 8
// probes; the receiver's indirect light is then albedo / pi x pi L = albedo L, up to float
// rounding (a few ulps per step; 1e-5 relative), at any scale and brightness.
TEST_F(DdgiTest, AUniformEnvironmentGivesEveryReceiverAlbedoTimesItsRadiance) {
  const float albedo = 0.6f;
  for (float scale : {1e-3f, 1.0f, 1e4f})
    for (float radiance : {1e-6f, 1.0f, 1e8f}) {
      SCOPED_TRACE("scale " + std::to_string(scale) + " radiance " + std::to_string(radiance));
      scenes::Scene s;
      const int m = test::add_material(s, glm::vec3(albedo));
      const float q = 1e-3f * scale, lo = -scale, hi = scale;
      test::add_quad(s, {lo - q, lo, lo + q}, {lo + q, lo, lo + q}, {lo + q, lo, lo - q}, {lo - q, lo, lo - q}, m);
      test::add_quad(s, {hi - q, hi, hi + q}, {hi + q, hi, hi + q}, {hi + q, hi, hi - q}, {hi - q, hi, hi - q}, m);
      scenes::Camera camera = scenes::Camera::look_at({lo, lo + q, lo}, {lo, lo, lo}, {0, 0, -1}, 0.6f);
      camera.znear = 0.1f * q;
      s.views.push_back({"top", camera, -1});
      s.environment = glm::vec3(radiance, 0.5f * radiance, 0.25f * radiance);
      s.derive();
      // No probe ray hits a surface, so classification would switch every probe off.
      const image::Image img = render(s, 16, {"probe_grid=2", "rays_per_probe=64", "classification=0"}, 2, "top");
      // Pixels that miss the quad see the environment (their direct layer) and get no
      // indirect light.
      size_t receivers = 0;
      for (size_t i = 0; i < img.pixel_count(); ++i) {
        const bool sky = img.channel("direct.R")[i] > 0.0f;
        receivers += sky ? 0 : 1;
        for (int c = 0; c < 3; ++c) {
          const float want = sky ? 0.0f : albedo * s.environment[c];
          ASSERT_NEAR(img.channel(layer("indirect", c))[i], want, 1e-5f * want) << c << " " << i;
        }
      }
      EXPECT_GT(receivers, img.pixel_count() / 2);
    }
}

// An object alone in space (a closed box under a uniform environment, as most glTF sample
// assets are seen): the volume over its bounds has every probe inside it, so `ddgi` gives no
// indirect light; `probe_padding=1` adds a layer of probes around it, and the box's faces,
// which see only the environment, get albedo x radiance (exact for a convex object; the
// probes' interpolation and visibility make it approximate: measured 0.998 of it, and 0
// without padding; bounded here at 0.6 to 1.2).
TEST_F(DdgiTest, PaddingPutsProbesAroundAnObjectAloneInSpace) {
  const float albedo = 0.6f, radiance = 2.0f;
  scenes::Scene s;
  const int m = test::add_material(s, glm::vec3(albedo));
  const glm::vec3 p[8] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}};
  const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& q : f) test::add_quad(s, p[q[0]], p[q[1]], p[q[2]], p[q[3]], m);
  s.views.push_back({"outside", scenes::Camera::look_at({2.5f, 2.0f, 3.0f}, {0, 0, 0}, {0, 1, 0}, 0.8f), -1});
  s.environment = glm::vec3(radiance);
  s.derive();
  auto box_indirect = [&](int padding) {
    const image::Image img = render(s, 32, {"probe_grid=4", "probe_padding=" + std::to_string(padding)}, 4, "outside");
    double sum = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < img.pixel_count(); ++i)
      if (img.channel("direct.R")[i] == 0.0f) sum += img.channel("indirect.R")[i], ++n;  // the box (not the sky)
    EXPECT_GT(n, img.pixel_count() / 4);
    return sum / double(n);
  };
  const double unpadded = box_indirect(0), padded = box_indirect(1);
  EXPECT_LT(unpadded, 0.05 * albedo * radiance);
  EXPECT_GT(padded, 0.6 * albedo * radiance);
  EXPECT_LT(padded, 1.2 * albedo * radiance);
}

// The white furnace closed: a double-sided sphere of radius R and albedo rho lit by a point
// light of intensity I at its centre. Every point of the wall receives E0 = I / R^2 (within
// the faceting, below), so the wall's radiance is uniform and every probe, wherever it is
// inside, sees the same radiance in every direction: ray hits return rho / pi (E0 + V) with V
// the volume's irradiance of the previous frame (multi-bounce feedback), so each frame's
// estimate is X = rho (E0 + V), exactly, and the blend turns the sequence of X into V_n by the
// schedule of ddgi_blend.comp (running mean, then the hysteresis, in the gamma-encoded space),
// which this test replays in double precision. The receiver's indirect light is
// rho / pi x V_n and its direct light rho / pi x E0, so indirect / direct = V_n / E0.
// Faceting: the UV sphere's flat triangles (64 x 32) lie inside the sphere, their points from
// R cos(a) to R away, a < 4 degrees, so E varies by less than a^2 ~ 0.5 %; 1 % bounds it.
TEST_F(DdgiTest, AClosedSphereLitFromItsCentreConvergesToTheMultiBounceIrradiance) {
  const float rho = 0.2f, radius = 1.0f, intensity = 3.0f;
  scenes::Scene s;
  const int m = test::add_material(s, glm::vec3(rho));
  s.materials[size_t(m)].double_sided = true;
  test::add_sphere(s, glm::vec3(0.0f), radius, 32, 64, m);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = glm::vec3(0.0f);
  l.intensity = intensity;
  s.lights.push_back(l);
  scenes::Camera camera = scenes::Camera::look_at({0, 0, 0}, {1, 0.2f, 0.1f}, {0, 1, 0}, 0.8f);
  camera.znear = 1e-3f;
  s.views.push_back({"inside", camera, -1});
  s.derive();
  const int frames = 40;
  const image::Image img = render(s, 16, {"probe_grid=2", "rays_per_probe=64"}, frames, "inside");
  // ddgi_blend.comp's schedule: no history on frame 0, then min(0.97, 1 - 1/(n + 1)); values
  // blended as E^(1/5). The relative change per frame stays below the thresholds (largest at
  // frame 1: (1 + rho)^(1/5) - 1 = 3.7 % < 10 %), so neither the clamp nor the lower hysteresis
  // applies.
  const double e0 = intensity / (radius * radius);
  double v = 0.0;
  for (int n = 0; n < frames; ++n) {
    const double x = rho * (e0 + (n > 0 ? v : 0.0));
    const double h = std::min(0.97, 1.0 - 1.0 / double(n + 1));
    v = std::pow((1.0 - h) * std::pow(x, 0.2) + h * std::pow(v, 0.2), 5.0);
  }
  for (size_t i = 0; i < img.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double direct = img.channel(layer("direct", c))[i], indirect = img.channel(layer("indirect", c))[i];
      ASSERT_GT(direct, 0.0) << i;
      ASSERT_NEAR(indirect / direct, v / e0, 0.01 * v / e0) << c << " " << i;
    }
  // The converged answer is rho / (1 - rho) = 0.25 of the direct light; 40 frames get within
  // a few per cent of it, from below.
  EXPECT_LT(v / e0, rho / (1.0 - rho));
  EXPECT_GT(v / e0, 0.9 * rho / (1.0 - rho));
}

TEST_F(DdgiTest, WithEveryLightOffIndirectLightIsExactlyZero) {
  const image::Image img = render(test::cornell_with_every_light_off(), 24, {"probe_grid=4", "rays_per_probe=64"}, 3);
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < img.pixel_count(); ++i) ASSERT_EQ(img.channel(layer("indirect", c))[i], 0.0f) << i;
}

// The `leak` scene's view looks at the unlit side of a wall whose other side is lit; the
// reference's indirect light there is close to 0. Probes on the lit side are within a cell of
// the dark receivers: without visibility they light them; the distance moments tell the
// receivers that those probes see the wall before them. Measured at 32^2, 4 frames: the mean
// indirect is about 100 times lower with visibility on; a factor of 10 is required.
TEST_F(DdgiTest, ChebyshevVisibilityStopsLightLeakingThroughAWall) {
  const scenes::Scene scene = builtin("leak");
  const image::Image on = render(scene, 32, {"visibility=1"}, 4);
  const image::Image off = render(scene, 32, {"visibility=0"}, 4);
  const double with = mean(on, "indirect.G"), without = mean(off, "indirect.G");
  EXPECT_GT(without, 0.0);
  EXPECT_LT(with, 0.1 * without) << with << " vs " << without;
}

class DdgiProbeTest : public test::VulkanTest {
 protected:
  // Runs ddgi_probes.comp once on one probe (spacing 1) whose fixed rays report distances
  // t(direction) (negative: a back face); returns the probe's offset and state.
  glm::vec4 classify(const std::function<float(glm::vec3)>& t, bool relocation = true) {
    gpu::GpuDdgiVolume v{};
    v.origin = glm::vec4(0, 0, 0, 1);
    v.counts = glm::uvec4(1, 1, 1, 1);
    v.tiles = glm::uvec4(1, 6, 14, 64);
    v.bias = glm::vec4(0.1f, 0.1f, 2.6f, 5.0f);
    v.switches = glm::uvec4(1, relocation ? 1 : 0, 1, 0);
    std::vector<glm::vec4> rays(64, glm::vec4(0.0f));
    for (uint32_t r = 0; r < GIQ_DDGI_FIXED_RAYS; ++r) rays[r].w = t(fibonacci(r, GIQ_DDGI_FIXED_RAYS));
    Buffer volume = Buffer::storage(*ctx, &v, sizeof(v));
    std::vector<glm::vec4> probe = {glm::vec4(0.0f)};
    Buffer probes = Buffer::storage(*ctx, probe);
    Buffer ray_buffer = Buffer::storage(*ctx, rays);
    std::vector<uint32_t> history = {0, 0, 0, 0};
    Buffer history_buffer = Buffer::storage(*ctx, history);
    const auto s = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    Pipeline p = Pipeline::compute(*ctx, compiler->compile("techniques/ddgi/ddgi_probes.comp"), {s, s, s, s},
                                   sizeof(gpu::DdgiProbePush));
    gpu::DdgiProbePush pc{};
    pc.backface_threshold = 0.25f;
    pc.min_frontface = 0.2f;
    pc.max_offset = 0.45f;
    ctx->submit_and_wait([&](VkCommandBuffer cmd) {
      p.bind(cmd);
      p.push_descriptors(cmd, {Descriptor::storage(volume), Descriptor::storage(probes), Descriptor::storage(ray_buffer),
                               Descriptor::storage(history_buffer)});
      p.push_constants(cmd, pc);
      vkCmdDispatch(cmd, 1, 1, 1);
    });
    const auto out = probes.download();
    glm::vec4 result;
    std::memcpy(&result, out.data(), sizeof(result));
    return result;
  }
  // Keinert et al. 2015, as ddgi_volume.glsl's spherical_fibonacci.
  static glm::vec3 fibonacci(uint32_t i, uint32_t n) {
    const double golden = 1.6180339887498949, pi = 3.14159265358979323846;
    const double phi = 2.0 * pi * (double(i) * (golden - 1.0) - std::floor(double(i) * (golden - 1.0)));
    const double c = 1.0 - (2.0 * i + 1.0) / n, s = std::sqrt(std::max(0.0, 1.0 - c * c));
    return glm::vec3(float(std::cos(phi) * s), float(std::sin(phi) * s), float(c));
  }
};

// Distance from the origin along unit d to the planes x = a (d.x > 0) or x = b (d.x < 0); a
// ray parallel to them goes far.
float to_slab_faces(glm::vec3 d, float a, float b) {
  if (d.x > 1e-6f) return a / d.x;
  if (d.x < -1e-6f) return b / d.x;
  return 1e30f;
}

TEST_F(DdgiProbeTest, AProbeInsideAWallMovesOutThroughItsNearestFaceAndIsSwitchedOff) {
  // The probe sits in a slab x in [-1, 0.1] whose one-sided faces point out of it: every
  // fixed ray hits a back face; the nearest is the face x = 0.1, along the ray with the
  // largest x component.
  const glm::vec4 r = classify([](glm::vec3 d) { return -to_slab_faces(d, 0.1f, -1.0f); });
  EXPECT_GT(r.x, 0.1f) << "the probe must leave the slab through x = 0.1";
  EXPECT_LE(std::abs(r.x), 0.45f);
  EXPECT_LE(std::abs(r.y), 0.45f);
  EXPECT_LE(std::abs(r.z), 0.45f);
  EXPECT_EQ(r.w, float(GIQ_DDGI_INACTIVE)) << "inside geometry this frame";
  // Without relocation it stays where it is.
  const glm::vec4 fixed = classify([](glm::vec3 d) { return -to_slab_faces(d, 0.1f, -1.0f); }, false);
  EXPECT_EQ(glm::vec3(fixed), glm::vec3(0.0f));
}

TEST_F(DdgiProbeTest, ProbesFarFromEverySurfaceAreSwitchedOffAndNearOnesStayOn) {
  // Every ray misses: nothing within the cells around the probe.
  EXPECT_EQ(classify([](glm::vec3) { return 3e38f; }).w, float(GIQ_DDGI_INACTIVE));
  // A floor 0.5 below: the downward rays hit it within a spacing; the probe stays still
  // (0.5 is beyond the distance it keeps from surfaces) and on.
  const glm::vec4 r = classify([](glm::vec3 d) { return d.y < -1e-3f ? -0.5f / d.y : 3e38f; });
  EXPECT_EQ(r.w, float(GIQ_DDGI_ACTIVE));
  EXPECT_EQ(glm::vec3(r), glm::vec3(0.0f));
}

class DdgiSceneTest : public DdgiTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(DdgiSceneTest, RendersFiniteIndirectLightAndComposesTheBeauty) {
  const scenes::Scene scene = builtin(GetParam());
  const image::Image img = render(scene, 32, {"probe_grid=4", "rays_per_probe=96"}, scene.features.animation ? 3 : 2);
  double indirect = 0.0;
  for (const auto& name : img.channel_names())
    for (size_t i = 0; i < img.pixel_count(); ++i) ASSERT_TRUE(std::isfinite(img.channel(name)[i])) << name << " " << i;
  for (int c = 0; c < 3; ++c) {
    const float *beauty = img.channel(layer("", c)), *direct = img.channel(layer("direct", c)),
                *ind = img.channel(layer("indirect", c));
    for (size_t i = 0; i < img.pixel_count(); ++i) {
      ASSERT_GE(ind[i], 0.0f) << i;
      ASSERT_EQ(beauty[i], direct[i] + ind[i]) << i;
      indirect += ind[i];
    }
  }
  EXPECT_GT(indirect, 0.0) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, DdgiSceneTest, ::testing::Values("cornell", "leak", "movinglight", "sunroom", "atrium"));

TEST_F(DdgiTest, RenderingTwiceGivesTheSameBits) {
  const scenes::Scene scene = builtin("cornell");
  const image::Image a = render(scene, 24, {"probe_grid=4", "rays_per_probe=64"}, 3);
  const image::Image b = render(scene, 24, {"probe_grid=4", "rays_per_probe=64"}, 3);
  for (const auto& name : a.channel_names())
    for (size_t i = 0; i < a.pixel_count(); ++i) ASSERT_EQ(a.channel(name)[i], b.channel(name)[i]) << name << i;
}

}  // namespace
}  // namespace giq::realtime
