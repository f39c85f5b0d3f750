#include "giq/metrics/strip.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "giq/image/io.h"
#include "giq/image/srgb.h"
#include "giq/metrics/colormap.h"
#include "parallel.h"

namespace giq::metrics {
namespace {

// Box filter of the source pixels that fall in panel pixel (px, py); fn(i, acc[3]) adds pixel
// i's value and returns false when the pixel is not finite.
template <class Fn>
bool box(int w, int h, int pw, int ph, int px, int py, double out[3], const Fn& fn) {
  const int x0 = int(int64_t(px) * w / pw), x1 = std::max(x0 + 1, int(int64_t(px + 1) * w / pw));
  const int y0 = int(int64_t(py) * h / ph), y1 = std::max(y0 + 1, int(int64_t(py + 1) * h / ph));
  out[0] = out[1] = out[2] = 0.0;
  size_t n = 0;
  bool bad = false;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      if (fn(size_t(y) * size_t(w) + size_t(x), out)) ++n;
      else bad = true;
    }
  if (n) out[0] /= double(n), out[1] /= double(n), out[2] /= double(n);
  return !bad;
}

}  // namespace

StripInfo write_strip(const std::filesystem::path& path, const RgbLayer& ref, const RgbLayer& test, const Map& error,
                      const MapRange& range, bool hdr, int max_panel) {
  const int w = ref.width, h = ref.height;
  const double scale = std::min(1.0, double(max_panel) / double(std::max(w, h)));
  StripInfo info;
  info.panel_width = std::max(1, int(std::lround(w * scale)));
  info.panel_height = std::max(1, int(std::lround(h * scale)));
  const detail::MeanSum lum = detail::reduce_rows<detail::MeanSum>(h, [&](int y0, int y1, detail::MeanSum& acc) {
    for (size_t i = size_t(y0) * size_t(w), end = size_t(y1) * size_t(w); i < end; ++i)
      if (ref.finite(i)) acc.sum += ref.luminance(i), ++acc.n;
  });
  const double mean = lum.n ? lum.sum / double(lum.n) : 0.0;
  info.exposure = (hdr && mean > 0.0) ? float(std::log2(0.18 / mean)) : 0.0f;
  const float gain = std::exp2(info.exposure);

  const int pw = info.panel_width, ph = info.panel_height, sw = 3 * pw;
  std::vector<uint8_t> rgb(size_t(sw) * size_t(ph) * 3);
  auto put = [&](int x, int y, Rgb8 c) {
    uint8_t* p = &rgb[(size_t(y) * size_t(sw) + size_t(x)) * 3];
    p[0] = c.r, p[1] = c.g, p[2] = c.b;
  };
  auto tone = [&](const double v[3], bool ok) {
    if (!ok) return Rgb8{255, 0, 255};  // magenta, as write_png marks NaN/Inf
    auto e = [&](double c) { return uint8_t(std::lround(image::srgb_encode(float(c) * gain) * 255.0f)); };
    return Rgb8{e(v[0]), e(v[1]), e(v[2])};
  };
  detail::for_rows(ph, [&](int y0, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = 0; px < pw; ++px) {
        double v[3];
        for (int panel = 0; panel < 2; ++panel) {
          const RgbLayer& im = panel == 0 ? ref : test;
          const bool ok = box(w, h, pw, ph, px, py, v, [&](size_t i, double* acc) {
            if (!im.finite(i)) return false;
            for (int k = 0; k < 3; ++k) acc[k] += im.c[k][i];
            return true;
          });
          put(panel * pw + px, py, tone(v, ok));
        }
        const bool ok = box(w, h, pw, ph, px, py, v, [&](size_t i, double* acc) {
          if (!std::isfinite(error.values[i])) return false;
          acc[0] += error.values[i];
          return true;
        });
        const float t = float((v[0] - range.lo) / (range.hi - range.lo));
        put(2 * pw + px, py, !ok ? kInvalidColour : error.is_signed ? diverging(2 * t - 1) : magma(t));
      }
  });
  image::write_png_rgb8(path, sw, ph, 3, rgb.data(),
                        {{"giq:panels", "reference | technique | " + error.name},
                         {"giq:exposure", std::to_string(info.exposure)},
                         {"giq:error_colormap", error.is_signed ? "blue-white-red" : "magma"},
                         {"giq:error_range_min", std::to_string(range.lo)},
                         {"giq:error_range_max", std::to_string(range.hi)}});
  return info;
}

}  // namespace giq::metrics
