// Textures, normal maps and alpha masks in the real-time module without the CPU reference:
// alpha-masked triangles in the BVH's closest- and any-hit queries against the scene
// library's own texture lookup, cut-out shadows of `direct` against the closed form, and the
// rasterised G-buffer against the ray-traced one on a scene using every texture feature.
#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <random>

#include "giq/realtime/ray_query.h"
#include "giq/realtime/scene_gpu.h"
#include "texture_queries.h"

namespace giq::realtime {
namespace {

using test::TexturesTest;
using test::add_random_texture;
using test::sample_on_gpu;

// The GPU lookup against scenes::Texture::sample (the reference's) for every wrap mode and
// filter. Power-of-two sizes: u * size - 0.5 is exact in float as in the reference's double,
// every later step is the same separately rounded float arithmetic (IEEE add and multiply are
// correctly rounded in Vulkan), so the results are the same bits. Other sizes: u * size is
// rounded once, which moves a bilinear weight by at most 2^-24 |u| size = 1.8e-6 here (|u| <= 3,
// size 5) and the result by that times the largest texel difference (1), plus a few ulps.
TEST_F(TexturesTest, LookupsAreTheSceneLibrarysTextureSample) {
  scenes::Scene s = test::lambert_plane(0.5f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  auto random_texel = [&](int, int) { return glm::vec4(u01(rng), u01(rng), u01(rng), u01(rng)); };
  using W = scenes::Wrap;
  using F = scenes::Filter;
  using X = scenes::TexelFormat;
  const struct {
    int w, h;
    F filter;
    W wrap;
    bool exact;
    X format = X::Rgba32F;
  } kinds[] = {
      {8, 4, F::Linear, W::Repeat, true},          {4, 4, F::Linear, W::MirroredRepeat, true},
      {16, 8, F::Linear, W::ClampToEdge, true},    {4, 2, F::Nearest, W::Repeat, true},
      {2, 8, F::Nearest, W::MirroredRepeat, true}, {5, 3, F::Linear, W::Repeat, false},
      {3, 5, F::Linear, W::MirroredRepeat, false},
      // 8-bit texels, decoded through scenes::decode_table on both sides.
      {8, 8, F::Linear, W::Repeat, true, X::Rgba8Srgb}, {4, 8, F::Nearest, W::ClampToEdge, true, X::Rgba8Unorm},
      {16, 4, F::Linear, W::MirroredRepeat, true, X::Rgba8Unorm}};
  for (const auto& k : kinds) {
    if (k.format == X::Rgba32F) {
      test::add_texture(s, k.w, k.h, random_texel, k.filter, k.wrap);
      continue;
    }
    add_random_texture(s, k.w, k.h, k.format, k.filter, k.wrap, rng);
  }
  // A material that uses a texture makes the scene textured (the texels are uploaded).
  s.materials[0].base_color_texture = 0;
  s.derive();
  ASSERT_TRUE(s.features.textures);
  std::uniform_real_distribution<float> uv(-3.0f, 3.0f);
  std::vector<glm::vec4> queries;
  for (int t = 0; t < int(std::size(kinds)); ++t)
    for (int i = 0; i < 2000; ++i) queries.emplace_back(uv(rng), uv(rng), float(t), 0.0f);
  const std::vector<glm::vec4> gpu = sample_on_gpu(*ctx, *compiler, s, queries);
  int exact = 0;
  for (size_t i = 0; i < queries.size(); ++i) {
    const auto& k = kinds[size_t(queries[i].z)];
    const glm::vec4 ref = s.textures[size_t(queries[i].z)].sample(glm::vec2(queries[i]));
    if (k.exact) {
      if (k.filter == F::Nearest) {
        // A uv on a texel edge may fall either way in float; none of 2000 random ones should.
        const float gx = queries[i].x * float(k.w), gy = queries[i].y * float(k.h);
        if (gx == std::floor(gx) || gy == std::floor(gy)) continue;
      }
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(gpu[i][c], ref[c]) << "query " << i << " texture " << queries[i].z;
      ++exact;
    } else {
      for (int c = 0; c < 4; ++c)
        EXPECT_NEAR(gpu[i][c], ref[c], 4e-6f) << "query " << i << " texture " << queries[i].z;
    }
  }
  EXPECT_GT(exact, 15000);
}

// Texel packing: scene order kept, no chunk over its size, every texture in one chunk, a new
// chunk only when the next texture does not fit, too large textures marked.
TEST(TexelPacking, NextFitInSceneOrder) {
  const TexelPacking p = pack_texels({6, 0, 3, 2, 9, 5, 11, 4}, 10);
  EXPECT_EQ(p.chunk, (std::vector<int>{0, 0, 0, 1, 2, 3, -1, 3}));
  EXPECT_EQ(p.first_word, (std::vector<uint64_t>{0, 0, 6, 0, 0, 0, 0, 5}));
  EXPECT_EQ(p.chunk_words, (std::vector<uint64_t>{9, 2, 9, 9}));
  const TexelPacking empty = pack_texels({0, 0}, 10);
  EXPECT_EQ(empty.chunk, (std::vector<int>{0, 0}));
  EXPECT_EQ(empty.chunk_words, (std::vector<uint64_t>{0}));
}

// Ten 2048² 8-bit textures (160 MiB, beyond lavapipe's 128 MiB maxStorageBufferRange, which
// used to bound a scene's texels) sampled on the GPU: the same bits as the scene library's
// lookup in every texture, the last ones included (read past 128 MiB).
TEST_F(TexturesTest, TexturesBeyondTheLargestStorageBufferAreSampled) {
  scenes::Scene s = test::lambert_plane(0.5f);
  std::mt19937 rng(17);
  const int kCount = 10, kSize = 2048;
  for (int i = 0; i < kCount; ++i)
    add_random_texture(s, kSize, kSize, i % 2 ? scenes::TexelFormat::Rgba8Srgb : scenes::TexelFormat::Rgba8Unorm,
                       scenes::Filter::Linear, scenes::Wrap::Repeat, rng);
  s.materials[0].base_color_texture = 0;
  s.derive();
  ASSERT_GT(uint64_t(kCount) * kSize * kSize * 4, uint64_t(128) << 20);
  std::uniform_real_distribution<float> uv(0.0f, 1.0f);
  std::vector<glm::vec4> queries;
  for (int t = 0; t < kCount; ++t)
    for (int i = 0; i < 500; ++i) queries.emplace_back(uv(rng), uv(rng), float(t), 0.0f);
  const std::vector<glm::vec4> gpu = sample_on_gpu(*ctx, *compiler, s, queries);
  for (size_t i = 0; i < queries.size(); ++i) {
    const glm::vec4 ref = s.textures[size_t(queries[i].z)].sample(glm::vec2(queries[i]));
    for (int c = 0; c < 4; ++c) ASSERT_EQ(gpu[i][c], ref[c]) << "query " << i << " texture " << queries[i].z;
  }
}

// An alpha-masked square [-h, h]^2 in the plane z = 0 facing +z (TEXCOORD_0 u along x, v
// along -y, `uv_scale` repeats) in front of an opaque wall at z = -1.
scenes::Scene masked_square(scenes::Filter filter, float uv_scale, float h) {
  scenes::Scene s;
  const int mask = test::add_material(s, glm::vec3(0.8f));
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  s.materials[mask].alpha_mode = scenes::AlphaMode::Mask;
  s.materials[mask].alpha_cutoff = 0.5f;
  s.materials[mask].base_color.a = 0.9f;  // the factor multiplies the texture's alpha
  s.materials[mask].base_color_texture = test::add_texture(
      s, 5, 3, [&](int, int) { return glm::vec4(1.0f, 1.0f, 1.0f, u(rng)); }, filter);
  test::add_textured_quad(s, {-h, h, 0}, {h, h, 0}, {h, -h, 0}, {-h, -h, 0}, mask, uv_scale);
  const int wall = test::add_material(s, glm::vec3(0.5f));
  test::add_quad(s, {-4, -4, -1}, {4, -4, -1}, {4, 4, -1}, {-4, 4, -1}, wall);
  s.views.push_back({"front", scenes::Camera::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 1.0f), -1});
  s.derive();
  return s;
}

// Closest and any hit through alpha-masked triangles: a ray stops at the square exactly where
// scenes::Texture::sample (the reference's lookup) gives alpha >= cutoff. Rays whose alpha is
// within 1e-3 of the cutoff are left out: the GPU's barycentrics differ from the exact ones
// in the last bits, which moves alpha by far less than that (texel gradients are below 1 per
// texel, 5 texels per unit of u).
TEST_F(TexturesTest, BvhSkipsCutOutsInClosestAndAnyHitQueries) {
  for (const auto filter : {scenes::Filter::Nearest, scenes::Filter::Linear}) {
    const float h = 0.8f, k = 1.7f;  // 1.7 repeats: the repeat wrap is exercised
    const scenes::Scene s = masked_square(filter, k, h);
    ASSERT_TRUE(s.features.alpha_mask);
    SceneGpu gpu(*ctx, *compiler, s);
    RayQuery query(*ctx, *compiler, gpu);
    const scenes::Texture& tex = s.textures[0];
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<QueryRay> rays;
    std::vector<int> expect;  // 1 = the square, 0 = the wall, -1 = too close to call
    for (int i = 0; i < 4000; ++i) {
      const glm::vec3 o(u(rng), u(rng), 1.0f);
      const glm::vec3 d = glm::normalize(glm::vec3(0.3f * u(rng), 0.3f * u(rng), -1.0f));
      const glm::vec3 q = o + (-o.z / d.z) * d;  // on the square's plane
      int e = 0;
      if (std::abs(q.x) < h && std::abs(q.y) < h) {
        const glm::vec2 uv(k * (q.x + h) / (2.0f * h), k * (h - q.y) / (2.0f * h));
        const float alpha = 0.9f * tex.sample(uv).a;
        const float gx = uv.x * float(tex.width), gy = uv.y * float(tex.height);
        const bool edge =
            std::abs(gx - std::round(gx)) < 1e-3f || std::abs(gy - std::round(gy)) < 1e-3f;
        e = std::abs(alpha - 0.5f) < 1e-3f || (filter == scenes::Filter::Nearest && edge)
                ? -1
                : alpha >= 0.5f;
        if (std::abs(std::abs(q.x) - h) < 1e-4f || std::abs(std::abs(q.y) - h) < 1e-4f) e = -1;
      }
      expect.push_back(e);
      rays.push_back({glm::vec4(o, 1e30f), glm::vec4(d, 0.0f)});
      rays.push_back({glm::vec4(o, 1e30f), glm::vec4(d, 1.0f)});  // any hit, unbounded
      rays.push_back(
          {glm::vec4(o, 1.5f / -d.z), glm::vec4(d, 1.0f)});  // any hit ending between the two
    }
    const auto hits = query.trace(rays);
    int square = 0, wall = 0;
    for (size_t i = 0; i < expect.size(); ++i) {
      if (expect[i] < 0) continue;
      const QueryHit& closest = hits[3 * i];
      const bool on_square = closest.triangle < 2u;  // the square's two triangles come first
      ASSERT_NE(closest.triangle, 0xffffffffu) << i;
      EXPECT_EQ(on_square, expect[i] == 1) << "ray " << i << " filter " << int(filter);
      EXPECT_NE(hits[3 * i + 1].triangle, 0xffffffffu) << i;  // the wall is opaque
      EXPECT_EQ(hits[3 * i + 2].triangle != 0xffffffffu, expect[i] == 1) << "any hit, ray " << i;
      (on_square ? square : wall)++;
    }
    // Both outcomes occur often: the test cannot pass by hitting (or missing) everything.
    EXPECT_GT(square, 400);
    EXPECT_GT(wall, 400);
  }
}

// BLEND in the BVH: a ray meets a square of alpha 0.3 with probability 0.3, decided by a hash
// of the ray, so the closest and any-hit queries of one ray decide alike, and over 4000
// random rays the fraction that stop at the square is 0.3 within 4 binomial standard errors.
TEST_F(TexturesTest, BvhPassesBlendSurfacesWithProbabilityOneMinusAlpha) {
  scenes::Scene s;
  const int card = test::add_material(s, glm::vec3(0.8f));
  s.materials[card].alpha_mode = scenes::AlphaMode::Blend;
  s.materials[card].base_color.a = 0.3f;
  test::add_quad(s, {-4, 4, 0}, {4, 4, 0}, {4, -4, 0}, {-4, -4, 0}, card);
  const int wall = test::add_material(s, glm::vec3(0.5f));
  test::add_quad(s, {-4, -4, -1}, {4, -4, -1}, {4, 4, -1}, {-4, 4, -1}, wall);
  s.derive();
  ASSERT_TRUE(s.features.alpha_mask);
  SceneGpu gpu(*ctx, *compiler, s);
  RayQuery query(*ctx, *compiler, gpu);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<QueryRay> rays;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 o(u(rng), u(rng), 1.0f);
    const glm::vec3 d = glm::normalize(glm::vec3(0.3f * u(rng), 0.3f * u(rng), -1.0f));
    rays.push_back({glm::vec4(o, 1e30f), glm::vec4(d, 0.0f)});
    rays.push_back({glm::vec4(o, 1.5f / -d.z), glm::vec4(d, 1.0f)});  // any hit, ending before the wall
  }
  const auto hits = query.trace(rays);
  int on_card = 0;
  for (int i = 0; i < n; ++i) {
    ASSERT_NE(hits[2 * i].triangle, 0xffffffffu) << i;  // the wall is opaque
    const bool card_hit = hits[2 * i].triangle < 2u;
    EXPECT_EQ(hits[2 * i + 1].triangle != 0xffffffffu, card_hit) << "ray " << i;
    on_card += card_hit;
  }
  EXPECT_NEAR(double(on_card) / n, 0.3, 4.0 * std::sqrt(0.3 * 0.7 / n));
}

// BLEND in the G-buffer, from either builder: an emissive square of alpha 0.3 over a black
// wall covers a fraction 0.3 of the pixels that see it (a screen-door dither for the
// rasteriser, the ray hash for the ray caster), within 4 binomial standard errors.
TEST_F(TexturesTest, BlendSurfacesAreDitheredInTheGBuffer) {
  scenes::Scene s;
  const int card = test::add_material(s, glm::vec3(0.0f), glm::vec3(1.0f));
  s.materials[card].alpha_mode = scenes::AlphaMode::Blend;
  s.materials[card].base_color.a = 0.3f;
  test::add_quad(s, {-4, -4, 0}, {4, -4, 0}, {4, 4, 0}, {-4, 4, 0}, card);  // facing the camera
  const int wall = test::add_material(s, glm::vec3(0.0f));
  test::add_quad(s, {-4, -4, -1}, {4, -4, -1}, {4, 4, -1}, {-4, 4, -1}, wall);
  s.views.push_back({"front", scenes::Camera::look_at({0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 1.0f), -1});
  s.derive();
  const uint32_t size = 64;
  for (const char* builder : {"gbuffer_ray_traced=0", "gbuffer_ray_traced=1"}) {
    const image::Image img = render(s, "direct", size, {builder});
    int lit = 0;
    for (size_t i = 0; i < img.pixel_count(); ++i) lit += img.channel("G")[i] > 0.5f;
    const double n = double(img.pixel_count());
    EXPECT_NEAR(lit / n, 0.3, 4.0 * std::sqrt(0.3 * 0.7 / n)) << builder;
  }
}

// A masked grating between a point light and a Lambertian plane: under its cut-outs the plane
// is lit exactly as the closed form says, under its bars it is black. `direct` sees the plane
// through the cut-outs (G-buffer discard) and its shadow maps let light through them (shadow
// pass discard). Points whose shadow ray crosses the grating within 0.03 of a bar's edge (6
// shadow-map texels: PCF radius, normal offset and bias) are left out.
TEST_F(TexturesTest, AlphaMaskedGratingCastsCutOutShadows) {
  const float rho = 0.5f;
  scenes::Scene s = test::lambert_plane(rho);
  const int mask = test::add_material(s, glm::vec3(0.6f));
  s.materials[mask].alpha_mode = scenes::AlphaMode::Mask;
  s.materials[mask].alpha_cutoff = 0.5f;
  s.materials[mask].double_sided = true;
  const int bars = 6;
  s.materials[mask].base_color_texture = test::add_texture(
      s, bars, 1, [](int x, int) { return glm::vec4(1.0f, 1.0f, 1.0f, x % 2 ? 0.0f : 1.0f); },
      scenes::Filter::Nearest);
  const float h = 0.6f, y0 = 0.8f;
  test::add_textured_quad(s, {-h, y0, h}, {h, y0, h}, {h, y0, -h}, {-h, y0, -h}, mask);
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.05f, 2.0f, 0.0f};
  l.intensity = 10.0f;
  s.lights.push_back(l);
  s.derive();
  ASSERT_TRUE(s.features.alpha_mask && s.features.textures);
  const int size = 64;
  const image::Image img = render(s, "direct", size, {"shadow_map_size=512"});
  const auto& cam = s.views[0].camera;
  // Column of the grating at x, or -1 outside it; `edge`: within `margin` of a bar's edge.
  auto column = [&](glm::vec3 q, float margin, bool& edge) {
    const float g = (q.x + h) / (2.0f * h) * float(bars);
    edge = std::abs(g - std::round(g)) * (2.0f * h / float(bars)) < margin ||
           std::abs(std::abs(q.z) - h) < margin;
    return std::abs(q.x) < h && std::abs(q.z) < h ? int(std::floor(g)) : -1;
  };
  int lit_through = 0, shadowed = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const glm::vec3 d = cam.ray_direction(x + 0.5f, y + 0.5f, size, size);
      bool edge = false;
      const glm::vec3 qc =
          cam.position + ((y0 - cam.position.y) / d.y) * d;  // on the grating's plane
      const int cc = column(qc, 1e-3f, edge);
      if (edge || (cc >= 0 && cc % 2 == 0)) continue;  // the camera sees a bar (or an edge)
      const glm::vec3 p = cam.position + (-cam.position.y / d.y) * d;
      const glm::vec3 to = l.position - p;
      const float dist = glm::length(to);
      const glm::vec3 q = p + ((y0 - p.y) / to.y) * to;  // where the shadow ray crosses
      const int c = column(q, 0.03f, edge);
      if (edge) continue;
      const bool blocked = c >= 0 && c % 2 == 0;
      const float expected =
          blocked ? 0.0f : rho / float(M_PI) * l.intensity * (to.y / dist) / (dist * dist);
      // float32 evaluation of the same formula: a few ulps of relative error.
      EXPECT_NEAR(img.at("G", x, y), expected, 1e-4f * expected + 1e-7f)
          << x << "," << y << (blocked ? " under a bar" : " lit");
      if (c >= 0) (blocked ? shadowed : lit_through)++;
    }
  EXPECT_GT(lit_through, 100);
  EXPECT_GT(shadowed, 100);
}

// The two G-buffers (rasterised, ray-traced) on a scene with every texture feature give the
// same `direct` image except where a pixel centre lies on a triangle edge (tie-breaking rules
// differ) or on a cut-out's edge: at most 1% of pixels.
TEST_F(TexturesTest, RasterisedAndRayTracedGBuffersAgree) {
  scenes::Scene s = test::textured_box();
  scenes::Light l;
  l.type = scenes::LightType::Point;
  l.position = {0.3f, 0.5f, 0.2f};
  l.intensity = 2.0f;
  s.lights.push_back(l);
  s.derive();
  ASSERT_TRUE(s.features.textures && s.features.normal_maps && s.features.alpha_mask);
  const int size = 48;
  const image::Image a = render(s, "direct", size, {"shadow_map_size=256"});
  const image::Image b = render(s, "direct", size, {"shadow_map_size=256", "gbuffer_ray_traced=1"});
  int differ = 0;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    const float x = a.channel("G")[i], y = b.channel("G")[i];
    ASSERT_TRUE(std::isfinite(x) && std::isfinite(y)) << i;
    differ += std::abs(x - y) > 1e-4f * std::max(x, y) + 1e-7f;
  }
  EXPECT_LE(differ, int(a.pixel_count() / 100))
      << differ << " of " << a.pixel_count() << " pixels differ";
}

}  // namespace
}  // namespace giq::realtime
