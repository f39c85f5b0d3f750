#include "giq/metrics/ztest.h"

#include <cmath>

namespace giq::metrics {

ZTest ztest(const RgbLayer& ref, const RgbLayer& test, const RgbLayer& ref_var, const RgbLayer* test_var) {
  ZTest z;
  for (size_t i = 0; i < ref.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double r = ref.c[c][i], t = test.c[c][i];
      const double var = double(ref_var.c[c][i]) + (test_var ? double(test_var->c[c][i]) : 0.0);
      if (!std::isfinite(r) || !std::isfinite(t) || !std::isfinite(var) || !(var > 0.0)) continue;
      ++z.tested;
      z.max_abs_z = std::max(z.max_abs_z, std::abs(t - r) / std::sqrt(var));
    }
  if (z.tested == 0) return z;
  // P(|Z| >= z) = erfc(z / sqrt 2); 1 - (1 - p)^N computed as -expm1(N log1p(-p)), which keeps
  // its precision when p is tiny and N large.
  z.p_min = std::erfc(z.max_abs_z / std::sqrt(2.0));
  z.p_sidak = z.p_min >= 1.0 ? 1.0 : -std::expm1(double(z.tested) * std::log1p(-z.p_min));
  return z;
}

}  // namespace giq::metrics
