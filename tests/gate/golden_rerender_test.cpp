// Re-renders one committed golden (golden/refs, the Cornell box still) at low spp with
// `giq reference` and checks that it agrees with the committed file within the noise of both
// (per-pixel z-scores from both variance layers). A change to the reference renderer that
// alters the truth (a BSDF, a light's units, the sampling) moves the low-spp render away from
// the golden and fails here, instead of silently re-defining what every gate case is scored
// against. The test also shows it can fail: the same render scaled by 1.05 or 0.97 must be
// rejected.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "gate/noise_agreement.h"
#include "giq/gate/golden_manifest.h"
#include "giq/image/io.h"
#include "support/subprocess.h"

namespace fs = std::filesystem;
using giq::test::Agreement;

namespace {

constexpr const char* kGolden = "cornell_0_f0-0";
// 256 spp: a 64x64 render takes about a second, and with the pooled variance of
// noise_agreement.h a pixel mean of 256 paths gives z-scores close to standard normal
// (measured on the committed golden: mean z^2 0.975, 4 of 12288 values beyond 4 sigma).
constexpr int kSpp = 256;

// The acceptance rule for n compared values (pixel-channels with a variance):
// - |z| > 4: a normal variable exceeds 4 with probability p = 6.33e-5, so the count is about
//   Binomial(n, p) (mean n p, 0.78 for 64x64x3). Pixel means of 256 light paths have heavier
//   tails than the normal (a rare bright path in one of the renders), so the bound allows ten
//   times the Gaussian rate plus five standard deviations of that count (22 for 64x64x3); a
//   renderer 5 % too bright puts about a hundred values beyond 4 sigma.
// - mean z: each z has unit variance; the three channels of a pixel come from the same paths,
//   so at worst they are one sample, and the mean over n/3 independent pixels has standard
//   deviation sqrt(3/n). |mean z| must stay within 5 of those (0.078 for 64x64x3).
// - sum test: per channel, the summed difference over its standard deviation is a standard
//   normal for agreeing renders; |D| <= 5 (a false alarm once in 1.7 million runs).
bool agrees(const Agreement& a, std::string* why) {
  const double n = double(a.with_variance);
  const double expected = 10.0 * 6.33e-5 * n;
  const double max_beyond = expected + 5.0 * std::sqrt(expected) + 1.0;
  const double max_mean = 5.0 * std::sqrt(3.0 / n);
  char buf[320];
  std::snprintf(
      buf, sizeof buf,
      "%zu of %zu values beyond 4 sigma (max %.1f), mean z %.4f (max |%.4f|), mean z^2 %.3f, "
      "sum test R %.2f G %.2f B %.2f (max |5|)",
      a.beyond_4, a.values, max_beyond, a.mean_z, max_mean, a.sum_z2 / n, a.sum_test[0],
      a.sum_test[1], a.sum_test[2]);
  *why = buf;
  bool sums = true;
  for (double d : a.sum_test) sums = sums && std::fabs(d) <= 5.0;
  return n > 0 && double(a.beyond_4) <= max_beyond && std::fabs(a.mean_z) <= max_mean && sums;
}

TEST(GoldenRerender, LowSppRenderAgreesWithCommittedGoldenWithinNoise) {
  const fs::path golden_dir = fs::path(GIQ_SOURCE_DIR) / "golden";
  const giq::gate::Manifest manifest = giq::gate::read_manifest(golden_dir / "refs/manifest.json");
  ASSERT_TRUE(manifest.entries.count(kGolden))
      << "no golden " << kGolden << " in golden/refs/manifest.json";
  const giq::gate::GoldenEntry& e = manifest.entries.at(kGolden);
  const fs::path file = golden_dir / "refs" / kGolden / "frame_0000.exr";
  // The committed file is the one the manifest recorded (else the gate would call it stale).
  ASSERT_EQ(giq::gate::file_hash(file), e.files.at("frame_0000.exr"));
  const auto& s = e.settings;
  const bool golden_half = s.value("half", false);
  const uint64_t seed = s.at("seed").get<uint64_t>();

  const fs::path scratch = fs::path(::testing::TempDir()) / "giq_golden_rerender";
  fs::remove_all(scratch);
  const fs::path low = scratch / "low.exr";
  // Another seed, so the two renders share no sample and their noise is independent; the
  // golden's sampler (independent unless its settings say otherwise), whose samples are i.i.d.
  // as the pooled per-sample variance assumes.
  const std::string cmd = giq::test::shell_quote(GIQ_BINARY) + " reference --scene " +
                          giq::test::shell_quote((golden_dir / e.scene).string()) + " --view " +
                          giq::test::shell_quote(s.at("view").get<std::string>()) + " --width " +
                          std::to_string(s.at("resolution")[0].get<int>()) + " --height " +
                          std::to_string(s.at("resolution")[1].get<int>()) + " --spp " +
                          std::to_string(kSpp) + " --seed " + std::to_string(seed + 1) + " --sampler " +
                          s.value("sampler", std::string("independent")) + " --out " +
                          giq::test::shell_quote(low.string());
  const giq::test::Outcome r = giq::test::run_captured(cmd, scratch);
  ASSERT_EQ(r.exit_code, 0) << cmd << "\n" << r.err;

  const giq::image::Image g = giq::image::read_image(file);
  const giq::image::Image t = giq::image::read_image(low);
  ASSERT_EQ(g.width(), t.width());
  ASSERT_EQ(g.height(), t.height());

  std::string why;
  const Agreement same = giq::test::agreement(g, t, golden_half, false);
  EXPECT_TRUE(agrees(same, &why)) << "the reference renderer no longer reproduces the golden: "
                                  << why;
  std::printf("unchanged: %s\n", why.c_str());
  // A renderer 5 % too bright or 3 % too dark must be caught by the same rule.
  for (const double scale : {1.05, 0.97}) {
    const Agreement changed = giq::test::agreement(g, t, golden_half, false, scale);
    EXPECT_FALSE(agrees(changed, &why)) << "a render scaled by " << scale << " passed: " << why;
    std::printf("scaled by %.2f: %s\n", scale, why.c_str());
  }
  fs::remove_all(scratch);
}

// The rounding term: a float16 golden equal to the truth up to its rounding must agree with
// an exact float32 value even where the render has no noise (a light seen directly).
TEST(GoldenRerender, HalfRoundingAloneIsWithinNoise) {
  giq::image::Image a(2, 1), b(2, 1);
  for (auto* img : {&a, &b}) {
    for (const char* c : {"R", "G", "B", "variance.R", "variance.G", "variance.B"})
      img->add_channel(c, 0.0f);
    img->add_channel("spp", 64.0f);
  }
  const float exact = 17.3f;
  const float rounded = 17.296875f;  // the nearest float16 (ulp 2^-6 between 16 and 32)
  for (const char* c : {"R", "G", "B"}) {
    a.channel(c)[0] = rounded;
    b.channel(c)[0] = exact;
  }
  const Agreement h = giq::test::agreement(a, b, true, false);
  EXPECT_EQ(h.beyond_4, 0u);
  EXPECT_EQ(h.exact, 3u);  // the black pixel: equal with no variance
  const Agreement f = giq::test::agreement(a, b, false, false);
  EXPECT_EQ(f.beyond_4, 3u);  // without the rounding term, a difference with zero variance
}

// The float16 decision (golden/README.md): in every committed golden, the rounding error of
// the beauty's float16 values (uniform within half an ulp, 2^-11 relative at most: variance
// ulp^2 / 12) against the pixel's own noise (its float32 variance). The gate's noise-corrected
// metrics see the golden's noise through means of its variance (the noise floors of
// docs/metrics.md), so rounding matters when it moves those: the test bounds the rounding
// variance summed over the image at 1 % of the summed noise variance, far inside the gate's
// 25 % margin and its factor 3 between a floor and a resolved error. Per pixel, rounding can
// reach a good part of the noise where there is almost none (sunlit or emitter-adjacent
// pixels at high spp; the printed p99 and max); the z-scores above add its variance. An
// all-black golden (leak's room B) has no noise and is exact in float16.
TEST(GoldenRerender, HalfRoundingIsNegligibleAgainstGoldenNoise) {
  const fs::path refs = fs::path(GIQ_SOURCE_DIR) / "golden" / "refs";
  const giq::gate::Manifest manifest = giq::gate::read_manifest(refs / "manifest.json");
  ASSERT_FALSE(manifest.entries.empty());
  for (const auto& [key, e] : manifest.entries) {
    if (!e.settings.value("half", false)) continue;
    std::vector<double> ratios;
    size_t noiseless = 0;
    double rounding_var = 0.0, noise_var = 0.0;
    for (const auto& [name, hash] : e.files) {
      const giq::image::Image g = giq::image::read_image(refs / key / name);
      for (const char* c : {"R", "G", "B"}) {
        const float *v = g.channel(c), *var = g.channel(std::string("variance.") + c);
        for (size_t i = 0; i < g.pixel_count(); ++i) {
          if (v[i] != 0.0f)
            rounding_var += giq::test::half_ulp(v[i]) * giq::test::half_ulp(v[i]) / 12.0;
          noise_var += var[i];
          if (!(var[i] > 0.0f)) {
            noiseless += v[i] != 0.0f;
            continue;
          }
          ratios.push_back(0.5 * giq::test::half_ulp(v[i]) / std::sqrt(double(var[i])));
        }
      }
    }
    if (ratios.empty()) {
      EXPECT_EQ(noiseless, 0u) << key << ": non-zero values without noise and nothing else";
      std::printf("%s: no pixel with noise (all exact zeros in float16)\n", key.c_str());
      continue;
    }
    std::sort(ratios.begin(), ratios.end());
    const double median = ratios[ratios.size() / 2],
                 p99 = ratios[size_t(0.99 * double(ratios.size() - 1))], max = ratios.back();
    std::printf(
        "%s: half rounding (half ulp) / noise sigma: median %.2e, p99 %.2e, max %.2e over %zu "
        "values; "
        "rounding variance / noise variance over the image %.2e; %zu noiseless non-zero\n",
        key.c_str(), median, p99, max, ratios.size(), rounding_var / noise_var, noiseless);
    EXPECT_LE(rounding_var / noise_var, 0.01) << key;
  }
}

}  // namespace
