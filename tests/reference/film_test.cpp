// The film: Welford's accumulator matches the two-pass mean and variance, the image's direct
// and indirect layers add up to the beauty exactly in float arithmetic, and a checkpoint's
// declared size is checked before anything is allocated.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "giq/base/error.h"
#include "giq/base/hash.h"
#include "giq/reference/checkpoint.h"
#include "giq/reference/film.h"
#include "giq/reference/sampling.h"

namespace giq::reference {
namespace {

TEST(Film, WelfordMatchesTwoPassStatistics) {
  PixelAccumulator acc;
  std::vector<double> xs;
  for (uint32_t i = 0; i < 1000; ++i) {
    // Large offset, small spread: where the naive sum-of-squares formula loses its digits.
    const float x = 1e4f + sample_1d(i, 0, 0, 1);
    const float b[3] = {x, x, x}, d[3] = {0, 0, 0};
    acc.add(b, d);
    xs.push_back(double(x));
  }
  double mean = 0.0, ss = 0.0;
  for (double x : xs) mean += x / double(xs.size());
  for (double x : xs) ss += (x - mean) * (x - mean);
  const double var_of_mean = ss / double(xs.size() - 1) / double(xs.size());
  EXPECT_NEAR(acc.mean[0], mean, 1e-9 * mean);
  EXPECT_NEAR(acc.variance_of_mean(0), var_of_mean, 1e-6 * var_of_mean);
  PixelAccumulator one;
  const float b[3] = {1, 2, 3}, d[3] = {1, 1, 1};
  one.add(b, d);
  EXPECT_EQ(one.variance_of_mean(0), 0.0);  // undefined below two samples: reported as 0
}

TEST(Film, DirectPlusIndirectIsBeautyExactly) {
  Film f(256, 256);
  for (size_t i = 0; i < f.pixels.size(); ++i) {
    PixelAccumulator& p = f.pixels[i];
    p.samples = 1 + uint32_t(i % 7);
    for (int c = 0; c < 3; ++c) {
      // Beauty over many binades; direct any fraction of it, including all and nothing.
      const double beauty = std::ldexp(double(sample_1d(uint32_t(i), 0, uint32_t(c), 2)), -int(i % 40));
      const double frac = (i % 11 == 0) ? 1.0 : (i % 13 == 0) ? 0.0 : double(sample_1d(uint32_t(i), 1, uint32_t(c), 2));
      p.mean[c] = beauty;
      p.direct_sum[c] = beauty * frac * p.samples;
    }
  }
  const image::Image img = f.to_image();
  for (const char* l : {"R", "G", "B"}) {
    const float* b = img.channel(l);
    const float* d = img.channel(std::string("direct.") + l);
    const float* r = img.channel(std::string("indirect.") + l);
    for (size_t k = 0; k < img.pixel_count(); ++k) {
      ASSERT_EQ(d[k] + r[k], b[k]) << l << " pixel " << k;
      ASSERT_GE(r[k], 0.0f);
      ASSERT_GE(d[k], 0.0f);
      // The direct part moved by at most a few of its ulps to make the sum exact.
      ASSERT_NEAR(d[k], float(f.pixels[k].direct_sum[l[0] == 'R' ? 0 : l[0] == 'G' ? 1 : 2] / f.pixels[k].samples),
                  4e-7f * b[k] + 1e-30f);
    }
  }
}

TEST(Checkpoint, DeclaredFilmSizeIsCheckedAgainstTheFileBeforeAllocating) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("giq_checkpoint_" + std::to_string(::getpid()) + ".ckpt");
  Film film(2, 2);
  write_checkpoint(p, film, "identity", 1.5);
  ASSERT_TRUE(read_checkpoint(p, "identity").has_value());
  std::string bytes;
  {
    std::ifstream in(p, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // Width and height follow the magic, the identity's length and text and the elapsed time;
  // the checksum is recomputed, so only the size check can refuse the file.
  const size_t at = std::strlen("giq-checkpoint 2\n") + 8 + std::strlen("identity") + 8;
  const int32_t huge = 65536;
  bytes.replace(at, 4, reinterpret_cast<const char*>(&huge), 4);
  bytes.replace(at + 4, 4, reinterpret_cast<const char*>(&huge), 4);
  const uint64_t hash = giq::Hasher().add(bytes.data(), bytes.size() - 8).value();
  bytes.replace(bytes.size() - 8, 8, reinterpret_cast<const char*>(&hash), 8);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
  try {
    read_checkpoint(p, "identity");
    FAIL() << "a 65536x65536 checkpoint of " << bytes.size() << " bytes was read";
  } catch (const giq::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("size does not match a 65536x65536 film"), std::string::npos) << e.what();
  }
  std::filesystem::remove(p);
}

}  // namespace
}  // namespace giq::reference
