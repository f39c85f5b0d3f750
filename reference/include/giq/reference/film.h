#pragma once
// Per-pixel accumulators of a reference render, and their conversion to the reference EXR
// layers (ARCHITECTURE.md, "Reference EXR").
//
// Each pixel keeps, in double precision, a running mean and sum of squared deviations of its
// beauty samples (Welford 1962, "Note on a Method for Calculating Corrected Sums of Squares
// and Products", Technometrics 4(3); the update of Knuth, TAOCP vol. 2, 4.2.2) and the sum of
// the direct part. A pixel's samples are always added in sample-index order, so its
// accumulator is the same bits whichever thread adds them and however the render is split
// into passes or resumed.

#include <cstdint>
#include <string>
#include <vector>

#include "giq/image/image.h"

namespace giq::reference {

struct PixelAccumulator {
  uint32_t samples = 0;
  uint32_t nonfinite = 0;  // samples discarded (counted as zero) because they were NaN or Inf
  double mean[3] = {0.0, 0.0, 0.0};
  double m2[3] = {0.0, 0.0, 0.0};
  double direct_sum[3] = {0.0, 0.0, 0.0};

  // Adds one sample: its beauty (direct + indirect) and its direct part.
  void add(const float beauty[3], const float direct[3]) {
    ++samples;
    const double n = double(samples);
    for (int c = 0; c < 3; ++c) {
      const double x = double(beauty[c]);
      const double delta = x - mean[c];
      mean[c] += delta / n;
      m2[c] += delta * (x - mean[c]);
      direct_sum[c] += double(direct[c]);
    }
  }
  // Variance of the pixel mean: the sample variance over n (unbiased, n - 1 in the
  // denominator). Zero below two samples, where it is undefined.
  double variance_of_mean(int c) const {
    return samples < 2 ? 0.0 : m2[c] / (double(samples) - 1.0) / double(samples);
  }
};

// First-hit quantities of the pixel centre's ray, the same sample a rasteriser's G-buffer
// takes, so real-time techniques can be compared buffer to buffer.
struct PixelAux {
  float albedo[3] = {0.0f, 0.0f, 0.0f};
  float normal[3] = {0.0f, 0.0f, 0.0f};
  float depth = 0.0f;  // view-space depth along the camera's forward axis; 0 = no hit
  uint32_t object_id = 0;
};

struct Film {
  int width = 0;
  int height = 0;
  std::vector<PixelAccumulator> pixels;  // row-major, top row first
  std::vector<PixelAux> aux;

  Film() = default;
  Film(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h)), aux(size_t(w) * size_t(h)) {}

  // Samples of the pixel with the fewest (the render's spp once a pass is complete).
  uint32_t min_samples() const;
  uint64_t nonfinite_samples() const;
  // Mean over pixels of the relative standard error of the luminance of the beauty:
  // sqrt(variance of the mean) / mean, for pixels whose mean is at least 1e-3 of the image's
  // mean luminance (darker pixels would divide by nearly nothing). Summed in pixel order,
  // so the same accumulators give the same number.
  double relative_standard_error() const;

  // The reference EXR image: R,G,B, direct.*, indirect.*, albedo.*, N.*, Z, objectId,
  // variance.*, spp. indirect is chosen so that direct + indirect == beauty exactly in float
  // arithmetic, for every pixel and channel.
  image::Image to_image() const;
};

}  // namespace giq::reference
