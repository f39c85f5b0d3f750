#include "giq/metrics/sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parallel.h"

namespace giq::metrics {
namespace {

struct FrameSums {
  size_t bad = 0, n = 0;
  double lum = 0;
  FrameSums& operator+=(const FrameSums& o) {
    bad += o.bad, n += o.n, lum += o.lum;
    return *this;
  }
};

struct PixelSums {
  size_t pixels = 0;
  double mse = 0, bias2 = 0, var = 0, noise = 0, bias2_c = 0, var_c = 0;
  PixelSums& operator+=(const PixelSums& o) {
    pixels += o.pixels, mse += o.mse, bias2 += o.bias2, var += o.var, noise += o.noise, bias2_c += o.bias2_c,
        var_c += o.var_c;
    return *this;
  }
};

}  // namespace

SequenceAccumulator::SequenceAccumulator(int width, int height, bool per_frame_reference)
    : width_(width), height_(height), per_frame_reference_(per_frame_reference) {
  const size_t n = size_t(width) * size_t(height);
  sum_e_.assign(n, 0.0);
  sum_e2_.assign(n, 0.0);
  sum_noise_.assign(n, 0.0f);
  count_.assign(n, 0);
}

void SequenceAccumulator::add(const RgbLayer& r, const RgbLayer& t, const RgbLayer* v) {
  const int w = width_;
  const FrameSums f = detail::reduce_rows<FrameSums>(height_, [&](int y0, int y1, FrameSums& acc) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i) {
      if (!r.finite(i) || !t.finite(i) || (v && !v->finite(i))) {
        ++acc.bad;
        continue;
      }
      const double e = double(t.luminance(i)) - double(r.luminance(i));
      sum_e_[i] += e;
      sum_e2_[i] += e * e;
      if (v) sum_noise_[i] += luminance_variance(v->c[0][i], v->c[1][i], v->c[2][i]);
      ++count_[i];
      acc.lum += r.luminance(i);
      ++acc.n;
    }
  });
  ++frames_;
  nonfinite_ += f.bad;
  luminance_sum_ += f.lum;
  luminance_count_ += f.n;
}

// Noise of the reference in the variance over time: with a reference per frame, each frame's
// reference noise is independent, adding mean_t sigma^2_t to Var_t e. With one reference for
// every frame it adds nothing to the variance.
double SequenceAccumulator::corrected_variance(size_t i) const {
  const double n = count_[i], mean = sum_e_[i] / n;
  const double var = std::max(0.0, sum_e2_[i] / n - mean * mean);
  return per_frame_reference_ ? std::max(0.0, var - double(sum_noise_[i]) / n) : var;
}

// Noise of the reference in the bias: the mean of n independent reference estimates carries
// mean_t sigma^2_t / n; a single reference carries its full sigma^2.
double SequenceAccumulator::corrected_bias2(size_t i) const {
  const double n = count_[i], mean = sum_e_[i] / n, noise = double(sum_noise_[i]) / n;
  return std::max(0.0, mean * mean - (per_frame_reference_ ? noise / n : noise));
}

SequenceStats SequenceAccumulator::stats() const {
  const int w = width_;
  const PixelSums p = detail::reduce_rows<PixelSums>(height_, [&](int y0, int y1, PixelSums& acc) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i) {
      if (!count_[i]) continue;
      const double n = count_[i], mean = sum_e_[i] / n;
      ++acc.pixels;
      acc.mse += sum_e2_[i] / n;
      acc.bias2 += mean * mean;
      acc.var += std::max(0.0, sum_e2_[i] / n - mean * mean);
      acc.noise += double(sum_noise_[i]) / n;
      acc.bias2_c += corrected_bias2(i);
      acc.var_c += corrected_variance(i);
    }
  });
  SequenceStats s;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  s.frames = frames_;
  s.pixels = p.pixels;
  s.nonfinite_pixel_frames = nonfinite_;
  s.per_frame_reference = per_frame_reference_;
  auto mean = [&](double v) { return p.pixels ? v / double(p.pixels) : nan; };
  s.mse_seq = mean(p.mse);
  s.bias2 = mean(p.bias2);
  s.variance = mean(p.var);
  s.reference_noise = mean(p.noise);
  s.bias2_corrected = mean(p.bias2_c);
  s.variance_corrected = mean(p.var_c);
  s.mean_reference_luminance = luminance_count_ ? luminance_sum_ / double(luminance_count_) : nan;
  const bool lit = s.mean_reference_luminance > 0.0;
  s.flicker = lit ? std::sqrt(s.variance_corrected) / s.mean_reference_luminance : nan;
  s.flicker_uncorrected = lit ? std::sqrt(s.variance) / s.mean_reference_luminance : nan;
  return s;
}

Map SequenceAccumulator::temporal_stddev_map() const {
  Map m{"temporal_stddev", "sqrt(variance_corrected(p)) of e_t = Y_T,t - Y_R,t", "radiance", false, width_,
        height_, {}};
  m.values.resize(count_.size());
  const int w = width_;
  detail::for_rows(height_, [&](int y0, int y1) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
      m.values[i] = count_[i] ? float(std::sqrt(corrected_variance(i))) : std::numeric_limits<float>::quiet_NaN();
  });
  return m;
}

}  // namespace giq::metrics
