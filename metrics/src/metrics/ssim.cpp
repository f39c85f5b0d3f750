#include "giq/metrics/ssim.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "giq/image/srgb.h"

namespace giq::metrics {
namespace {

constexpr int kBandRows = 32;
// Filtered quantities: weight m, m x, m y, m x^2, m y^2, m x y.
constexpr int kMoments = 6;

using LumaRow = std::function<void(int y, float* x, float* yv)>;

std::vector<double> gaussian(const SsimOptions& o) {
  std::vector<double> g(size_t(2 * o.radius + 1));
  for (int d = -o.radius; d <= o.radius; ++d) g[size_t(d + o.radius)] = std::exp(-d * d / (2.0 * o.sigma * o.sigma));
  // Normalisation cancels (the window is renormalised by the filtered weight m), kept for clarity.
  double s = 0;
  for (double v : g) s += v;
  for (double& v : g) v /= s;
  return g;
}

SsimResult run(int w, int h, const LumaRow& luma, bool keep_map, const SsimOptions& o) {
  SsimResult result;
  if (keep_map) result.map.assign(size_t(w) * size_t(h), std::numeric_limits<float>::quiet_NaN());
  const std::vector<double> g = gaussian(o);
  const int r = o.radius;
  const double c1 = (o.k1 * 1.0) * (o.k1 * 1.0), c2 = (o.k2 * 1.0) * (o.k2 * 1.0);  // L = 1

  struct Scratch {
    std::vector<float> x, y;
    std::vector<double> horizontal;  // (band + 2r) rows x kMoments x w
    std::vector<double> acc;         // kMoments x w
  };
  tbb::enumerable_thread_specific<Scratch> scratch;
  const int bands = (h + kBandRows - 1) / kBandRows;
  std::vector<double> band_sum(size_t(bands), 0.0);
  std::vector<size_t> band_count(size_t(bands), 0);

  tbb::parallel_for(tbb::blocked_range<int>(0, bands, 1), [&](const tbb::blocked_range<int>& br) {
    Scratch& s = scratch.local();
    s.x.resize(size_t(w));
    s.y.resize(size_t(w));
    s.acc.resize(size_t(kMoments) * size_t(w));
    for (int b = br.begin(); b != br.end(); ++b) {
      const int y0 = b * kBandRows, y1 = std::min(h, y0 + kBandRows);
      const int in0 = std::max(0, y0 - r), in1 = std::min(h, y1 + r);
      s.horizontal.assign(size_t(in1 - in0) * kMoments * size_t(w), 0.0);
      // Pass 1: horizontal filtering of the six moments, row by row.
      for (int yy = in0; yy < in1; ++yy) {
        luma(yy, s.x.data(), s.y.data());
        double* row = &s.horizontal[size_t(yy - in0) * kMoments * size_t(w)];
        for (int px = 0; px < w; ++px) {
          double m[kMoments] = {0, 0, 0, 0, 0, 0};
          const int q0 = std::max(0, px - r), q1 = std::min(w - 1, px + r);
          for (int q = q0; q <= q1; ++q) {
            const float a = s.x[size_t(q)], bv = s.y[size_t(q)];
            if (std::isnan(a) || std::isnan(bv)) continue;
            const double wt = g[size_t(q - px + r)];
            m[0] += wt, m[1] += wt * a, m[2] += wt * bv, m[3] += wt * a * a, m[4] += wt * bv * bv, m[5] += wt * a * bv;
          }
          for (int k = 0; k < kMoments; ++k) row[size_t(k) * size_t(w) + size_t(px)] = m[k];
        }
      }
      // Pass 2: vertical filtering and the SSIM of each pixel of the band.
      double sum = 0.0;
      size_t count = 0;
      for (int yy = y0; yy < y1; ++yy) {
        std::fill(s.acc.begin(), s.acc.end(), 0.0);
        const int r0 = std::max(in0, yy - r), r1 = std::min(in1 - 1, yy + r);
        for (int ry = r0; ry <= r1; ++ry) {
          const double wt = g[size_t(ry - yy + r)];
          const double* row = &s.horizontal[size_t(ry - in0) * kMoments * size_t(w)];
          for (size_t k = 0; k < size_t(kMoments) * size_t(w); ++k) s.acc[k] += wt * row[k];
        }
        luma(yy, s.x.data(), s.y.data());
        for (int px = 0; px < w; ++px) {
          if (std::isnan(s.x[size_t(px)]) || std::isnan(s.y[size_t(px)])) continue;
          const double m = s.acc[size_t(px)];
          auto at = [&](int k) { return s.acc[size_t(k) * size_t(w) + size_t(px)] / m; };
          const double mx = at(1), my = at(2);
          const double vx = std::max(0.0, at(3) - mx * mx), vy = std::max(0.0, at(4) - my * my);
          const double cxy = at(5) - mx * my;
          // Wang et al. 2004, eq. 13.
          const double v = ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
          sum += v;
          ++count;
          if (keep_map) result.map[size_t(yy) * size_t(w) + size_t(px)] = float(v);
        }
      }
      band_sum[size_t(b)] = sum;
      band_count[size_t(b)] = count;
    }
  });
  double total = 0.0;
  for (int b = 0; b < bands; ++b) total += band_sum[size_t(b)], result.valid_pixels += band_count[size_t(b)];
  result.mean = result.valid_pixels ? total / double(result.valid_pixels) : std::numeric_limits<double>::quiet_NaN();
  return result;
}

}  // namespace

float display_luma(const RgbLayer& im, size_t i) {
  if (!im.finite(i)) return std::numeric_limits<float>::quiet_NaN();
  return 0.2126f * image::srgb_encode(im.c[0][i]) + 0.7152f * image::srgb_encode(im.c[1][i]) +
         0.0722f * image::srgb_encode(im.c[2][i]);
}

SsimResult ssim(const RgbLayer& ref, const RgbLayer& test, bool keep_map, const SsimOptions& options) {
  const int w = ref.width;
  return run(
      w, ref.height,
      [&](int y, float* x, float* yv) {
        for (int px = 0; px < w; ++px) {
          const size_t i = size_t(y) * size_t(w) + size_t(px);
          x[px] = display_luma(ref, i);
          yv[px] = display_luma(test, i);
        }
      },
      keep_map, options);
}

SsimResult ssim_planes(const float* a, const float* b, int w, int h, bool keep_map, const SsimOptions& options) {
  return run(
      w, h,
      [&](int y, float* x, float* yv) {
        for (int px = 0; px < w; ++px) {
          const size_t i = size_t(y) * size_t(w) + size_t(px);
          x[px] = std::isfinite(a[i]) ? a[i] : std::numeric_limits<float>::quiet_NaN();
          yv[px] = std::isfinite(b[i]) ? b[i] : std::numeric_limits<float>::quiet_NaN();
        }
      },
      keep_map, options);
}

}  // namespace giq::metrics
