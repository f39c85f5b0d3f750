// The Sobol sampler: its nets stratify as a (0,m,2)-net should whatever the scramble, every
// point is uniformly distributed over the scrambles, renders with it agree with renders with
// independent numbers, and the variance it reports (from its blocks) is the variance of the
// pixel mean that repeated renders show, where the per-sample variance would overstate it.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <set>
#include <vector>

#include "giq/reference/renderer.h"
#include "giq/reference/sampling.h"
#include "giq/reference/sobol.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

// Every prefix of 2^m points of a block (m <= bits) is a (0,m,2)-net in dimensions 0 and 1:
// each elementary interval [a 2^-i, (a+1) 2^-i) x [b 2^-(m-i), (b+1) 2^-(m-i)) holds exactly
// one point, and each dimension alone has one point per interval of 2^-m.
TEST(Sobol, EveryPrefixOfAScrambledBlockIsANet) {
  for (int bits : {1, 3, 5, 8})
    for (uint32_t seed : {0u, 1u, 0xdeadbeefu, 123456789u}) {
      std::vector<std::array<uint32_t, 4>> pts;
      for (uint32_t k = 0; k < (1u << bits); ++k) pts.push_back(scrambled_sobol4(k, bits, seed));
      for (int m = 0; m <= bits; ++m) {
        const uint32_t n = 1u << m;
        for (int d = 0; d < 4; ++d) {
          std::set<uint32_t> cells;
          for (uint32_t k = 0; k < n; ++k) cells.insert(m == 0 ? 0 : pts[k][size_t(d)] >> (32 - m));
          EXPECT_EQ(cells.size(), size_t(n)) << "dimension " << d << ", 2^" << m << " points, seed " << seed;
        }
        for (int i = 0; i <= m; ++i) {
          std::set<uint64_t> cells;
          for (uint32_t k = 0; k < n; ++k) {
            const uint64_t a = i == 0 ? 0 : pts[k][0] >> (32 - i), b = m - i == 0 ? 0 : pts[k][1] >> (32 - (m - i));
            cells.insert((a << 32) | b);
          }
          EXPECT_EQ(cells.size(), size_t(n)) << "interval shape " << i << "," << m - i << ", seed " << seed;
        }
      }
    }
}

// Over scrambles, a point is uniform in [0,1)^2 in its first two dimensions and in each
// dimension alone: chi-square over 256 cells of 65536 seeds has mean 255 and standard
// deviation sqrt(510) = 22.6; 255 + 6 sd = 390 is not reached by a uniform law.
TEST(Sobol, EachPointIsUniformOverScrambles) {
  constexpr int kSeeds = 1 << 16;
  for (uint32_t k : {0u, 5u, 31u}) {
    std::vector<int> joint(256, 0);
    std::array<std::vector<int>, 4> marginal;
    for (auto& h : marginal) h.assign(256, 0);
    for (uint32_t seed = 0; seed < uint32_t(kSeeds); ++seed) {
      const uint32_t scramble = uint32_t(mix64(seed) >> 32);
      const std::array<uint32_t, 4> x = scrambled_sobol4(k, 5, scramble);
      ++joint[(x[0] >> 28) * 16 + (x[1] >> 28)];
      for (size_t d = 0; d < 4; ++d) ++marginal[d][x[d] >> 24];
    }
    const auto chi2 = [&](const std::vector<int>& h) {
      const double e = double(kSeeds) / double(h.size());
      double c = 0.0;
      for (int v : h) c += (v - e) * (v - e) / e;
      return c;
    };
    EXPECT_LT(chi2(joint), 390.0) << "point " << k << ", dimensions 0 and 1";
    for (size_t d = 0; d < 4; ++d) EXPECT_LT(chi2(marginal[d]), 390.0) << "point " << k << ", dimension " << d;
  }
}

// The glossy scene of the estimator tests, with a point light and a sun added so that every
// light type's sample dimensions are exercised.
scenes::Scene all_lights_scene() {
  scenes::Scene s = test::glossy_scene();
  scenes::Light point;
  point.type = scenes::LightType::Point;
  point.position = {1.5f, 1.5f, 1.0f};
  point.intensity = 2.0f;
  s.lights.push_back(point);
  scenes::Light sun;
  sun.type = scenes::LightType::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.4f));
  sun.intensity = 0.8f;
  s.lights.push_back(sun);
  s.derive();
  return s;
}

Film render(const scenes::Scene& s, Sampler sampler, uint32_t spp, uint64_t seed, int size) {
  RenderSettings rs;
  rs.width = rs.height = size;
  rs.max_bounces = 6;
  rs.sampler = sampler;
  rs.seed = seed;
  Renderer r(s, test::glossy_scene_camera(), rs);
  Film f = r.make_film();
  r.render(f, spp);
  EXPECT_EQ(f.nonfinite_samples(), 0u);
  return f;
}

// Unbiased: the same image as independent numbers give, block by block, within the standard
// errors that each sampler reports (the Sobol render's from 32 blocks).
TEST(Sobol, RendersAgreeWithIndependentSampling) {
  const scenes::Scene s = all_lights_scene();
  const Film sobol = render(s, Sampler::Sobol, 1024, 1, 16);
  const Film indep = render(s, Sampler::Independent, 1024, 2, 16);
  double z_sum = 0.0;
  int blocks = 0;
  for (int y = 0; y < 16; y += 4)
    for (int x = 0; x < 16; x += 4) {
      const test::BlockStat a = test::block_luminance(sobol, x, y, 4, 4);
      const test::BlockStat b = test::block_luminance(indep, x, y, 4, 4);
      EXPECT_NEAR(a.mean, b.mean, 4.5 * std::sqrt(a.variance + b.variance)) << "block " << x << "," << y;
      if (!(a.variance + b.variance > 0.0)) continue;  // unlit in both: no noise to compare
      z_sum += (a.mean - b.mean) / std::sqrt(a.variance + b.variance);
      ++blocks;
    }
  // The blocks' z-scores are independent with standard deviation at most 1 (the block
  // variances bound the luminance's): their mean has a standard error of at most 1/sqrt(n).
  ASSERT_GT(blocks, 8);
  EXPECT_LT(std::abs(z_sum / blocks), 4.0 / std::sqrt(double(blocks)));
}

// The variance of the mean that a render reports against the variance that repeated renders
// with other seeds show, summed over pixels and channels, as a ratio whose standard error is
// taken by the jackknife over renders (Efron & Stein 1981). For the Sobol sampler the ratio
// must be 1 (it is unbiased by construction), and the per-sample estimate, which treats the
// stratified samples as independent, must overstate it.
TEST(Sobol, ReportedVarianceIsTheVarianceOfTheMean) {
  const scenes::Scene s = test::cornell();
  constexpr int kRenders = 48, kSize = 8;
  constexpr uint32_t kSpp = 128;  // 4 blocks of 32
  constexpr size_t kValues = size_t(kSize) * kSize * 3;
  std::vector<std::array<double, kValues>> mean(kRenders), reported(kRenders), per_sample(kRenders);
  for (int r = 0; r < kRenders; ++r) {
    const Film f = render(s, Sampler::Sobol, kSpp, 1000 + uint64_t(r), kSize);
    for (size_t i = 0; i < f.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const PixelAccumulator& p = f.pixels[i];
        ASSERT_EQ(p.variance_dof(), 3u);
        mean[size_t(r)][3 * i + size_t(c)] = p.mean[c];
        reported[size_t(r)][3 * i + size_t(c)] = p.variance_of_mean(c);
        per_sample[size_t(r)][3 * i + size_t(c)] = p.m2[c] / double(kSpp - 1) / double(kSpp);
      }
  }
  // Ratio of the mean reported variance to the empirical variance over renders, leaving out
  // render `skip` (or none).
  const auto ratio = [&](const std::vector<std::array<double, kValues>>& est, int skip) {
    const double n = skip < 0 ? kRenders : kRenders - 1;
    double num = 0.0, den = 0.0;
    for (size_t v = 0; v < kValues; ++v) {
      double m = 0.0, e = 0.0, q = 0.0;
      for (int r = 0; r < kRenders; ++r)
        if (r != skip) m += mean[size_t(r)][v] / n, e += est[size_t(r)][v] / n;
      for (int r = 0; r < kRenders; ++r)
        if (r != skip) q += (mean[size_t(r)][v] - m) * (mean[size_t(r)][v] - m);
      num += e;
      den += q / (n - 1.0);
    }
    return num / den;
  };
  const auto jackknife_se = [&](const std::vector<std::array<double, kValues>>& est) {
    std::vector<double> t(kRenders);
    double tm = 0.0;
    for (int r = 0; r < kRenders; ++r) tm += (t[size_t(r)] = ratio(est, r)) / kRenders;
    double ss = 0.0;
    for (double x : t) ss += (x - tm) * (x - tm);
    return std::sqrt(double(kRenders - 1) / kRenders * ss);
  };
  const double blocks = ratio(reported, -1), blocks_se = jackknife_se(reported);
  const double samples = ratio(per_sample, -1), samples_se = jackknife_se(per_sample);
  std::printf("reported / empirical variance: blocks %.3f (se %.3f), per sample %.3f (se %.3f)\n", blocks, blocks_se, samples,
              samples_se);
  EXPECT_NEAR(blocks, 1.0, 4.0 * blocks_se);
  EXPECT_GT(samples, 1.0 + 4.0 * samples_se);
}

}  // namespace
}  // namespace giq::reference
