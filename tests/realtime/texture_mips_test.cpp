// Mip maps for the G-buffer's primary hits (docs/realtime.md, "Mip maps for primary hits"):
// the levels texture_mips.comp makes against the same box filter in C++, the level a
// G-buffer point reads against the footprint of its pixel, and minified textures rendered as
// the mean the reference converges to.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <iterator>
#include <random>

#include "giq/realtime/scene_gpu.h"
#include "shaders/camera_shared.h"
#include "texture_queries.h"

namespace giq::realtime {
namespace {

using test::TexturesTest;
using test::add_random_texture;
using test::sample_on_gpu;

// The mip levels made on the GPU (shaders/texture_mips.comp) against the same box filter in
// C++: each texel the mean of the 2 x 2 above it (an odd side's last row or column read twice)
// as decoded floats summed in the same order, stored as the nearest byte of the decode table
// (sRGB or linear) or as the float. The same IEEE operations in the same order: the same bits.
// Read back at texel centres of every level (nearest filter, integral lod), and between two
// levels (lod + 0.5: their mean, one rounding of mix()).
TEST_F(TexturesTest, MipLevelsAreBoxMeansInLinearLight) {
  scenes::Scene s = test::lambert_plane(0.5f);
  std::mt19937 rng(23);
  using X = scenes::TexelFormat;
  const struct {
    int w, h;
    X format;
  } kinds[] = {{8, 4, X::Rgba8Srgb}, {5, 3, X::Rgba8Unorm}, {6, 7, X::Rgba32F}, {1, 16, X::Rgba8Srgb}};
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (const auto& k : kinds) {
    if (k.format == X::Rgba32F) {
      test::add_texture(s, k.w, k.h, [&](int, int) { return glm::vec4(u01(rng), u01(rng), u01(rng), u01(rng)); },
                        scenes::Filter::Nearest);
      continue;
    }
    add_random_texture(s, k.w, k.h, k.format, scenes::Filter::Nearest, scenes::Wrap::Repeat, rng);
  }
  s.materials[0].base_color_texture = 0;
  s.derive();
  const auto& table = scenes::decode_table();
  auto nearest_byte = [&](float c, size_t base) {  // texture_mips.comp's encode_byte
    uint32_t lo = 0, hi = 255;
    while (lo < hi) {
      const uint32_t mid = (lo + hi) / 2;
      if (table[base + mid] < c) lo = mid + 1;
      else hi = mid;
    }
    return lo > 0 && c - table[base + lo - 1] <= table[base + lo] - c ? lo - 1 : lo;
  };
  std::vector<glm::vec4> queries, expected;
  for (size_t ti = 0; ti < std::size(kinds); ++ti) {
    const auto& k = kinds[ti];
    const scenes::Texture& tex = s.textures[ti];
    const uint32_t levels = mip_levels(uint32_t(k.w), uint32_t(k.h));
    ASSERT_EQ(levels, uint32_t(std::bit_width(uint32_t(std::max(k.w, k.h)))));
    // Level 0 decoded, then each level from the one above.
    int w = k.w, h = k.h;
    std::vector<glm::vec4> level(size_t(w) * size_t(h));
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) level[size_t(y * w + x)] = tex.texel(x, y);
    std::vector<std::vector<glm::vec4>> chain{level};
    std::vector<glm::ivec2> sizes{{w, h}};
    for (uint32_t l = 1; l < levels; ++l) {
      const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
      std::vector<glm::vec4> next(size_t(nw) * size_t(nh));
      for (int y = 0; y < nh; ++y)
        for (int x = 0; x < nw; ++x) {
          glm::vec4 sum(0.0f);
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx)
              sum += level[size_t(std::min(2 * y + dy, h - 1) * w + std::min(2 * x + dx, w - 1))];
          glm::vec4 mean = sum * 0.25f;
          if (k.format != X::Rgba32F)
            for (int c = 0; c < 4; ++c) {
              const size_t base = k.format == X::Rgba8Srgb && c < 3 ? 256 : 0;
              mean[c] = table[base + nearest_byte(mean[c], base)];
            }
          next[size_t(y * nw + x)] = mean;
        }
      level = next, w = nw, h = nh;
      chain.push_back(level);
      sizes.emplace_back(w, h);
    }
    for (uint32_t l = 0; l < levels; ++l)
      for (int y = 0; y < sizes[l].y; ++y)
        for (int x = 0; x < sizes[l].x; ++x) {
          const glm::vec2 uv((float(x) + 0.5f) / float(sizes[l].x), (float(y) + 0.5f) / float(sizes[l].y));
          queries.emplace_back(uv, float(ti), float(l));
          expected.push_back(chain[l][size_t(y * sizes[l].x + x)]);
          if (l + 1 == levels) continue;
          // Halfway to the next level: the same uv there (nearest), mixed half and half.
          const glm::ivec2 n = sizes[l + 1];
          const glm::vec4 below = chain[l + 1][size_t(std::min(int(uv.y * float(n.y)), n.y - 1) * n.x +
                                                      std::min(int(uv.x * float(n.x)), n.x - 1))];
          queries.emplace_back(uv, float(ti), float(l) + 0.5f);
          expected.push_back(glm::mix(chain[l][size_t(y * sizes[l].x + x)], below, 0.5f));
        }
  }
  const std::vector<glm::vec4> gpu = sample_on_gpu(*ctx, *compiler, s, queries);
  for (size_t i = 0; i < queries.size(); ++i)
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(gpu[i][c], expected[i][c], queries[i].w == std::floor(queries[i].w) ? 0.0f : 1e-7f)
          << "texture " << queries[i].z << " lod " << queries[i].w << " uv " << queries[i].x << "," << queries[i].y;
}

// The mip level a G-buffer point reads: pixel_footprint (shaders/camera.glsl) is the larger
// of the distances from the pixel's point on the plane to its neighbours' (+1 in x, +1 in y),
// here against the same construction in double from the reference's camera rays, for a
// camera looking down at a plane at 50 degrees; texture_lod turns it into log2(footprint x
// texels a metre): 256 texels over 2 m of the plane's uv (4 repeats over 8 m), 128. Float
// rays and a float plane intersection: a relative error of a few 1e-6 in each distance.
TEST_F(TexturesTest, MipLevelIsLog2OfTheFootprintInTexels) {
  scenes::Scene s = test::lambert_plane(1.0f);
  s.meshes.clear();
  s.materials[0].base_color_texture = test::add_texture(s, 256, 256, [](int, int) { return glm::vec4(1.0f); });
  test::add_textured_quad(s, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4}, 0, 4.0f);
  s.derive();
  const scenes::Camera cam = scenes::Camera::look_at({0.3f, 2.0f, 2.2f}, {0.0f, 0.0f, 0.5f}, {0, 1, 0}, 1.0f);
  const int size = 64;
  const std::string src = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "shaders/camera.glsl"
#include "shaders/textures.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = GIQ_SCENE_BINDING_COUNT) readonly buffer Queries { vec2 pixels[]; };
layout(std430, binding = GIQ_SCENE_BINDING_COUNT + 1) writeonly buffer Results { vec2 results[]; };
layout(push_constant) uniform Push { GpuCamera camera; vec2 size; uint count; } pc;
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  vec3 o = camera_ray_origin(pc.camera, pixels[i], pc.size), d = camera_ray_direction(pc.camera, pixels[i], pc.size);
  vec3 p = o + (-o.y / d.y) * d;
  float f = pixel_footprint(pc.camera, pixels[i], pc.size, p, vec3(0.0, 1.0, 0.0));
  results[i] = vec2(f, texture_lod(texture_lod(0u, f), scene_materials[0], GIQ_SLOT_BASE_COLOR, 0));
}
)";
  struct Push {
    gpu::GpuCamera camera;
    glm::vec2 size;
    uint32_t count;
  };
  std::vector<glm::vec2> pixels;
  for (int y = 0; y < size; y += 7)
    for (int x = 0; x < size; x += 5) pixels.emplace_back(float(x) + 0.5f, float(y) + 0.5f);
  const std::vector<glm::vec2> r = test::scene_query<glm::vec2>(
      *ctx, *compiler, s, "tests/footprint_query.comp", src, pixels,
      Push{gpu::make_gpu_camera(cam), glm::vec2(float(size)), uint32_t(pixels.size())});
  auto on_plane = [&](glm::vec2 q) {
    const glm::dvec3 o = cam.ray_origin(q.x, q.y, size, size), d = cam.ray_direction(q.x, q.y, size, size);
    return o + (-o.y / d.y) * d;
  };
  double lo = 1e30, hi = 0.0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const glm::dvec3 p = on_plane(pixels[i]);
    const double f = std::max(glm::length(on_plane(pixels[i] + glm::vec2(1, 0)) - p),
                              glm::length(on_plane(pixels[i] + glm::vec2(0, 1)) - p));
    EXPECT_NEAR(r[i].x, f, 1e-5 * f) << "pixel " << pixels[i].x << "," << pixels[i].y;
    EXPECT_NEAR(r[i].y, std::log2(f * 128.0), 1e-4) << "pixel " << pixels[i].x << "," << pixels[i].y;
    lo = std::min(lo, f), hi = std::max(hi, f);
  }
  EXPECT_GT(hi / lo, 1.5);  // the footprint does vary over the view
}

// A checkerboard of single texels, 7 texels to a pixel: level 0 aliases (each pixel centre
// lands on some texel: values spread over [0, 1]), the mip levels give every pixel the
// checker's mean, 1/2 (exactly: float texels, and every level from 1 on is all 1/2), which is
// what the reference's pixel converges to (the mean over the pixel's area). Lit from straight
// above by a sun of irradiance E, `direct` is rho E / pi, from either G-buffer builder; a
// sampler whose minFilter asks for no mip maps keeps level 0.
TEST_F(TexturesTest, MinifiedTexturesReadTheirMipLevels) {
  scenes::Scene s = test::lambert_plane(1.0f);
  s.meshes.clear();
  const int n = 256;
  s.materials[0].base_color_texture =
      test::add_texture(s, n, n, [](int x, int y) { return glm::vec4(glm::vec3(float((x + y) % 2)), 1.0f); });
  const float half = 4.0f, repeats = 4.0f;  // 128 texels a metre; the view spans 3.46 m at 64 pixels
  test::add_textured_quad(s, {-half, 0, half}, {half, 0, half}, {half, 0, -half}, {-half, 0, -half}, 0, repeats);
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction = {0.0f, -1.0f, 0.0f};
  sun.intensity = 3.0f;
  s.lights.push_back(sun);
  s.derive();
  const float expected = 0.5f * sun.intensity / float(M_PI);
  for (const char* builder : {"gbuffer_ray_traced=0", "gbuffer_ray_traced=1"}) {
    const image::Image img = render(s, "direct", 64, {builder});
    for (size_t i = 0; i < img.pixel_count(); ++i)
      ASSERT_NEAR(img.channel("G")[i], expected, 1e-5f * expected) << builder << " pixel " << i;
  }
  s.textures[0].mip_maps = false;
  const image::Image aliased = render(s, "direct", 64);
  double sum = 0.0, sum2 = 0.0;
  for (size_t i = 0; i < aliased.pixel_count(); ++i) {
    const double v = aliased.channel("G")[i] / expected;
    sum += v, sum2 += v * v;
  }
  const double mean = sum / double(aliased.pixel_count());
  EXPECT_GT(std::sqrt(sum2 / double(aliased.pixel_count()) - mean * mean), 0.2);
}

}  // namespace
}  // namespace giq::realtime
