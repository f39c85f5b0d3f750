#include "giq/metrics/flip.h"

#include <cmath>
#include <limits>

#include "giq/metrics/layer.h"

namespace giq::metrics {

FlipResult flip_valid(const image::Image& ref, const image::Image& test, std::string_view layer, bool hdr,
                      const FlipOptions& options) {
  const RgbLayer r = rgb_layer(ref, layer, ""), t = rgb_layer(test, layer, "");
  const size_t n = r.pixel_count();
  size_t bad = 0;
  for (size_t i = 0; i < n; ++i) bad += !(r.finite(i) && t.finite(i));
  auto run = [&](const image::Image& a, const image::Image& b, std::string_view l) {
    return hdr ? hdr_flip(a, b, l, options) : ldr_flip(a, b, l, options);
  };
  if (!bad) return run(ref, test, layer);

  // Copies of the compared layer only, with the invalid pixels zeroed in both.
  image::Image a(r.width, r.height), b(r.width, r.height);
  const char* names[3] = {"R", "G", "B"};
  for (int k = 0; k < 3; ++k) {
    float* pa = a.add_channel(names[k]);
    float* pb = b.add_channel(names[k]);
    for (size_t i = 0; i < n; ++i) {
      const bool ok = r.finite(i) && t.finite(i);
      pa[i] = ok ? r.c[k][i] : 0.0f;
      pb[i] = ok ? t.c[k][i] : 0.0f;
    }
  }
  FlipResult f = run(a, b, "");
  double sum = 0.0, mx = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (!(r.finite(i) && t.finite(i))) {
      f.map[i] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    sum += f.map[i];
    mx = std::max(mx, double(f.map[i]));
  }
  f.mean = n > bad ? sum / double(n - bad) : std::numeric_limits<double>::quiet_NaN();
  f.max = mx;
  return f;
}

}  // namespace giq::metrics
