#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "giq/scenes/texture.h"

namespace giq::scenes {
namespace {

// A 2 x 1 texture: black texel at u in [0, 0.5), white at [0.5, 1).
Texture two_texels(Wrap wrap, Filter filter) {
  Texture t;
  t.assign(2, 1, {glm::vec4(0, 0, 0, 1), glm::vec4(1, 1, 1, 1)});
  t.wrap_s = t.wrap_t = wrap;
  t.filter = filter;
  return t;
}

float red(const Texture& t, float u) { return t.sample({u, 0.5f}).r; }

TEST(Texture, LinearInterpolatesBetweenTexelCentres) {
  const Texture t = two_texels(Wrap::ClampToEdge, Filter::Linear);
  EXPECT_FLOAT_EQ(red(t, 0.25f), 0.0f);  // centre of texel 0
  EXPECT_FLOAT_EQ(red(t, 0.75f), 1.0f);  // centre of texel 1
  EXPECT_FLOAT_EQ(red(t, 0.5f), 0.5f);
  EXPECT_FLOAT_EQ(red(t, 0.375f), 0.25f);
  EXPECT_FLOAT_EQ(t.sample({0.5f, 0.5f}).a, 1.0f);
}

TEST(Texture, WrapModesAtTheEdge) {
  // u = 0 lies half a texel left of texel 0's centre.
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::ClampToEdge, Filter::Linear), 0.0f), 0.0f);       // texel 0 twice
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::Repeat, Filter::Linear), 0.0f), 0.5f);            // texel 1 wraps in
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::MirroredRepeat, Filter::Linear), 0.0f), 0.0f);    // mirror of texel 0
  // u = 1.25: Repeat is u = 0.25 (texel 0); MirroredRepeat reflects to u = 0.75 (texel 1).
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::Repeat, Filter::Linear), 1.25f), 0.0f);
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::MirroredRepeat, Filter::Linear), 1.25f), 1.0f);
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::ClampToEdge, Filter::Linear), 7.0f), 1.0f);
}

TEST(Texture, NearestPicksTheCoveringTexel) {
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::Repeat, Filter::Nearest), 0.49f), 0.0f);
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::Repeat, Filter::Nearest), 0.51f), 1.0f);
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::Repeat, Filter::Nearest), -0.1f), 1.0f);          // texel -1 = texel 1
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::ClampToEdge, Filter::Nearest), -0.1f), 0.0f);
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::MirroredRepeat, Filter::Nearest), -0.1f), 0.0f);  // texel -1 mirrors texel 0
  EXPECT_FLOAT_EQ(red(two_texels(Wrap::MirroredRepeat, Filter::Nearest), -0.6f), 1.0f);  // texel -2 mirrors texel 1
}

TEST(Texture, RowsRunAlongV) {
  Texture t;
  t.assign(1, 2, {glm::vec4(0.25f), glm::vec4(0.75f)});
  t.filter = Filter::Nearest;
  EXPECT_FLOAT_EQ(t.sample({0.5f, 0.1f}).g, 0.25f);  // first row = v 0
  EXPECT_FLOAT_EQ(t.sample({0.5f, 0.9f}).g, 0.75f);
}

// Every wrap mode against OpenGL's definition (4.6 core, 8.14.2, Table 8.20; glTF's sampler
// takes its meaning), on a 5 x 3 texture whose texels hold their own indices: nearest lookups
// at texel centres from -3 to 3 periods and near the 1e6 bound on |uv|, bilinear halfway
// between neighbouring centres.
TEST(Texture, WrapModesFollowOpenGlsDefinition) {
  constexpr int w = 5, h = 3;
  std::vector<glm::vec4> texels;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) texels.emplace_back(float(x), float(y), 0.0f, 1.0f);
  const auto positive_mod = [](int64_t a, int64_t n) { return ((a % n) + n) % n; };
  const auto wrapped = [&](int64_t i, int64_t n, Wrap mode) -> int64_t {
    switch (mode) {
      case Wrap::Repeat: return positive_mod(i, n);
      case Wrap::ClampToEdge: return std::clamp<int64_t>(i, 0, n - 1);
      case Wrap::MirroredRepeat: {
        const int64_t a = positive_mod(i, 2 * n) - n;
        return (n - 1) - (a >= 0 ? a : -(1 + a));
      }
    }
    return -1;
  };
  std::vector<int64_t> indices;
  for (int64_t i = -3 * 2 * w; i <= 3 * 2 * w; ++i) indices.push_back(i);
  for (int64_t k : {1, 2, 3, 7}) indices.push_back(1000000 * w - k), indices.push_back(-1000000 * w + k - 1);
  for (Wrap mode : {Wrap::Repeat, Wrap::ClampToEdge, Wrap::MirroredRepeat}) {
    Texture t;
    t.assign(w, h, texels);
    t.wrap_s = t.wrap_t = mode;
    t.filter = Filter::Nearest;
    for (int64_t i : indices) {
      const glm::vec4 c = t.sample({float((double(i) + 0.5) / w), 0.5f / h});
      EXPECT_EQ(c.x, float(wrapped(i, w, mode))) << "u index " << i << " mode " << int(mode);
      const int64_t j = std::abs(i) < 1000 ? i : (i > 0 ? 1000000 * h - 1 : -1000000 * h);  // within |v| <= 1e6
      EXPECT_EQ(t.sample({0.5f / w, float((double(j) + 0.5) / h)}).y, float(wrapped(j, h, mode))) << "v index " << j << " mode " << int(mode);
    }
    t.filter = Filter::Linear;
    for (int64_t i = -3 * 2 * w; i <= 3 * 2 * w; ++i) {
      // Halfway between centres i and i + 1 along u, on row 1's centre along v; u rounded to
      // float is off by at most |u| 2^-24, a blend weight by w times that.
      const glm::vec4 c = t.sample({float(double(i + 1) / w), 1.5f / h});
      EXPECT_NEAR(c.x, 0.5f * float(wrapped(i, w, mode)) + 0.5f * float(wrapped(i + 1, w, mode)), (w - 1) * 64 * 0x1p-24)
          << "u index " << i << " mode " << int(mode);
      EXPECT_NEAR(c.y, 1.0f, 1e-6f);
    }
  }
}

TEST(Texture, HostileCoordinatesStayInside) {
  const Texture t = two_texels(Wrap::Repeat, Filter::Linear);
  for (float u : {1e30f, -1e30f, INFINITY, -INFINITY, NAN}) {
    const float r = red(t, u);
    EXPECT_GE(r, 0.0f);
    EXPECT_LE(r, 1.0f);
  }
  EXPECT_EQ(Texture{}.sample({0.5f, 0.5f}), glm::vec4(0.0f));
}

}  // namespace
}  // namespace giq::scenes

namespace giq::scenes {
namespace {

TEST(Texture, EightBitTexelsDecodeThroughOneTable) {
  const auto& table = decode_table();
  // Linear half: c / 255 exactly rounded; sRGB half: IEC 61966-2-1 at c / 255.
  for (int c = 0; c < 256; ++c) {
    EXPECT_EQ(table[size_t(c)], float(c) / 255.0f);
    EXPECT_EQ(table[size_t(256 + c)], srgb_to_linear(float(c) / 255.0f));
  }
  EXPECT_EQ(table[256], 0.0f);
  EXPECT_EQ(table[511], 1.0f);
  EXPECT_NEAR(table[256 + 128], 0.2158605f, 1e-6f);  // ((128/255 + 0.055) / 1.055)^2.4
  // One word a texel, R in the low byte: colour channels through the sRGB half, alpha linear.
  Texture t;
  t.width = 1, t.height = 1;
  t.words = std::make_shared<std::vector<uint32_t>>(std::vector<uint32_t>{128u | 64u << 8 | 255u << 16 | 128u << 24});
  t.format = TexelFormat::Rgba8Srgb;
  EXPECT_EQ(t.texel(0, 0), glm::vec4(table[256 + 128], table[256 + 64], 1.0f, table[128]));
  t.format = TexelFormat::Rgba8Unorm;
  EXPECT_EQ(t.texel(0, 0), glm::vec4(table[128], table[64], 1.0f, table[128]));
  // Too few words for the size: not a texture (samples as 0, as the GPU's).
  t.width = 2;
  EXPECT_FALSE(t.valid());
  EXPECT_EQ(t.sample({0.5f, 0.5f}), glm::vec4(0.0f));
}

}  // namespace
}  // namespace giq::scenes
