#pragma once
// Colour maps for heat maps.
//  magma: the perceptually uniform map of van der Walt and Smith (matplotlib 1.5, 2015), here as
//    its nine published samples at t = k/8 (the hex values listed by the viridis colour-map
//    documentation: #000004 #1D1147 #51127C #822681 #B63679 #E65164 #FB8861 #FEC287 #FCFDBF),
//    linearly interpolated between samples in sRGB-encoded space. Dark = small.
//  diverging: blue (too dark) - white (0) - red (too bright). The end colours are the blue and
//    red of Moreland's "Diverging Color Maps for Scientific Visualization" (ISVC 2009),
//    sRGB (59, 76, 192) and (180, 4, 38); each half interpolates linearly in linear-light RGB
//    between white and the end colour, then encodes to sRGB, so equal steps of |t| look
//    roughly equally strong.
// Pixels without a value (NaN/Inf) are painted kInvalidColour, pure green, which neither map
// contains.

#include <cstdint>

namespace giq::metrics {

struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
};

inline constexpr Rgb8 kInvalidColour{0, 255, 0};

Rgb8 magma(float t);       // t in [0, 1], clamped
Rgb8 diverging(float t);   // t in [-1, 1], clamped

}  // namespace giq::metrics
