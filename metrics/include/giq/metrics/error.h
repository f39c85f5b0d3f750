#pragma once
// Per-image error statistics (docs/metrics.md, "Per-image error"): mse, rmse, mae, relmse,
// smape, psnr, and the noise floor of a path-traced reference with the "unresolved" flags.
// Means run over pixels x RGB of the pixels where both images are finite; non-finite test
// pixels are counted, never averaged.

#include <cstddef>
#include <optional>
#include <string>

#include "giq/metrics/layer.h"

namespace giq::metrics {

// The reference's own noise in the units of each metric (expected value of the metric
// between the reference estimate and the truth it estimates).
struct NoiseFloor {
  std::string layer;           // variance layer used
  double mean_variance = 0.0;  // mean sigma^2 over pixels x RGB: the mse noise floor
  double relmse = 0.0;         // mean sigma^2 / (R^2 + 0.01)
  double relmse_trimmed = 0.0; // the same over the pixels ErrorStats::relmse_trimmed keeps
  double mae = 0.0;            // mean sqrt(2/pi) sigma  (E|N(0, sigma^2)|)
  double smape = 0.0;          // mean sqrt(2/pi) sigma / (2|R| + 1e-4)
};

struct ErrorStats {
  size_t pixels = 0;                       // width x height
  size_t valid_pixels = 0;                 // pixels entering every mean
  size_t nonfinite_pixels = 0;             // test pixels with a NaN/Inf channel
  size_t reference_nonfinite_pixels = 0;   // reference pixels with NaN/Inf, or its variance NaN/Inf/negative
  // NaN when there is no valid pixel.
  double mse = 0.0, rmse = 0.0, mae = 0.0, relmse = 0.0, smape = 0.0;
  // relmse without the kTrimFraction of valid pixels with the largest relative error (hot
  // pixels: a sun glint, a firefly), which alone can decide relmse on real assets.
  double relmse_trimmed = 0.0;
  size_t trimmed_pixels = 0;  // how many were left out: floor(kTrimFraction x valid_pixels)
  double mse_clamped = 0.0;  // mse of the images clamped to [0, 1], for psnr
  double psnr = 0.0;         // 10 log10(1 / mse_clamped); +inf for identical clamped images
  std::optional<NoiseFloor> noise;  // when the reference has a variance layer
  double mse_debiased = 0.0;        // mse - noise->mean_variance (only with noise)
  // Metric below 3x its noise floor: the reference is too noisy to resolve it.
  bool unresolved_mse = false, unresolved_relmse = false, unresolved_mae = false, unresolved_smape = false;
  bool unresolved_relmse_trimmed = false;
};

inline constexpr double kRelmseEpsilon = 0.01;   // Rousselle et al. 2011
inline constexpr double kSmapeEpsilon = 1e-4;
inline constexpr double kUnresolvedFactor = 3.0;
inline constexpr double kTrimFraction = 1e-4;  // 0.01 % of the pixels, as rendering papers trim

// variance: the reference's per-pixel variance of the mean for the same layer, or nullptr.
ErrorStats error_stats(const RgbLayer& reference, const RgbLayer& test, const RgbLayer* variance = nullptr);

}  // namespace giq::metrics
