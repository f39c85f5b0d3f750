// PNG texels decoded with libpng (scenes/src/png_texels.h) are stb_image's, which decodes
// every other image and which they replaced for speed: every colour type, bit depth,
// palette, tRNS and interlacing, on an odd-sized image of random samples.
#include <gtest/gtest.h>
#include <png.h>
#include <stb_image.h>

#include <csetjmp>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "png_texels.h"

namespace giq::scenes {
namespace {

struct Variant {
  int colour, depth;
  bool trns, interlaced;
};

std::string name(const Variant& v) {
  return "colour type " + std::to_string(v.colour) + ", " + std::to_string(v.depth) + " bits" + (v.trns ? ", tRNS" : "") +
         (v.interlaced ? ", Adam7" : "");
}

void on_write(png_structp png, png_bytep data, png_size_t n) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + n);
}

// Rows of random packed samples, written as they are (libpng packs nothing for us).
std::vector<uint8_t> encode(const Variant& v, int w, int h, std::mt19937& rng) {
  const int channels = v.colour == PNG_COLOR_TYPE_GRAY ? 1 : v.colour == PNG_COLOR_TYPE_GRAY_ALPHA ? 2
                       : v.colour == PNG_COLOR_TYPE_RGB ? 3 : v.colour == PNG_COLOR_TYPE_RGB_ALPHA ? 4 : 1;
  const size_t row_bytes = (size_t(w) * size_t(channels) * size_t(v.depth) + 7) / 8;
  std::vector<std::vector<uint8_t>> rows(size_t(h), std::vector<uint8_t>(row_bytes, uint8_t(0)));
  const int palette_size = 1 << std::min(v.depth, 8);
  for (auto& r : rows)
    for (auto& b : r) b = uint8_t(rng());
  if (v.colour == PNG_COLOR_TYPE_PALETTE && v.depth == 8)
    for (auto& r : rows)
      for (auto& b : r) b = uint8_t(b % 200);  // within the palette below
  std::vector<png_bytep> pointers;
  for (auto& r : rows) pointers.push_back(r.data());

  std::vector<uint8_t> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    ADD_FAILURE() << "libpng could not write " << name(v);
    return {};
  }
  png_set_write_fn(png, &out, on_write, nullptr);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), v.depth, v.colour, v.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette(size_t(std::min(palette_size, 200)));
  std::vector<png_byte> alpha(palette.size() / 2);
  for (auto& c : palette) c = {uint8_t(rng()), uint8_t(rng()), uint8_t(rng())};
  for (auto& a : alpha) a = uint8_t(rng());
  png_color_16 key{};
  const uint16_t max = uint16_t((1u << v.depth) - 1);
  key.gray = uint16_t(rows[0][0] >> (8 - std::min(v.depth, 8))) & max;  // the first sample: some pixels match
  key.red = key.green = key.blue = uint16_t(rows[0][0]) & max;
  if (v.colour == PNG_COLOR_TYPE_PALETTE) png_set_PLTE(png, info, palette.data(), int(palette.size()));
  if (v.trns) {
    if (v.colour == PNG_COLOR_TYPE_PALETTE) png_set_tRNS(png, info, alpha.data(), int(alpha.size()), nullptr);
    else png_set_tRNS(png, info, nullptr, 0, &key);
  }
  png_write_info(png, info);
  png_write_image(png, pointers.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return out;
}

TEST(PngTexels, SameTexelsAsStbImageForEveryKindOfPng) {
  std::mt19937 rng(3);
  std::vector<Variant> variants;
  for (bool interlaced : {false, true}) {
    for (int depth : {1, 2, 4, 8, 16})
      for (bool trns : {false, true}) variants.push_back({PNG_COLOR_TYPE_GRAY, depth, trns, interlaced});
    for (int depth : {1, 2, 4, 8})
      for (bool trns : {false, true}) variants.push_back({PNG_COLOR_TYPE_PALETTE, depth, trns, interlaced});
    for (int depth : {8, 16}) {
      for (bool trns : {false, true}) variants.push_back({PNG_COLOR_TYPE_RGB, depth, trns, interlaced});
      variants.push_back({PNG_COLOR_TYPE_GRAY_ALPHA, depth, false, interlaced});
      variants.push_back({PNG_COLOR_TYPE_RGB_ALPHA, depth, false, interlaced});
    }
  }
  const int w = 13, h = 7;
  for (const Variant& v : variants) {
    SCOPED_TRACE(name(v));
    const std::vector<uint8_t> file = encode(v, w, h, rng);
    ASSERT_TRUE(is_png(file));
    const int n = int(file.size());
    int sw = 0, sh = 0, comp = 0;
    if (v.depth == 16) {
      std::unique_ptr<stbi_us, void (*)(void*)> ref(stbi_load_16_from_memory(file.data(), n, &sw, &sh, &comp, 4), stbi_image_free);
      ASSERT_TRUE(ref) << stbi_failure_reason();
      std::vector<uint16_t> got;
      ASSERT_EQ(decode_png(file, w, h, nullptr, &got), "");
      ASSERT_EQ(got.size(), size_t(4 * w * h));
      EXPECT_EQ(std::memcmp(got.data(), ref.get(), got.size() * 2), 0);
    } else {
      ASSERT_FALSE(stbi_is_16_bit_from_memory(file.data(), n));
      std::unique_ptr<stbi_uc, void (*)(void*)> ref(stbi_load_from_memory(file.data(), n, &sw, &sh, &comp, 4), stbi_image_free);
      ASSERT_TRUE(ref) << stbi_failure_reason();
      std::vector<uint32_t> got;
      ASSERT_EQ(decode_png(file, w, h, &got, nullptr), "");
      ASSERT_EQ(got.size(), size_t(w * h));
      for (size_t i = 0; i < got.size(); ++i) {
        const uint8_t* p = ref.get() + 4 * i;
        ASSERT_EQ(got[i], uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24) << "texel " << i;
      }
    }
  }
}

// What libpng refuses comes back as a reason (the loader then tries stb_image), never a crash.
TEST(PngTexels, DamagedFilesAreReportedNotDecoded) {
  std::mt19937 rng(4);
  const std::vector<uint8_t> file = encode({PNG_COLOR_TYPE_RGB, 8, false, false}, 13, 7, rng);
  std::vector<uint32_t> words;
  for (size_t cut : {size_t(8), size_t(33), file.size() / 2, file.size() - 13}) {
    const std::vector<uint8_t> part(file.begin(), file.begin() + std::ptrdiff_t(cut));
    EXPECT_NE(decode_png(part, 13, 7, &words, nullptr), "") << "cut at " << cut;
  }
  EXPECT_NE(decode_png(file, 14, 7, &words, nullptr), "");  // a size the header does not say
  std::vector<uint16_t> sixteen;
  EXPECT_NE(decode_png(file, 13, 7, nullptr, &sixteen), "");  // an 8-bit file read as 16-bit
}

}  // namespace
}  // namespace giq::scenes
