#pragma once
// Sequence error split into its persistent and changing parts (docs/metrics.md, "Flicker and
// bias"). With e_t(p) = Y_T,t(p) - Y_R,t(p) over the frames where pixel p is valid:
//   bias^2(p)   = (mean_t e_t(p))^2
//   variance(p) = mean_t e_t(p)^2 - bias^2(p)      (population variance over the frames)
// so that mse_seq = mean_p (bias^2 + variance) = mean_{p,t} e^2 exactly. The reference's own
// noise is then removed where it belongs: with a reference per frame its noise changes from
// frame to frame and inflates the variance; with one reference for a static scene it is the
// same every frame and inflates the bias (docs/metrics.md).
//   flicker = sqrt(mean_p variance_corrected) / mean_{p,t} Y_R,t
//
// Frames are added one at a time; memory is two doubles, one float and one counter per pixel.

#include <cstdint>
#include <vector>

#include "giq/metrics/layer.h"
#include "giq/metrics/maps.h"

namespace giq::metrics {

struct SequenceStats {
  int frames = 0;
  size_t pixels = 0;                // pixels valid in at least one frame
  size_t nonfinite_pixel_frames = 0;  // (pixel, frame) pairs excluded for NaN/Inf
  bool per_frame_reference = true;
  double mse_seq = 0.0;            // mean_{p,t} e^2 = bias2 + variance
  double bias2 = 0.0;              // mean_p bias^2(p)
  double variance = 0.0;           // mean_p variance(p)
  double reference_noise = 0.0;    // mean_{p,t} sigma^2_Y,R,t (0 without a variance layer)
  double bias2_corrected = 0.0;    // mean_p max(0, bias^2 - noise share)
  double variance_corrected = 0.0; // mean_p max(0, variance - noise share)
  double mean_reference_luminance = 0.0;  // mean_{p,t} Y_R,t
  double flicker = 0.0;            // NaN when the reference is black
  double flicker_uncorrected = 0.0;
};

class SequenceAccumulator {
 public:
  // per_frame_reference: false when one reference image stands for every frame.
  SequenceAccumulator(int width, int height, bool per_frame_reference);

  // One frame; variance is the reference's variance layer for the compared layer, or nullptr.
  void add(const RgbLayer& reference, const RgbLayer& test, const RgbLayer* variance);

  SequenceStats stats() const;
  // sqrt(variance_corrected(p)): the temporal standard deviation of the error (NaN where a
  // pixel was never valid).
  Map temporal_stddev_map() const;

 private:
  double corrected_variance(size_t i) const;
  double corrected_bias2(size_t i) const;

  int width_, height_;
  bool per_frame_reference_;
  int frames_ = 0;
  size_t nonfinite_ = 0;
  double luminance_sum_ = 0.0;
  size_t luminance_count_ = 0;
  std::vector<double> sum_e_, sum_e2_;
  std::vector<float> sum_noise_;
  std::vector<uint32_t> count_;
};

}  // namespace giq::metrics
