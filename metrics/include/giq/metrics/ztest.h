#pragma once
// A per-pixel test of the hypothesis "the test image and the reference estimate the same
// image", for a test that is itself an unbiased estimate (a path tracer's, `pt`'s) or a
// converged image, against a reference that carries the variance of its pixel means. Each
// channel value gives z = (T - R) / sqrt(Var R + Var T) (Var T from the test's own variance
// layer, 0 without one), standard normal under the hypothesis; values whose variance is 0 on
// both sides are left out (noise-free pixels compare exactly elsewhere). The largest |z| of
// N values is judged with the Šidák correction for N tests: p = 1 - (1 - p_min)^N, with p_min
// the two-sided normal p-value of that |z| (Mitsuba's render tests judge their per-pixel
// Welch t-tests the same way). A small p (e.g. below 0.01) rejects the hypothesis: somewhere
// the difference is larger than the noise allows. docs/metrics.md, "Per-pixel z-test".

#include <cstddef>

#include "giq/metrics/layer.h"

namespace giq::metrics {

struct ZTest {
  size_t tested = 0;       // channel values with a positive variance
  double max_abs_z = 0.0;  // 0 when none was tested
  double p_min = 1.0;      // two-sided p-value of max_abs_z
  double p_sidak = 1.0;    // 1 - (1 - p_min)^tested
};

// ref_var: the reference's variance of the pixel mean; test_var: the test's, or nullptr.
// Pixels with a non-finite value on either side are left out.
ZTest ztest(const RgbLayer& ref, const RgbLayer& test, const RgbLayer& ref_var, const RgbLayer* test_var);

}  // namespace giq::metrics
