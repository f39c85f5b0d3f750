#pragma once
// The sRGB transfer function (IEC 61966-2-1:1999, the piecewise curve with the linear toe),
// shared by PNG writing, 8-bit decoding and the display-referred metrics (SSIM, PSNR).

#include <cmath>

namespace giq::image {

// Linear [0,1] -> encoded [0,1]. Input outside [0,1] is clamped first.
inline float srgb_encode(float linear) {
  float v = linear < 0.0f ? 0.0f : (linear > 1.0f ? 1.0f : linear);
  if (v >= 1.0f) return 1.0f;  // 1.055 - 0.055 rounds to 0.99999994 in float
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// Encoded [0,1] -> linear [0,1].
inline float srgb_decode(float encoded) {
  float v = encoded < 0.0f ? 0.0f : (encoded > 1.0f ? 1.0f : encoded);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

}  // namespace giq::image
