#include "exposure.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "constants.h"
#include "giq/base/error.h"

namespace giq::metrics::flip {

float aces_x_max() {
  // (k0 - t k3) x^2 + (k1 - t k4) x - t k5 = 0; a > 0 and c < 0, so the roots have opposite signs
  // and x_max is the positive one.
  using K = AcesCoefficients;
  const float t = kToneMappedTarget;
  const float a = K::k0 - t * K::k3, b = K::k1 - t * K::k4, c = -t * K::k5;
  const float mid = -0.5f * b / a;
  return mid + std::sqrt(mid * mid - c / a);
}

std::vector<float> ExposureRange::stops() const {
  std::vector<float> out(size_t(std::max(count, 0)));
  const float step = count > 1 ? (stop - start) / float(count - 1) : 0.0f;
  for (int i = 0; i < count; ++i) out[size_t(i)] = start + float(i) * step;
  return out;
}

ExposureRange choose_exposure_range(const float* r, const float* g, const float* b, size_t pixel_count,
                                    std::optional<float> start, std::optional<float> stop,
                                    std::optional<int> count) {
  ExposureRange range;
  if (!start || !stop) {
    std::vector<float> luminance(pixel_count);
    float y_max = 0.0f;
    size_t positive = 0;
    for (size_t i = 0; i < pixel_count; ++i) {
      const float y = 0.2126f * r[i] + 0.7152f * g[i] + 0.0722f * b[i];
      luminance[i] = y;
      y_max = std::max(y_max, y);
      positive += y > 0.0f;
    }
    float computed_start = 0.0f, computed_stop = 0.0f;
    if (y_max > 0.0f) {
      // The paper's median is the middle element (the upper one for an even count). When it is
      // not positive, log2(x_max / median) is undefined: use the median of the lit pixels.
      size_t mid = pixel_count / 2;
      std::nth_element(luminance.begin(), luminance.begin() + ptrdiff_t(mid), luminance.end());
      float y_median = luminance[mid];
      if (y_median <= 0.0f) {
        auto lit_end = std::partition(luminance.begin(), luminance.end(), [](float y) { return y > 0.0f; });
        mid = positive / 2;
        std::nth_element(luminance.begin(), luminance.begin() + ptrdiff_t(mid), lit_end);
        y_median = luminance[mid];
      }
      const float x_max = aces_x_max();
      computed_start = std::log2(x_max / y_max);
      computed_stop = std::log2(x_max / y_median);
    }
    range.start = start.value_or(computed_start);
    range.stop = stop.value_or(computed_stop);
  } else {
    range.start = *start;
    range.stop = *stop;
  }
  if (!std::isfinite(range.start) || !std::isfinite(range.stop) || range.start > range.stop)
    throw InputError("", "start_exposure/stop_exposure",
                     "the HDR-FLIP exposure range must be finite with start <= stop, got start " +
                         std::to_string(range.start) + ", stop " + std::to_string(range.stop));
  if (count) {
    if (*count < 1)
      throw InputError("", "exposures", "the number of HDR-FLIP exposures must be at least 1, got " +
                                            std::to_string(*count));
    range.count = *count;
  } else {
    range.count = int(std::max(2.0f, std::ceil(range.stop - range.start)));
  }
  return range;
}

}  // namespace giq::metrics::flip
