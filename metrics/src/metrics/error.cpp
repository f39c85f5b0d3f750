#include "giq/metrics/error.h"

#include <cmath>
#include <limits>
#include <numbers>

#include "parallel.h"

namespace giq::metrics {
namespace {

struct Sums {
  size_t valid = 0, test_bad = 0, ref_bad = 0;
  double se = 0, ae = 0, rel = 0, smape = 0, se_clamped = 0;
  double var = 0, var_rel = 0, sd = 0, sd_smape = 0;
  Sums& operator+=(const Sums& o) {
    valid += o.valid, test_bad += o.test_bad, ref_bad += o.ref_bad;
    se += o.se, ae += o.ae, rel += o.rel, smape += o.smape, se_clamped += o.se_clamped;
    var += o.var, var_rel += o.var_rel, sd += o.sd, sd_smape += o.sd_smape;
    return *this;
  }
};

double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

}  // namespace

ErrorStats error_stats(const RgbLayer& ref, const RgbLayer& test, const RgbLayer* variance) {
  const int w = ref.width;
  const Sums s = detail::reduce_rows<Sums>(ref.height, [&](int y0, int y1, Sums& acc) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i) {
      // A variance is finite and not negative, or the pixel's reference cannot be trusted: it
      // is left out like a non-finite one (and counted with them).
      const bool ref_ok = ref.finite(i) && (!variance || (variance->finite(i) && variance->c[0][i] >= 0.0f &&
                                                          variance->c[1][i] >= 0.0f && variance->c[2][i] >= 0.0f));
      if (!test.finite(i)) {
        ++acc.test_bad;
        if (!ref_ok) ++acc.ref_bad;
        continue;
      }
      if (!ref_ok) {
        ++acc.ref_bad;
        continue;
      }
      ++acc.valid;
      for (int k = 0; k < 3; ++k) {
        const double r = ref.c[k][i], t = test.c[k][i], d = t - r;
        acc.se += d * d;
        acc.ae += std::abs(d);
        acc.rel += d * d / (r * r + kRelmseEpsilon);
        acc.smape += std::abs(d) / (std::abs(t) + std::abs(r) + kSmapeEpsilon);
        const double dc = clamp01(t) - clamp01(r);
        acc.se_clamped += dc * dc;
        if (variance) {
          const double v = variance->c[k][i];
          // E|X| = sqrt(2/pi) sigma for X ~ N(0, sigma^2).
          const double sd = std::sqrt(v) * std::sqrt(2.0 / std::numbers::pi);
          acc.var += v;
          acc.var_rel += v / (r * r + kRelmseEpsilon);
          acc.sd += sd;
          acc.sd_smape += sd / (2.0 * std::abs(r) + kSmapeEpsilon);
        }
      }
    }
  });

  ErrorStats e;
  e.pixels = ref.pixel_count();
  e.valid_pixels = s.valid;
  e.nonfinite_pixels = s.test_bad;
  e.reference_nonfinite_pixels = s.ref_bad;
  const double n = 3.0 * double(s.valid);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto mean = [&](double sum) { return s.valid ? sum / n : nan; };
  e.mse = mean(s.se);
  e.rmse = std::sqrt(e.mse);
  e.mae = mean(s.ae);
  e.relmse = mean(s.rel);
  e.smape = mean(s.smape);
  e.mse_clamped = mean(s.se_clamped);
  e.psnr = !s.valid ? nan
           : e.mse_clamped == 0.0 ? std::numeric_limits<double>::infinity()
                                  : 10.0 * std::log10(1.0 / e.mse_clamped);
  if (variance) {
    NoiseFloor nf;
    nf.mean_variance = mean(s.var);
    nf.relmse = mean(s.var_rel);
    nf.mae = mean(s.sd);
    nf.smape = mean(s.sd_smape);
    e.mse_debiased = e.mse - nf.mean_variance;
    e.unresolved_mse = e.mse < kUnresolvedFactor * nf.mean_variance;
    e.unresolved_relmse = e.relmse < kUnresolvedFactor * nf.relmse;
    e.unresolved_mae = e.mae < kUnresolvedFactor * nf.mae;
    e.unresolved_smape = e.smape < kUnresolvedFactor * nf.smape;
    e.noise = nf;
  }
  return e;
}

}  // namespace giq::metrics
