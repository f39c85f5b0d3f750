#include "giq/metrics/leak.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "parallel.h"

namespace giq::metrics {
namespace {

bool valid(const RgbLayer& r, const RgbLayer& t, const RgbLayer* v, size_t i) {
  return r.finite(i) && t.finite(i) && (!v || v->finite(i));
}

struct LumSum {
  double sum = 0;
  size_t n = 0;
  LumSum& operator+=(const LumSum& o) {
    sum += o.sum, n += o.n;
    return *this;
  }
};

struct RegionSums {
  size_t auto_px = 0, auto_leaky = 0, decl_px = 0, decl_leaky = 0;
  double auto_excess = 0, decl_excess = 0;
  RegionSums& operator+=(const RegionSums& o) {
    auto_px += o.auto_px, auto_leaky += o.auto_leaky, decl_px += o.decl_px, decl_leaky += o.decl_leaky;
    auto_excess += o.auto_excess, decl_excess += o.decl_excess;
    return *this;
  }
};

}  // namespace

float leak_excess(const RgbLayer& r, const RgbLayer& t, const RgbLayer* v, size_t i, double sigma_factor) {
  double sigma = 0.0;
  if (v) sigma = std::sqrt(double(luminance_variance(v->c[0][i], v->c[1][i], v->c[2][i])));
  return float(std::max(0.0, double(t.luminance(i)) - double(r.luminance(i)) - sigma_factor * sigma));
}

LeakResult leak(const RgbLayer& r, const RgbLayer& t, const RgbLayer* v, const float* object_id,
                const LeakOptions& o) {
  const int w = r.width;
  const LumSum lum = detail::reduce_rows<LumSum>(r.height, [&](int y0, int y1, LumSum& acc) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
      if (valid(r, t, v, i)) acc.sum += r.luminance(i), ++acc.n;
  });
  LeakResult res;
  res.reference_luminance_sum = lum.sum;
  res.valid_pixels = lum.n;
  res.dark_threshold = lum.n ? o.dark_fraction * lum.sum / double(lum.n) : 0.0;
  const bool declared = object_id != nullptr && !o.declared_object_ids.empty();
  std::vector<uint32_t> ids = o.declared_object_ids;
  std::sort(ids.begin(), ids.end());

  const RegionSums s = detail::reduce_rows<RegionSums>(r.height, [&](int y0, int y1, RegionSums& acc) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i) {
      if (!valid(r, t, v, i)) continue;
      const double e = leak_excess(r, t, v, i, o.sigma_factor);
      // "<=" so that an all-black reference makes every pixel part of the dark region.
      if (double(r.luminance(i)) <= res.dark_threshold) acc.auto_px++, acc.auto_excess += e, acc.auto_leaky += e > 0;
      if (declared) {
        const float id = object_id[i];
        if (std::isfinite(id) && id >= 0.0f &&
            std::binary_search(ids.begin(), ids.end(), uint32_t(std::lround(id))))
          acc.decl_px++, acc.decl_excess += e, acc.decl_leaky += e > 0;
      }
    }
  });
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto region = [&](size_t px, size_t leaky, double excess) {
    LeakRegion g;
    g.pixels = px;
    g.excess_sum = excess;
    g.leak = lum.sum > 0.0 ? excess / lum.sum : nan;
    g.leak_absolute = lum.n ? excess / double(lum.n) : nan;
    g.leak_pixels = px ? double(leaky) / double(px) : nan;
    return g;
  };
  res.automatic = region(s.auto_px, s.auto_leaky, s.auto_excess);
  if (declared) res.declared = region(s.decl_px, s.decl_leaky, s.decl_excess);
  return res;
}

Map leak_map(const RgbLayer& r, const RgbLayer& t, const RgbLayer* v, double sigma_factor) {
  Map m{"leak", "max(0, Y_T - Y_R - 3 sigma_Y,R)", "radiance", false, r.width, r.height, {}};
  m.values.resize(r.pixel_count());
  const int w = r.width;
  detail::for_rows(r.height, [&](int y0, int y1) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
      m.values[i] = valid(r, t, v, i) ? leak_excess(r, t, v, i, sigma_factor) : std::numeric_limits<float>::quiet_NaN();
  });
  return m;
}

}  // namespace giq::metrics
