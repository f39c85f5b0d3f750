#include "giq/metrics/colormap.h"

#include <algorithm>
#include <cmath>

#include "giq/image/srgb.h"

namespace giq::metrics {
namespace {

struct Sample {
  float r, g, b;
};

// magma at t = 0, 1/8, ..., 1 (see colormap.h for the source of these nine colours).
constexpr Sample kMagma[9] = {{0x00, 0x00, 0x04}, {0x1D, 0x11, 0x47}, {0x51, 0x12, 0x7C},
                              {0x82, 0x26, 0x81}, {0xB6, 0x36, 0x79}, {0xE6, 0x51, 0x64},
                              {0xFB, 0x88, 0x61}, {0xFE, 0xC2, 0x87}, {0xFC, 0xFD, 0xBF}};

uint8_t to8(float v) { return uint8_t(std::lround(std::fmin(std::fmax(v, 0.0f), 255.0f))); }

float decode8(float c) { return image::srgb_decode(c / 255.0f); }

}  // namespace

Rgb8 magma(float t) {
  if (std::isnan(t)) return kInvalidColour;
  t = std::fmin(std::fmax(t, 0.0f), 1.0f) * 8.0f;
  const int k = std::min(int(t), 7);
  const float f = t - float(k);
  const Sample& a = kMagma[k];
  const Sample& b = kMagma[k + 1];
  return {to8(a.r + f * (b.r - a.r)), to8(a.g + f * (b.g - a.g)), to8(a.b + f * (b.b - a.b))};
}

Rgb8 diverging(float t) {
  if (std::isnan(t)) return kInvalidColour;
  t = std::fmin(std::fmax(t, -1.0f), 1.0f);
  const Sample end = t < 0 ? Sample{59, 76, 192} : Sample{180, 4, 38};
  const float f = std::fabs(t);
  auto mix = [&](float c) {
    const float linear = (1.0f - f) * 1.0f + f * decode8(c);
    return to8(image::srgb_encode(linear) * 255.0f);
  };
  return {mix(end.r), mix(end.g), mix(end.b)};
}

}  // namespace giq::metrics
