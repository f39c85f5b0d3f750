#pragma once
// SSIM (Wang, Bovik, Sheikh, Simoncelli, "Image Quality Assessment: From Error Visibility to
// Structural Similarity", IEEE TIP 13(4), 2004), on the luma of the display-referred images
// (each channel clamped to [0, 1] and sRGB-encoded, then 0.2126 R' + 0.7152 G' + 0.0722 B'),
// 11x11 Gaussian window with sigma 1.5, K1 = 0.01, K2 = 0.03, dynamic range L = 1 (eq. 13).
//
// The window is separable and applied in two 1D passes over bands of rows, so working memory
// is O(width x band) whatever the image height. Pixels that are non-finite in either input
// carry weight 0 and the window is renormalised over the valid pixels it covers; the image
// border is handled the same way (pixels outside have weight 0). For an image at least 11
// pixels wide and tall and no invalid pixels, interior values equal Wang's; the mean runs over
// every valid pixel instead of only the "valid" convolution region, so small and single-pixel
// images have a defined SSIM (docs/metrics.md).

#include <vector>

#include "giq/metrics/layer.h"

namespace giq::metrics {

struct SsimOptions {
  int radius = 5;       // 11x11 window
  double sigma = 1.5;
  double k1 = 0.01;
  double k2 = 0.03;
};

struct SsimResult {
  double mean = 0.0;        // NaN when no pixel is valid
  size_t valid_pixels = 0;
  std::vector<float> map;   // per pixel (NaN where invalid); filled only when asked for
};

// The display-referred luma used by ssim(): NaN where the pixel is not finite.
float display_luma(const RgbLayer& image, size_t i);

SsimResult ssim(const RgbLayer& reference, const RgbLayer& test, bool keep_map = false,
                const SsimOptions& options = {});

// SSIM of two single-channel planes already in [0, 1] (NaN marks an invalid pixel).
SsimResult ssim_planes(const float* x, const float* y, int width, int height, bool keep_map = false,
                       const SsimOptions& options = {});

}  // namespace giq::metrics
