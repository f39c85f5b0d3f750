#include <gtest/gtest.h>

#include <memory>

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
