#pragma once
// Per-pixel accumulators of a reference render, and their conversion to the reference EXR
// layers (ARCHITECTURE.md, "Reference EXR").
//
// Each pixel keeps, in double precision, a running mean and sum of squared deviations of its
// beauty samples (Welford 1962, "Note on a Method for Calculating Corrected Sums of Squares
// and Products", Technometrics 4(3); the update of Knuth, TAOCP vol. 2, 4.2.2), the same of
// its block means when samples come in blocks of correlated samples, and the sum of the
// direct part. A pixel's samples are always added in sample-index order, so its
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
  // Samples per independent block (the Sobol sampler's replicates, reference/sampling.h), or
  // 0 when every sample is independent of the others.
  uint32_t block = 0;
  uint32_t blocks = 0;  // complete blocks
  double mean[3] = {0.0, 0.0, 0.0};
  double m2[3] = {0.0, 0.0, 0.0};
  double direct_sum[3] = {0.0, 0.0, 0.0};
  double block_sum[3] = {0.0, 0.0, 0.0};   // of the samples of the block being filled
  double block_mean[3] = {0.0, 0.0, 0.0};  // Welford over the complete blocks' means
  double block_m2[3] = {0.0, 0.0, 0.0};

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
    if (block == 0) return;
    for (int c = 0; c < 3; ++c) block_sum[c] += double(beauty[c]);
    if (samples % block != 0) return;
    ++blocks;
    for (int c = 0; c < 3; ++c) {
      const double x = block_sum[c] / double(block);
      const double delta = x - block_mean[c];
      block_mean[c] += delta / double(blocks);
      block_m2[c] += delta * (x - block_mean[c]);
      block_sum[c] = 0.0;
    }
  }

  // Variance of the pixel mean (unbiased, n - 1 in the denominators):
  // - independent samples: the sample variance over n;
  // - blocks: the variance of the block means times block / n, which is the variance of the
  //   mean of the complete blocks, scaled as 1/n when an incomplete block follows them.
  //   Samples within a block are correlated by design (that is what stratifies them), so
  //   their sample variance would overestimate the variance of the mean. Below two complete
  //   blocks the per-sample estimate is all there is, and it is used.
  // Zero below two samples, where it is undefined.
  double variance_of_mean(int c) const {
    if (block != 0 && blocks >= 2) return block_m2[c] / (double(blocks) - 1.0) * double(block) / double(samples);
    return samples < 2 ? 0.0 : m2[c] / (double(samples) - 1.0) / double(samples);
  }
  // Degrees of freedom of variance_of_mean (0 where it is undefined).
  uint32_t variance_dof() const {
    if (block != 0 && blocks >= 2) return blocks - 1;
    return samples < 2 ? 0 : samples - 1;
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
  // block: samples per independent block (PixelAccumulator::block), 0 for independent samples.
  Film(int w, int h, uint32_t block = 0) : width(w), height(h), pixels(size_t(w) * size_t(h)), aux(size_t(w) * size_t(h)) {
    for (PixelAccumulator& p : pixels) p.block = block;
  }

  // Samples of the pixel with the fewest (the render's spp once a pass is complete).
  uint32_t min_samples() const;
  uint64_t nonfinite_samples() const;
  // Mean over pixels of the relative standard error of the luminance of the beauty:
  // sqrt(variance of the mean) / mean, with the square root divided by c4 so that it is not
  // biased low when the variance has few degrees of freedom, for pixels whose mean is at least 1e-3 of the image's
  // mean luminance (darker pixels would divide by nearly nothing). Summed in pixel order,
  // so the same accumulators give the same number.
  double relative_standard_error() const;

  // The reference EXR image: R,G,B, direct.*, indirect.*, albedo.*, N.*, Z, objectId,
  // variance.*, spp. indirect is chosen so that direct + indirect == beauty exactly in float
  // arithmetic, for every pixel and channel.
  image::Image to_image() const;
};

}  // namespace giq::reference
