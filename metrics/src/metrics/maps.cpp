#include "giq/metrics/maps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "giq/image/io.h"
#include "giq/metrics/colormap.h"
#include "giq/metrics/error.h"
#include "parallel.h"

namespace giq::metrics {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

template <class PixelFn>
Map make_map(const RgbLayer& ref, const RgbLayer& test, std::string name, std::string definition, std::string unit,
             bool is_signed, const PixelFn& fn) {
  Map m{std::move(name), std::move(definition), std::move(unit), is_signed, ref.width, ref.height, {}};
  m.values.resize(ref.pixel_count());
  const int w = ref.width;
  detail::for_rows(ref.height, [&](int y0, int y1) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
      m.values[i] = (ref.finite(i) && test.finite(i)) ? fn(i) : kNaN;
  });
  return m;
}

std::string format(float v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

}  // namespace

Map abs_error_map(const RgbLayer& r, const RgbLayer& t) {
  return make_map(r, t, "abs_error", "mean_c |T_c - R_c|", "radiance", false, [&](size_t i) {
    double s = 0;
    for (int k = 0; k < 3; ++k) s += std::abs(double(t.c[k][i]) - double(r.c[k][i]));
    return float(s / 3.0);
  });
}

Map relative_error_map(const RgbLayer& r, const RgbLayer& t) {
  return make_map(r, t, "relative_error", "mean_c (T_c - R_c)^2 / (R_c^2 + 0.01)", "1", false, [&](size_t i) {
    double s = 0;
    for (int k = 0; k < 3; ++k) {
      const double d = double(t.c[k][i]) - double(r.c[k][i]), rv = r.c[k][i];
      s += d * d / (rv * rv + kRelmseEpsilon);
    }
    return float(s / 3.0);
  });
}

Map signed_luminance_map(const RgbLayer& r, const RgbLayer& t) {
  return make_map(r, t, "signed_luminance_error", "Y_T - Y_R", "radiance", true,
                  [&](size_t i) { return t.luminance(i) - r.luminance(i); });
}

MapRange auto_range(const Map& map) {
  const size_t n = map.values.size();
  const size_t stride = std::max<size_t>(1, n >> 20);
  std::vector<float> sample;
  sample.reserve(n / stride + 1);
  for (size_t i = 0; i < n; i += stride) {
    const float v = map.values[i];
    if (std::isfinite(v)) sample.push_back(map.is_signed ? std::fabs(v) : v);
  }
  float p = 0.0f;
  if (!sample.empty()) {
    const size_t k = std::min(sample.size() - 1, size_t(std::ceil(0.99 * double(sample.size()))) - 1);
    std::nth_element(sample.begin(), sample.begin() + std::ptrdiff_t(k), sample.end());
    p = sample[k];
  }
  if (!(p > 0.0f) || !std::isfinite(p)) p = 1.0f;
  MapRange r;
  r.lo = map.is_signed ? -p : 0.0f;
  r.hi = p;
  r.rule = map.is_signed ? "symmetric, 99th percentile of |value| (1 when that is 0)"
                         : "0 to the 99th percentile (1 when that is 0)";
  return r;
}

std::vector<uint8_t> colourise(const Map& map, const MapRange& range) {
  std::vector<uint8_t> rgb(map.values.size() * 3);
  const float span = range.hi - range.lo;
  detail::for_rows(map.height, [&](int y0, int y1) {
    for (size_t i = size_t(y0) * size_t(map.width), end = size_t(y1) * size_t(map.width); i < end; ++i) {
      const float v = map.values[i];
      Rgb8 c = kInvalidColour;
      if (std::isfinite(v)) {
        const float t = (v - range.lo) / span;  // [0, 1] across the range
        c = map.is_signed ? diverging(2.0f * t - 1.0f) : magma(t);
      }
      rgb[i * 3] = c.r, rgb[i * 3 + 1] = c.g, rgb[i * 3 + 2] = c.b;
    }
  });
  return rgb;
}

WrittenMap write_map(const Map& map, const std::filesystem::path& dir, const MapRange& range) {
  WrittenMap out;
  out.exr = dir / (map.name + ".exr");
  out.png = dir / (map.name + ".png");
  out.range = range;
  out.colormap = map.is_signed ? "blue-white-red" : "magma";
  {
    image::Image im(map.width, map.height);
    float* y = im.add_channel("Y");
    std::copy(map.values.begin(), map.values.end(), y);
    im.metadata["giq:map"] = map.name;
    im.metadata["giq:definition"] = map.definition;
    im.metadata["giq:unit"] = map.unit;
    image::write_exr(im, out.exr);
  }
  const std::vector<uint8_t> rgb = colourise(map, range);
  image::write_png_rgb8(out.png, map.width, map.height, 3, rgb.data(),
                        {{"giq:map", map.name},
                         {"giq:definition", map.definition},
                         {"giq:unit", map.unit},
                         {"giq:colormap", out.colormap},
                         {"giq:range_min", format(range.lo)},
                         {"giq:range_max", format(range.hi)},
                         {"giq:range_rule", range.rule},
                         {"giq:invalid_colour", "green (0,255,0): pixel excluded (NaN/Inf input)"}});
  return out;
}

}  // namespace giq::metrics
