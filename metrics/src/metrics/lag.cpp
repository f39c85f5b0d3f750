#include "giq/metrics/lag.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "parallel.h"

namespace giq::metrics {
namespace {

}  // namespace

std::vector<uint8_t> changed_region(const RgbLayer& before, const RgbLayer* vb, const RgbLayer& after,
                                    const RgbLayer* va, double sigma_factor) {
  std::vector<uint8_t> region(before.pixel_count(), 0);
  const int w = before.width;
  detail::for_rows(before.height, [&](int y0, int y1) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i) {
      if (!before.finite(i) || !after.finite(i) || (vb && !vb->finite(i)) || (va && !va->finite(i))) continue;
      double var = 0.0;
      if (vb) var += luminance_variance(vb->c[0][i], vb->c[1][i], vb->c[2][i]);
      if (va) var += luminance_variance(va->c[0][i], va->c[1][i], va->c[2][i]);
      const double d = std::abs(double(after.luminance(i)) - double(before.luminance(i)));
      region[i] = d > sigma_factor * std::sqrt(var);
    }
  });
  return region;
}

double region_abs_error(const RgbLayer& r, const RgbLayer& t, const std::vector<uint8_t>& region) {
  const int w = r.width;
  return detail::reduce_rows<detail::MeanSum>(r.height, [&](int y0, int y1, detail::MeanSum& acc) {
           for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
             if (region[i] && r.finite(i) && t.finite(i))
               acc.sum += std::abs(double(t.luminance(i)) - double(r.luminance(i))), ++acc.n;
         })
      .mean();
}

double mean_luminance_change(const RgbLayer& prev, const RgbLayer& cur) {
  const int w = prev.width;
  return detail::reduce_rows<detail::MeanSum>(prev.height, [&](int y0, int y1, detail::MeanSum& acc) {
           for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
             if (prev.finite(i) && cur.finite(i))
               acc.sum += std::abs(double(cur.luminance(i)) - double(prev.luminance(i))), ++acc.n;
         })
      .mean();
}

LagResult lag90(const std::vector<double>& r, int t0, std::optional<double> frame_ms) {
  const int frames = int(r.size());
  if (t0 < 0 || t0 >= frames)
    throw std::invalid_argument("lag90: step frame " + std::to_string(t0) + " outside 0.." + std::to_string(frames - 1));
  LagResult out;
  out.t0 = t0;
  out.r_t0 = r[size_t(t0)];
  const int tail = std::max(1, (frames + 3) / 4);  // last 25% of the frames, rounded up
  double sum = 0.0;
  int n = 0;
  for (int t = frames - tail; t < frames; ++t)
    if (std::isfinite(r[size_t(t)])) sum += r[size_t(t)], ++n;
  out.r_inf = n ? sum / n : std::numeric_limits<double>::quiet_NaN();
  // The settled error's own frame-to-frame spread over the same frames. Where other content
  // keeps moving after the step the error fluctuates, and 10 % of a step no larger than that
  // fluctuation would time the fluctuation, not the response: a frame within 2 s of r_inf is
  // as settled as the settled frames are, so the threshold is never inside that band (and a
  // step within it is no measurable lag).
  double squares = 0.0;
  for (int t = frames - tail; t < frames; ++t)
    if (std::isfinite(r[size_t(t)])) squares += (r[size_t(t)] - out.r_inf) * (r[size_t(t)] - out.r_inf);
  out.r_inf_stddev = n > 1 ? std::sqrt(squares / (n - 1)) : 0.0;
  out.threshold = out.r_inf + std::max(0.1 * (out.r_t0 - out.r_inf), 2.0 * out.r_inf_stddev);
  for (int t = t0; t < frames; ++t) {
    if (std::isfinite(r[size_t(t)]) && r[size_t(t)] <= out.threshold) {
      out.lag_frames = t - t0;
      break;
    }
  }
  if (out.lag_frames && frame_ms) out.lag_ms = *out.lag_frames * *frame_ms;
  return out;
}

}  // namespace giq::metrics
