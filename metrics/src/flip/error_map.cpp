#include "error_map.h"

#include <algorithm>
#include <cmath>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "colour.h"
#include "exposure.h"
#include "filters.h"

// Structure: the image is cut into horizontal bands, processed in parallel. For each band and
// each exposure, every input row the band's filters reach (the band plus a halo of the larger
// filter radius, clamped at the image border as in the paper's implementation) is converted to
// display values, to YCxCz and to normalised luminance, and filtered horizontally; then each
// output row is filtered vertically and the colour and feature differences are combined. Only
// the band's horizontal planes are kept, so memory stays bounded for any image height, and
// every exposure of a band reuses the same buffers. Nothing is allocated per pixel.

namespace giq::metrics::flip {
namespace {

// Horizontally filtered planes of one image of the pair.
enum Plane { kCsfY, kCsfCx, kCsfCz1, kCsfCz2, kFeatGauss, kFeatFirst, kFeatSecond, kPlaneCount };
// Display-space rows of one image, padded by the largest filter radius on each side.
enum Row { kRowY, kRowCx, kRowCz, kRowLum, kRowCount };

constexpr int kChunk = 256;  // columns per vertical-filter chunk: the accumulators stay in L1

struct Kernels {
  CsfFilters csf;
  FeatureFilters feature;
  int pad = 0;  // max of the two radii
  ColourRedistribution redistribution;
};

// Both passes compute out_k[x] = sum_t w_k[t] src[x + t * step] for K kernels sharing one
// source, taps in order (the order of the paper's implementation, so the sums round alike).
// Blocks of 8 outputs keep their K running sums in registers across all taps, and kernels that
// share a source load it once (Float4: fast_math.h).
template <int K>
void convolve(const float* __restrict src, size_t step, const float* const (&w)[K], int taps, int n,
              float* const (&out)[K]) {
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    Float4 lo[K], hi[K];
    for (int k = 0; k < K; ++k) lo[k] = hi[k] = Float4{};
    for (int t = 0; t < taps; ++t) {
      const float* p = src + size_t(t) * step + size_t(x);
      const Float4 s0 = load4(p), s1 = load4(p + 4);
      for (int k = 0; k < K; ++k) {
        const float wt = w[k][t];
        lo[k] += wt * s0;
        hi[k] += wt * s1;
      }
    }
    for (int k = 0; k < K; ++k) {
      store4(out[k] + x, lo[k]);
      store4(out[k] + x + 4, hi[k]);
    }
  }
  for (; x < n; ++x) {
    float acc[K] = {};
    for (int t = 0; t < taps; ++t)
      for (int k = 0; k < K; ++k) acc[k] += w[k][t] * src[size_t(t) * step + size_t(x)];
    for (int k = 0; k < K; ++k) out[k][x] = acc[k];
  }
}

// Written without std::isfinite, which does not vectorise: v - v is 0 for a finite v and NaN
// for an infinite or NaN one.
template <class T>
T sanitise(T v, T fallback) { return (v - v) == splat<T>(0.0f) ? v : fallback; }

// One display value in [0, 1] from a linear input value ([HDRFLIP]: expose, tone map, clamp;
// [FLIP] LDR input: clamp).
template <bool kHdr, class T>
T to_display(T v, float scale) {
  if constexpr (kHdr) return clamp01(tone_map_aces(v * scale));
  return clamp01(v);
}

// One reference/test pixel (or four) of a row: sanitised linear RGB -> display RGB -> XYZ ->
// YCxCz, plus the feature pipeline's normalised achromatic value ([FLIP]: (Y + 16) / 116 of
// YCxCz, which is XYZ's Y / Yn, Yn = 1).
template <bool kHdr, class T>
void prepare_pixel(const T (&ref)[3], const T (&test)[3], float scale, T (&ref_out)[4], T (&test_out)[4]) {
  const T r0 = sanitise(ref[0], splat<T>(0.0f)), g0 = sanitise(ref[1], splat<T>(0.0f)), b0 = sanitise(ref[2], splat<T>(0.0f));
  const T r1 = sanitise(test[0], r0), g1 = sanitise(test[1], g0), b1 = sanitise(test[2], b0);
  const ColourT<T> xyz0 = linear_rgb_to_xyz(
      ColourT<T>{to_display<kHdr>(r0, scale), to_display<kHdr>(g0, scale), to_display<kHdr>(b0, scale)});
  const ColourT<T> xyz1 = linear_rgb_to_xyz(
      ColourT<T>{to_display<kHdr>(r1, scale), to_display<kHdr>(g1, scale), to_display<kHdr>(b1, scale)});
  const ColourT<T> o0 = xyz_to_ycxcz(xyz0), o1 = xyz_to_ycxcz(xyz1);
  ref_out[0] = o0.c0, ref_out[1] = o0.c1, ref_out[2] = o0.c2, ref_out[3] = xyz0.c1;
  test_out[0] = o1.c0, test_out[1] = o1.c1, test_out[2] = o1.c2, test_out[3] = xyz1.c1;
}

// The FLIP value of one pixel (or four) from its filtered values, per image: [0..2] the
// CSF-filtered Y, Cx and the two Cz terms' sum [2]+[3], [4..7] the feature responses
// (x first, x second, y first, y second derivative).
template <class T>
T pixel_flip(const T (&r)[8], const T (&t)[8], const ColourRedistribution& redistribution) {
  // [FLIP] colour pipeline: filtered YCxCz -> linear RGB clamped to [0,1] -> Hunt L*a*b* -> HyAB.
  const ColourT<T> ref = linear_rgb_to_hunt_lab(clamp01(xyz_to_linear_rgb(ycxcz_to_xyz(ColourT<T>{r[0], r[1], r[2] + r[3]}))));
  const ColourT<T> test = linear_rgb_to_hunt_lab(clamp01(xyz_to_linear_rgb(ycxcz_to_xyz(ColourT<T>{t[0], t[1], t[2] + t[3]}))));
  const T colour = redistribute_colour_error(hyab(ref, test), redistribution);
  // [FLIP] feature pipeline: edge = |gradient|, point = |(second x, second y)|.
  const T edge_ref = vsqrt(r[4] * r[4] + r[6] * r[6]), edge_test = vsqrt(t[4] * t[4] + t[6] * t[6]);
  const T point_ref = vsqrt(r[5] * r[5] + r[7] * r[7]), point_test = vsqrt(t[5] * t[5] + t[7] * t[7]);
  const T feature = feature_difference(vabs(edge_ref - edge_test), vabs(point_ref - point_test));
  return combine_differences(colour, feature);
}

class BandWorker {
 public:
  void process(const ImagePair& pair, const Kernels& k, const DisplayMapping& mapping,
               const std::vector<float>& scales, int y0, int y1, float* map) {
    const int w = pair.width;
    const int band_rows = (y1 - y0) + 2 * k.pad;
    reserve(w, band_rows, k.pad);
    const size_t passes = mapping.hdr ? scales.size() : 1;
    for (size_t e = 0; e < passes; ++e) {
      const float scale = mapping.hdr ? scales[e] : 1.0f;
      for (int j = 0; j < band_rows; ++j) {
        const int py = std::clamp(y0 - k.pad + j, 0, pair.height - 1);
        if (mapping.hdr)
          prepare_rows<true>(pair, py, scale, k.pad);
        else
          prepare_rows<false>(pair, py, scale, k.pad);
        filter_horizontally(k, size_t(j) * size_t(w), w);
      }
      // Column chunks outside, rows inside: the rows a chunk's vertical filters reach stay in the
      // L2 cache while the filter window slides down the band.
      for (int x0 = 0; x0 < w; x0 += kChunk)
        for (int y = y0; y < y1; ++y)
          filter_vertically_and_compare(k, y - y0, x0, std::min(kChunk, w - x0), w, e == 0,
                                        map + size_t(y) * size_t(w) + size_t(x0));
    }
  }

 private:
  void reserve(int width, int band_rows, int pad) {
    const size_t row = size_t(width) + 2 * size_t(pad);
    const size_t plane = size_t(width) * size_t(band_rows);
    for (int i = 0; i < 2; ++i) {
      for (auto& r : rows_[i]) r.resize(row);
      for (auto& p : planes_[i]) p.resize(plane);
      for (auto& a : acc_[i]) a.resize(kChunk);
    }
  }

  // Reference and test row `py` -> display RGB -> XYZ -> YCxCz and the feature pipeline's
  // normalised achromatic value ([FLIP]: (Y + 16) / 116 of YCxCz, which is XYZ's Y / Yn).
  template <bool kHdr>
  void prepare_rows(const ImagePair& pair, int py, float scale, int pad) {
    const size_t base = size_t(py) * size_t(pair.width);
    const int w = pair.width;
    float* ry = rows_[0][kRowY].data() + pad;
    float* rcx = rows_[0][kRowCx].data() + pad;
    float* rcz = rows_[0][kRowCz].data() + pad;
    float* rl = rows_[0][kRowLum].data() + pad;
    float* ty = rows_[1][kRowY].data() + pad;
    float* tcx = rows_[1][kRowCx].data() + pad;
    float* tcz = rows_[1][kRowCz].data() + pad;
    float* tl = rows_[1][kRowLum].data() + pad;
    const RgbPlanes& ref = pair.reference;
    const RgbPlanes& test = pair.test;
    int x = 0;
    for (; x + 4 <= w; x += 4) {
      const size_t i = base + size_t(x);
      const Float4 in0[3] = {load4(ref.r + i), load4(ref.g + i), load4(ref.b + i)};
      const Float4 in1[3] = {load4(test.r + i), load4(test.g + i), load4(test.b + i)};
      Float4 o0[4], o1[4];
      prepare_pixel<kHdr>(in0, in1, scale, o0, o1);
      store4(ry + x, o0[0]), store4(rcx + x, o0[1]), store4(rcz + x, o0[2]), store4(rl + x, o0[3]);
      store4(ty + x, o1[0]), store4(tcx + x, o1[1]), store4(tcz + x, o1[2]), store4(tl + x, o1[3]);
    }
    for (; x < w; ++x) {
      const size_t i = base + size_t(x);
      const float in0[3] = {ref.r[i], ref.g[i], ref.b[i]};
      const float in1[3] = {test.r[i], test.g[i], test.b[i]};
      float o0[4], o1[4];
      prepare_pixel<kHdr>(in0, in1, scale, o0, o1);
      ry[x] = o0[0], rcx[x] = o0[1], rcz[x] = o0[2], rl[x] = o0[3];
      ty[x] = o1[0], tcx[x] = o1[1], tcz[x] = o1[2], tl[x] = o1[3];
    }
    // Clamp-to-edge padding, as the paper's implementation clamps filter taps to the image.
    for (int i = 0; i < 2; ++i)
      for (auto& row : rows_[i]) {
        float* p = row.data();
        std::fill(p, p + pad, p[pad]);
        std::fill(p + pad + w, p + 2 * pad + w, p[pad + w - 1]);
      }
  }

  void filter_horizontally(const Kernels& k, size_t offset, int w) {
    const int csf_taps = 2 * k.csf.radius + 1, csf_off = k.pad - k.csf.radius;
    const int feat_taps = 2 * k.feature.radius + 1, feat_off = k.pad - k.feature.radius;
    for (int i = 0; i < 2; ++i) {
      auto& row = rows_[i];
      auto& pl = planes_[i];
      convolve<1>(row[kRowY].data() + csf_off, 1, {k.csf.y.data()}, csf_taps, w, {pl[kCsfY].data() + offset});
      convolve<1>(row[kRowCx].data() + csf_off, 1, {k.csf.cx.data()}, csf_taps, w, {pl[kCsfCx].data() + offset});
      convolve<2>(row[kRowCz].data() + csf_off, 1, {k.csf.cz1.data(), k.csf.cz2.data()}, csf_taps, w,
                  {pl[kCsfCz1].data() + offset, pl[kCsfCz2].data() + offset});
      convolve<3>(row[kRowLum].data() + feat_off, 1,
                  {k.feature.gaussian.data(), k.feature.first.data(), k.feature.second.data()}, feat_taps, w,
                  {pl[kFeatGauss].data() + offset, pl[kFeatFirst].data() + offset, pl[kFeatSecond].data() + offset});
    }
  }

  // Columns [x0, x0 + n) of output row `yl` of the band (band row yl + pad): vertical filtering,
  // then per pixel the colour difference, the feature difference and their combination; `first`
  // stores, later exposures keep the per-pixel maximum ([HDRFLIP]).
  void filter_vertically_and_compare(const Kernels& k, int yl, int x0, int n, int w, bool first, float* out) {
    const size_t stride = size_t(w);
    const int csf_taps = 2 * k.csf.radius + 1, feat_taps = 2 * k.feature.radius + 1;
    const size_t csf_row0 = size_t(yl + k.pad - k.csf.radius) * stride;
    const size_t feat_row0 = size_t(yl + k.pad - k.feature.radius) * stride;
    for (int i = 0; i < 2; ++i) {
      auto& pl = planes_[i];
      auto& acc = acc_[i];
      const size_t c = csf_row0 + size_t(x0), f = feat_row0 + size_t(x0);
      convolve<1>(pl[kCsfY].data() + c, stride, {k.csf.y.data()}, csf_taps, n, {acc[0].data()});
      convolve<1>(pl[kCsfCx].data() + c, stride, {k.csf.cx.data()}, csf_taps, n, {acc[1].data()});
      convolve<1>(pl[kCsfCz1].data() + c, stride, {k.csf.cz1.data()}, csf_taps, n, {acc[2].data()});
      convolve<1>(pl[kCsfCz2].data() + c, stride, {k.csf.cz2.data()}, csf_taps, n, {acc[3].data()});
      // x derivatives: derivative taps horizontally, Gaussian vertically; y derivatives: the
      // horizontally smoothed luminance with derivative taps vertically.
      convolve<1>(pl[kFeatFirst].data() + f, stride, {k.feature.gaussian.data()}, feat_taps, n, {acc[4].data()});
      convolve<1>(pl[kFeatSecond].data() + f, stride, {k.feature.gaussian.data()}, feat_taps, n, {acc[5].data()});
      convolve<2>(pl[kFeatGauss].data() + f, stride, {k.feature.first.data(), k.feature.second.data()}, feat_taps,
                  n, {acc[6].data(), acc[7].data()});
    }
    compare_chunk(k.redistribution, n, first, out);
  }

  void compare_chunk(const ColourRedistribution& redistribution, int n, bool first, float* out) {
    const auto& a = acc_[0];
    const auto& b = acc_[1];
    int x = 0;
    for (; x + 4 <= n; x += 4) {
      Float4 r[8], t[8];
      for (int c = 0; c < 8; ++c) r[c] = load4(a[c].data() + x), t[c] = load4(b[c].data() + x);
      const Float4 e = pixel_flip(r, t, redistribution);
      store4(out + x, first ? e : vmax(load4(out + x), e));
    }
    for (; x < n; ++x) {
      float r[8], t[8];
      for (int c = 0; c < 8; ++c) r[c] = a[c][size_t(x)], t[c] = b[c][size_t(x)];
      const float e = pixel_flip(r, t, redistribution);
      out[x] = first ? e : std::max(out[x], e);
    }
  }

  std::vector<float> rows_[2][kRowCount];
  std::vector<float> planes_[2][kPlaneCount];
  std::vector<float> acc_[2][8];
};

// Band height: about 128 rows, with a band count that is a multiple of the worker count so the
// last round of bands keeps every core busy, and capped so a worker's planes stay near 64 MiB
// for very wide images.
int choose_band_height(int width, int height, int pad) {
  const int workers = std::max(1, tbb::this_task_arena::max_concurrency());
  int bands = (height + 127) / 128;
  bands = ((bands + workers - 1) / workers) * workers;
  int rows = (height + bands - 1) / bands;
  constexpr size_t kFloatsPerWorker = size_t(16) << 20;
  const int cap = int(kFloatsPerWorker / (size_t(2 * kPlaneCount) * size_t(width))) - 2 * pad;
  return std::max(1, std::min(rows, std::max(cap, 8)));
}

}  // namespace

void compute_error_map(const ImagePair& pair, float pixels_per_degree, const DisplayMapping& mapping, float* map) {
  if (pair.width <= 0 || pair.height <= 0) return;
  Kernels k;
  k.csf = make_csf_filters(pixels_per_degree);
  k.feature = make_feature_filters(pixels_per_degree);
  k.pad = std::max(k.csf.radius, k.feature.radius);
  k.redistribution = make_colour_redistribution();
  // [HDRFLIP]: exposure c scales the linear input by 2^c.
  std::vector<float> scales;
  for (float stop : mapping.exposure_stops) scales.push_back(std::pow(2.0f, stop));
  if (mapping.hdr && scales.empty()) {
    std::fill(map, map + size_t(pair.width) * size_t(pair.height), 0.0f);
    return;
  }

  const int band = choose_band_height(pair.width, pair.height, k.pad);
  const int bands = (pair.height + band - 1) / band;
  tbb::enumerable_thread_specific<BandWorker> workers;
  tbb::parallel_for(0, bands, [&](int b) {
    const int y0 = b * band, y1 = std::min(pair.height, y0 + band);
    workers.local().process(pair, k, mapping, scales, y0, y1, map);
  });
}

}  // namespace giq::metrics::flip
