#pragma once
// HDR-FLIP's exposures: the tone mapper that turns each exposure of an HDR image into a display
// image, and the exposure range chosen from the reference ([HDRFLIP], see constants.h).

#include <cstddef>
#include <optional>
#include <vector>

namespace giq::metrics::flip {

// [HDRFLIP] tone mapper: Narkowicz's fit of the ACES filmic curve (2015),
//   t(x) = x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),
// applied to x = 0.6 c, the 0.6 cancelling the pre-exposure the fit bakes in. Written as the
// rational function (k0 c^2 + k1 c) / (k3 c^2 + k4 c + k5) of the exposed channel value c.
struct AcesCoefficients {
  static constexpr float k0 = 0.6f * 0.6f * 2.51f;
  static constexpr float k1 = 0.6f * 0.03f;
  static constexpr float k3 = 0.6f * 0.6f * 2.43f;
  static constexpr float k4 = 0.6f * 0.59f;
  static constexpr float k5 = 0.14f;
};
template <class T>  // float or Float4
inline T tone_map_aces(T c) {
  using K = AcesCoefficients;
  return (c * c * K::k0 + c * K::k1) / (c * c * K::k3 + c * K::k4 + K::k5);
}

// [HDRFLIP] x_max: the exposed luminance that the tone mapper maps to 0.85, the larger root of
// t(x) = 0.85 (a quadratic once the denominator is multiplied out).
float aces_x_max();

struct ExposureRange {
  float start = 0.0f;
  float stop = 0.0f;
  int count = 0;
  std::vector<float> stops() const;  // the exposures in stops, start to stop, evenly spaced
};

// [HDRFLIP] exposure range from the reference's luminance Y (BT.709 weights):
//   start = log2(x_max / max Y)   (the brightest pixel just reaches 0.85),
//   stop  = log2(x_max / median Y) (the median pixel reaches 0.85),
//   count = max(2, ceil(stop - start)) (about one exposure per stop).
// The paper leaves two cases undefined, which giq defines (docs/flip.md): when more than half
// of the pixels have Y <= 0, the median is taken over the pixels with Y > 0; when no pixel has
// Y > 0, start = stop = 0. Explicit start/stop/count override the computed ones; throws
// InputError when start > stop or count < 1.
ExposureRange choose_exposure_range(const float* r, const float* g, const float* b, size_t pixel_count,
                                    std::optional<float> start, std::optional<float> stop,
                                    std::optional<int> count);

}  // namespace giq::metrics::flip
