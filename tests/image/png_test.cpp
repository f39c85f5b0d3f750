// PNG output read back through OpenImageIO (read_image), which decodes 8-bit sRGB to linear.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "giq/base/error.h"
#include "giq/image/io.h"
#include "giq/image/srgb.h"

namespace fs = std::filesystem;
using giq::image::Image;

namespace {

fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("giq_png_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// 8-bit code c decoded with the sRGB curve, computed in double as the reference.
double decoded(int c) {
  double v = c / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

}  // namespace

TEST(Srgb, KnownValues) {
  // IEC 61966-2-1: linear 0.5 encodes to 0.735357; 0.0031308 is the toe's end (12.92 * x).
  EXPECT_NEAR(giq::image::srgb_encode(0.5f), 0.7353569, 1e-6);
  EXPECT_NEAR(giq::image::srgb_encode(0.0031308f), 0.0404500, 1e-6);
  EXPECT_NEAR(giq::image::srgb_decode(0.7353569f), 0.5, 1e-6);
  EXPECT_EQ(giq::image::srgb_encode(-1.0f), 0.0f);
  EXPECT_EQ(giq::image::srgb_encode(7.0f), 1.0f);
}

TEST(Png, RoundTripThroughOiioWithKnownSrgbCodes) {
  fs::path d = fresh_dir("roundtrip");
  Image img(4, 2);
  float* r = img.add_channel("R");
  float* g = img.add_channel("G");
  float* b = img.add_channel("B");
  // linear -> expected 8-bit code: 0 -> 0, 1 -> 255, 0.5 -> round(0.735357*255) = 188,
  // 0.2159 -> round(0.5002*255) = 128 (sRGB mid-grey), 2.0 -> clamped 255, -1 -> 0,
  // 0.001 -> round(12.92*0.001*255) = 3.
  const float lin[8] = {0.0f, 1.0f, 0.5f, 0.2159f, 2.0f, -1.0f, 0.001f, 0.5f};
  const int code[8] = {0, 255, 188, 128, 255, 0, 3, 188};
  for (int i = 0; i < 8; ++i) r[i] = lin[i], g[i] = lin[7 - i], b[i] = 0.5f;
  img.metadata["giq:colour_scale"] = "magma 0..0.25";
  img.metadata["Comment"] = "caf\xc3\xa9";  // UTF-8 -> iTXt
  giq::image::write_png(img, d / "a.png");
  Image back = giq::image::read_image(d / "a.png");
  ASSERT_EQ(back.width(), 4);
  ASSERT_EQ(back.height(), 2);
  for (int i = 0; i < 8; ++i) {
    // OIIO converts 8-bit to float exactly (c/255); the decode is float maths: 1e-6.
    EXPECT_NEAR(back.channel("R")[i], decoded(code[i]), 1e-6) << i;
    EXPECT_NEAR(back.channel("G")[i], decoded(code[7 - i]), 1e-6) << i;
    EXPECT_NEAR(back.channel("B")[i], decoded(188), 1e-6) << i;
  }
  EXPECT_NEAR(decoded(188), 0.50289, 1e-5);  // the published table value for code 188
  EXPECT_EQ(back.metadata["giq:colour_scale"], "magma 0..0.25");
  EXPECT_EQ(back.metadata["Comment"], "caf\xc3\xa9");
}

// OpenImageIO (some 250 shared libraries) is loaded with the first image that is not OpenEXR,
// not when giq starts (oiio_module.cpp). Checked in a fresh process (a re-executed death
// test), whose mapped files say what is loaded.
bool oiio_mapped() {
  std::ifstream maps("/proc/self/maps");
  std::stringstream all;
  all << maps.rdbuf();
  return all.str().find("libOpenImageIO") != std::string::npos;
}

TEST(Png, OpenImageIoLoadsWithTheFirstNonExrImage) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const fs::path d = fresh_dir("lazy");
  Image img(2, 2);
  for (const char* c : {"R", "G", "B"}) img.add_channel(c);
  giq::image::write_png(img, d / "a.png");
  giq::image::write_exr(img, d / "a.exr");
  EXPECT_EXIT(
      {
        if (oiio_mapped()) std::exit(1);
        giq::image::read_image(d / "a.exr");
        if (oiio_mapped()) std::exit(2);
        giq::image::read_image(d / "a.png");
        std::exit(oiio_mapped() ? 0 : 3);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(Png, ExposureLinearModeAndNonFiniteAsMagenta) {
  fs::path d = fresh_dir("exposure");
  Image img(3, 1);
  for (const char* c : {"indirect.R", "indirect.G", "indirect.B"}) img.add_channel(c, 0.25f);
  img.channel("indirect.G")[1] = std::numeric_limits<float>::quiet_NaN();
  img.channel("indirect.B")[2] = std::numeric_limits<float>::infinity();
  giq::image::PngOptions opt;
  opt.layer = "indirect";
  opt.exposure = 1.0f;  // 0.25 * 2 = 0.5 -> code 188
  giq::image::write_png(img, d / "e.png", opt);
  Image back = giq::image::read_image(d / "e.png");
  EXPECT_NEAR(back.channel("R")[0], decoded(188), 1e-6);
  for (int px : {1, 2}) {
    EXPECT_NEAR(back.channel("R")[px], 1.0, 1e-6);
    EXPECT_NEAR(back.channel("G")[px], 0.0, 1e-6);
    EXPECT_NEAR(back.channel("B")[px], 1.0, 1e-6);
  }
  opt.srgb = false;  // clamp linear: 0.5 -> round(127.5) = 128
  giq::image::write_png(img, d / "e.png", opt);
  back = giq::image::read_image(d / "e.png");
  EXPECT_NEAR(back.channel("R")[0], decoded(128), 1e-6);
  EXPECT_THROW(giq::image::write_png(img, d / "x.png"), giq::InputError);  // no beauty layer
}

TEST(Png, TextChunksHaveValidCrc) {
  fs::path d = fresh_dir("crc");
  const unsigned char px[3] = {1, 2, 3};
  giq::image::write_png_rgb8(d / "t.png", 1, 1, 3, px, {{"Software", "giq"}});
  std::ifstream in(d / "t.png", std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  // The tEXt chunk right after IHDR: length 12 ("Software\0giq"), then its CRC-32 over type
  // and data: CRC-32 of "tEXtSoftware\0giq" is 0xcb3979a6 (as zlib's crc32 computes it).
  ASSERT_GT(s.size(), 33u + 12u + 12u);
  EXPECT_EQ(s.substr(33 + 4, 4), "tEXt");
  EXPECT_EQ(s.substr(33 + 8, 12), std::string("Software\0giq", 12));
  EXPECT_EQ(s.substr(33 + 20, 4), std::string("\xcb\x39\x79\xa6", 4));
  EXPECT_THROW(giq::image::write_png_rgb8(d / "u.png", 1, 1, 3, px, {{"", "x"}}), giq::InputError);
  // OIIO (libpng) verifies chunk CRCs when reading; a bad CRC would be an error here.
  Image back = giq::image::read_image(d / "t.png");
  EXPECT_EQ(back.metadata["Software"], "giq");
  EXPECT_NEAR(back.channel("B")[0], decoded(3), 1e-6);
}

TEST(Png, CorruptPngIsInputError) {
  fs::path d = fresh_dir("corrupt");
  { std::ofstream(d / "c.png", std::ios::binary) << "\x89PNG\r\n\x1a\n garbage garbage"; }
  try {
    giq::image::read_image(d / "c.png");
    FAIL() << "corrupt PNG read";
  } catch (const giq::InputError& e) {
    EXPECT_EQ(e.file(), (d / "c.png").string());
  }
}

namespace {

// CRC-32 as PNG chunks use it (ISO 3309, polynomial 0xedb88320), bit by bit.
uint32_t crc32(const std::string& bytes) {
  uint32_t c = 0xffffffffu;
  for (unsigned char b : bytes) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return c ^ 0xffffffffu;
}

std::string be32(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

}  // namespace

TEST(Png, DeclaredSizeIsCheckedBeforeAllocating) {
  fs::path d = fresh_dir("declared");
  const unsigned char px[4 * 4 * 3] = {};
  giq::image::write_png_rgb8(d / "small.png", 4, 4, 3, px);
  std::ifstream in(d / "small.png", std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), {});
  // IHDR's width and height (bytes 16..23) rewritten with a valid CRC: only the declared size
  // is wrong, so only the size check can catch it.
  auto declare = [&](uint32_t w, uint32_t h, const std::string& name) {
    std::string t = s;
    t.replace(16, 8, be32(w) + be32(h));
    t.replace(29, 4, be32(crc32(t.substr(12, 17))));
    std::ofstream(d / name, std::ios::binary) << t;
    try {
      giq::image::read_image(d / name);
    } catch (const giq::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // 40000^2 RGB: 2 x 17.9 GiB of floats while decoding.
  const std::string huge = declare(40000, 40000, "huge.png");
  EXPECT_NE(huge.find("40000x40000 pixels of 6 channels decode to 35.8 GiB"), std::string::npos) << huge;
  // 4000^2 RGB8 rows are 48 MB: deflate (at most 1032:1) needs 46.5 KB for them, not ~80 bytes.
  const std::string deflated = declare(4000, 4000, "deflated.png");
  EXPECT_NE(deflated.find("the 4000x4000 pixels it declares cannot be stored in"), std::string::npos) << deflated;
}
