// The sampling helpers: the counter-based generator is uniform and decorrelated, the warps
// have the densities they claim, the alias table reproduces its distribution and ray offsets
// leave the surface at every scale.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "giq/reference/alias_table.h"
#include "giq/reference/sampling.h"

namespace giq::reference {
namespace {

// Pearson's chi-square statistic of counts against equal expected counts.
double chi_square(const std::vector<int>& counts, double expected) {
  double x = 0.0;
  for (int c : counts) x += (c - expected) * (c - expected) / expected;
  return x;
}

TEST(Sampling, HashedNumbersAreUniformAlongEveryKeyComponent) {
  // 64 bins, 65536 draws along each key component: chi-square with 63 degrees of freedom has
  // mean 63 and standard deviation ~11.2; 120 is beyond 5 standard deviations.
  for (int axis = 0; axis < 4; ++axis) {
    std::vector<int> bins(64, 0);
    for (uint32_t i = 0; i < 65536; ++i) {
      const float u = axis == 0 ? sample_1d(i, 7, 3, 42) : axis == 1 ? sample_1d(7, i, 3, 42)
                    : axis == 2 ? sample_1d(7, 3, i, 42) : sample_1d(7, 3, 5, i);
      ASSERT_GE(u, 0.0f);
      ASSERT_LT(u, 1.0f);
      ++bins[size_t(u * 64.0f)];
    }
    EXPECT_LT(chi_square(bins, 1024.0), 120.0) << "axis " << axis;
  }
}

TEST(Sampling, ConsecutiveDimensionsAreUncorrelated) {
  // Pearson correlation of (u_d, u_{d+1}) over 65536 samples: standard error 1/256.
  double sx = 0, sy = 0, sxy = 0, sxx = 0, syy = 0;
  const int n = 65536;
  for (int i = 0; i < n; ++i) {
    const double x = sample_1d(uint32_t(i), 0, 4, 1), y = sample_1d(uint32_t(i), 0, 5, 1);
    sx += x, sy += y, sxy += x * y, sxx += x * x, syy += y * y;
  }
  const double cov = sxy / n - sx / n * sy / n;
  const double r = cov / std::sqrt((sxx / n - sx / n * sx / n) * (syy / n - sy / n * sy / n));
  EXPECT_LT(std::abs(r), 5.0 / 256.0);
}

TEST(Sampling, CosineHemisphereHasItsDensity) {
  // E[cos] under pdf cos/pi is 2/3; E[1/pdf] over the hemisphere is its solid angle 2 pi.
  const int n = 200000;
  double mean_cos = 0.0, solid_angle = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 w = square_to_cosine_hemisphere({sample_1d(uint32_t(i), 0, 0, 9), sample_1d(uint32_t(i), 0, 1, 9)});
    ASSERT_NEAR(glm::length(w), 1.0f, 1e-5f);
    ASSERT_GE(w.z, 0.0f);
    mean_cos += w.z / n;
    if (w.z > 1e-3f) solid_angle += 1.0 / cosine_hemisphere_pdf(w.z) / n;
  }
  // Standard deviation of cos under this pdf: sqrt(1/2 - 4/9) = 0.236.
  EXPECT_NEAR(mean_cos, 2.0 / 3.0, 5.0 * 0.236 / std::sqrt(double(n)));
  // 1/pdf has infinite variance near the horizon; the cut at cos 1e-3 removes 1e-6 of 2 pi.
  EXPECT_NEAR(solid_angle, 2.0 * 3.14159265358979, 0.05);
}

TEST(Sampling, QuarterTurnSineAndCosineAreAccurateToFloat) {
  // Over [-pi/4, pi/4] the polynomials must be as good as float sin and cos: within one ulp
  // of the true value (a correctly rounded result is within half an ulp).
  const int n = 1 << 20;
  double worst = 0.0;
  for (int i = 0; i <= n; ++i) {
    const float a = std::clamp(-kPi / 4.0f + (kPi / 2.0f) * float(i) / float(n), -kPi / 4.0f, kPi / 4.0f);
    const SinCos sc = sincos_quarter(a);
    const double s = std::sin(double(a)), c = std::cos(double(a));
    const auto ulp = [](double v) {
      const float f = std::abs(float(v));
      return double(std::nextafter(f, std::numeric_limits<float>::infinity()) - f);
    };
    if (s != 0.0) worst = std::max(worst, std::abs(double(sc.sin) - s) / ulp(s));
    worst = std::max(worst, std::abs(double(sc.cos) - c) / ulp(c));
  }
  EXPECT_LE(worst, 1.0);
}

TEST(Sampling, ConcentricDiskMatchesThePolarMap) {
  // Shirley & Chiu's map with the library's sin and cos, in double: the float map must agree
  // to a few ulps of the unit radius everywhere, including the wedges' borders and the centre.
  const int n = 512;
  double worst = 0.0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const glm::vec2 u(float(i) / float(n), float(j) / float(n));
      const double ox = 2.0 * u.x - 1.0, oy = 2.0 * u.y - 1.0;
      double x = 0.0, y = 0.0;
      if (std::abs(ox) > std::abs(oy)) {
        const double t = 3.14159265358979323846 / 4.0 * (oy / ox);
        x = ox * std::cos(t), y = ox * std::sin(t);
      } else if (oy != 0.0) {
        const double t = 3.14159265358979323846 / 2.0 - 3.14159265358979323846 / 4.0 * (ox / oy);
        x = oy * std::cos(t), y = oy * std::sin(t);
      }
      const glm::vec2 d = square_to_concentric_disk(u);
      worst = std::max({worst, std::abs(d.x - x), std::abs(d.y - y)});
    }
  EXPECT_LE(worst, 4.0 * 0x1p-24);
}

TEST(Sampling, UniformTriangleBarycentricsAreUniform) {
  // The mean of barycentrics of a uniform point is (1/3, 1/3, 1/3); variance of each is 1/18.
  const int n = 100000;
  double b1 = 0.0, b2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec2 b = square_to_triangle_barycentrics({sample_1d(uint32_t(i), 1, 0, 3), sample_1d(uint32_t(i), 1, 1, 3)});
    ASSERT_LE(b.x + b.y, 1.0f + 1e-6f);
    b1 += b.x / n, b2 += b.y / n;
  }
  const double se = std::sqrt(1.0 / 18.0 / n);
  EXPECT_NEAR(b1, 1.0 / 3.0, 5 * se);
  EXPECT_NEAR(b2, 1.0 / 3.0, 5 * se);
}

TEST(Sampling, PowerHeuristicWeightsSumToOne) {
  for (float a : {0.01f, 0.5f, 3.0f, 1e4f})
    for (float b : {0.0f, 0.2f, 7.0f}) EXPECT_NEAR(power_heuristic(a, b) + power_heuristic(b, a), 1.0f, 1e-6f);
  EXPECT_EQ(power_heuristic(0.0f, 0.0f), 0.0f);
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(power_heuristic(1e30f, 1.0f), 1.0f);  // squares overflow: the limit, not NaN
  EXPECT_EQ(power_heuristic(1.0f, 1e30f), 0.0f);
  EXPECT_EQ(power_heuristic(inf, 2.0f), 1.0f);
  EXPECT_EQ(power_heuristic(2.0f, inf), 0.0f);
  EXPECT_NEAR(power_heuristic(3.0f, 1.0f), 0.9f, 1e-6f);
}

TEST(Sampling, FrameIsOrthonormal) {
  for (glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::normalize(glm::vec3(1, -2, 0.001f)), glm::vec3(0, -1, 0)}) {
    const Frame f = Frame::from_normal(n);
    EXPECT_NEAR(glm::dot(f.t, f.b), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(f.t, f.n), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.t), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::length(f.b), 1.0f, 1e-6f);
    const glm::vec3 v(0.3f, -0.2f, 0.9f);
    const glm::vec3 back = f.to_world(f.to_local(v));
    EXPECT_NEAR(glm::length(back - v), 0.0f, 1e-6f);
  }
}

TEST(AliasTable, ReproducesItsDistribution) {
  const std::vector<double> w = {1.0, 0.0, 5.0, 2.5, 0.001, 10.0, 3.0};
  const AliasTable t(w);
  double sum = 0.0;
  for (double x : w) sum += x;
  const int n = 200000;
  std::vector<int> counts(w.size(), 0);
  for (int i = 0; i < n; ++i) {
    const AliasTable::Pick p = t.sample(sample_1d(uint32_t(i), 0, 0, 5), sample_1d(uint32_t(i), 0, 1, 5));
    ++counts[p.index];
    ASSERT_FLOAT_EQ(p.pmf, float(w[p.index] / sum));
  }
  for (size_t i = 0; i < w.size(); ++i) {
    const double p = w[i] / sum;
    EXPECT_NEAR(counts[i] / double(n), p, 5.0 * std::sqrt(p * (1 - p) / n) + 1e-9) << "entry " << i;
  }
  EXPECT_THROW(AliasTable(std::vector<double>{0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(AliasTable(std::vector<double>{1.0, -1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace giq::reference
