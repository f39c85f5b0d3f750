// Convergence: an unbiased Monte Carlo estimator's mean squared error falls as 1/spp, a
// slope of -1 on a log-log plot. Measured on a Cornell-like box built in code (its light
// covers more pixels than the built-in box's, whose few light-edge pixels, with jitter
// between radiance 13 and 0.5, make the mse of a 32x32 image too noisy for a +-0.1 slope
// test at this cost) against a long render; the
// long render's own variance (known from its accumulators) is subtracted from each mse, since
// the two renders are independent: E[(a - b)^2] = mse(a) + var(b).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "giq/reference/renderer.h"
#include "scene_builder.h"

namespace giq::reference {
namespace {

const scenes::Scene& builtin_cornell() {
  static const scenes::Scene s = scenes::load(std::string(GIQ_SCENES_DIR) + "/cornell.gltf");
  return s;
}

struct MseCurve {
  std::vector<double> mse;     // mean over renders, the long render's variance subtracted
  std::vector<double> mse_se;  // standard error of that mean, from the renders' spread
  double slope = 0.0;          // least-squares slope of log mse over log spp
};

// The mse of one render has heavy-tailed noise (the Cornell box's small, bright light):
// average it over independent renders, which are cheap next to the reference. Each spp
// count gets renders of its own: nested counts (the first 8 samples inside the first 16)
// would carry one early outlier, decaying as 1/spp^2, through every point and bend the slope.
MseCurve measure(const scenes::Scene& s, const Film& ref, double ref_var, Sampler sampler, const std::vector<uint32_t>& spps) {
  constexpr int kRenders = 6;
  MseCurve out;
  RenderSettings rs;
  rs.width = rs.height = 32;
  rs.sampler = sampler;
  std::vector<double> xs, ys;
  for (size_t j = 0; j < spps.size(); ++j) {
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < kRenders; ++k) {
      rs.seed = 100 + 16 * j + uint64_t(k);
      Renderer r(s, s.views[0].camera, rs);
      Film f = r.make_film();
      r.render(f, spps[j]);
      EXPECT_EQ(f.nonfinite_samples(), 0u);
      double e = 0.0;
      for (size_t i = 0; i < f.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) {
          const double d = f.pixels[i].mean[c] - ref.pixels[i].mean[c];
          e += d * d;
        }
      e /= double(f.pixels.size() * 3);
      sum += e, sum2 += e * e;
    }
    const double m = sum / kRenders;
    out.mse.push_back(m - ref_var);
    out.mse_se.push_back(std::sqrt(std::max(0.0, sum2 / kRenders - m * m) / (kRenders - 1)));
    EXPECT_GT(out.mse.back(), 0.0);
    xs.push_back(std::log(double(spps[j])));
    ys.push_back(std::log(std::max(1e-300, out.mse.back())));
  }
  double mx = 0, my = 0;
  for (size_t i = 0; i < xs.size(); ++i) mx += xs[i] / double(xs.size()), my += ys[i] / double(ys.size());
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < xs.size(); ++i) sxy += (xs[i] - mx) * (ys[i] - my), sxx += (xs[i] - mx) * (xs[i] - mx);
  out.slope = sxy / sxx;
  return out;
}

// Independent samples: mse falls as 1/spp from the first sample. The Sobol sampler's blocks
// of 32 are independent replicates, so from one block on its mse falls as 1/spp too (within
// a block it falls faster, which is the point of it), and at equal spp it is lower.
TEST(Convergence, MseFallsAsOneOverSpp) {
  const scenes::Scene s = test::cornell();
  RenderSettings rs;
  rs.width = rs.height = 32;
  rs.seed = 1;
  Renderer ref_renderer(s, s.views[0].camera, rs);
  Film ref = ref_renderer.make_film();
  ref_renderer.render(ref, 2048);
  double ref_var = 0.0;
  for (const PixelAccumulator& p : ref.pixels)
    for (int c = 0; c < 3; ++c) ref_var += p.variance_of_mean(c);
  ref_var /= double(ref.pixels.size() * 3);
  EXPECT_EQ(ref.nonfinite_samples(), 0u);

  const MseCurve indep = measure(s, ref, ref_var, Sampler::Independent, {8, 16, 32, 64, 128});
  const MseCurve sobol = measure(s, ref, ref_var, Sampler::Sobol, {32, 64, 128, 256});
  std::printf("slope: independent %.3f, sobol %.3f; mse at 32 spp: independent %.3g (se %.2g), sobol %.3g (se %.2g)\n",
              indep.slope, sobol.slope, indep.mse[2], indep.mse_se[2], sobol.mse[0], sobol.mse_se[0]);
  EXPECT_NEAR(indep.slope, -1.0, 0.1);
  EXPECT_NEAR(sobol.slope, -1.0, 0.1);
  EXPECT_LT(sobol.mse[0] + 4.0 * std::hypot(sobol.mse_se[0], indep.mse_se[2]), indep.mse[2]);
}

}  // namespace
}  // namespace giq::reference

namespace giq::reference {
namespace {

TEST(Convergence, DefaultBounceLimitCutsLessEnergyThanTheNoise) {
  // The same paths (same random numbers) with the default limit and with practically none:
  // they differ only by the energy of paths longer than the default, which must be far below
  // the image's own standard error. On the built-in Cornell box and the code-built one.
  for (const scenes::Scene& s : {builtin_cornell(), test::cornell()}) {
  RenderSettings rs;
  rs.width = rs.height = 16;
  Renderer limited(s, s.views[0].camera, rs);
  ASSERT_EQ(rs.max_bounces, 64);
  rs.max_bounces = 100000;
  Renderer unlimited(s, s.views[0].camera, rs);
  Film a = limited.make_film(), b = unlimited.make_film();
  limited.render(a, 64);
  unlimited.render(b, 64);
  double mean_a = 0.0, mean_b = 0.0, var = 0.0;
  const double n = double(a.pixels.size() * 3);
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      mean_a += a.pixels[i].mean[c] / n;
      mean_b += b.pixels[i].mean[c] / n;
      var += a.pixels[i].variance_of_mean(c) / (n * n);
    }
  EXPECT_GE(mean_b, mean_a);
  EXPECT_LT(mean_b - mean_a, 0.01 * std::sqrt(var));
  EXPECT_GT(var, 0.0);
  }
}

}  // namespace
}  // namespace giq::reference
