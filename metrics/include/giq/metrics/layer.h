#pragma once
// The RGB layer a metric compares (`--layer indirect` -> indirect.R/G/B), checked once at the
// boundary so every metric below can assume two same-sized, three-channel inputs.

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "giq/image/image.h"

namespace giq::metrics {

// Non-owning planar view of one RGB layer.
struct RgbLayer {
  const float* c[3] = {nullptr, nullptr, nullptr};
  int width = 0;
  int height = 0;
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  bool finite(size_t i) const;  // all three channels finite at pixel i
  float luminance(size_t i) const { return image::luminance(c[0][i], c[1][i], c[2][i]); }
};

// The RGB layer `layer` of `image` ("" or "beauty" = R,G,B). Throws InputError(file, layer, ...)
// naming the layers present when it is missing.
RgbLayer rgb_layer(const image::Image& image, std::string_view layer, const std::string& file);

// The channels that belong to `layer` ("" -> R,G,B,A present; "indirect" -> indirect.*).
std::vector<std::string> layer_channel_set(const image::Image& image, std::string_view layer);

// Validates a reference/technique pair for `layer`: same width and height, the layer present
// in both with the same channel count. Throws InputError naming the offending file.
void check_pair(const image::Image& reference, const std::string& reference_file, const image::Image& test,
                const std::string& test_file, std::string_view layer);

// Per-pixel variance of the mean of `layer` in the reference, when the reference carries it:
// "<layer>.variance" if present, else the beauty "variance" layer (a stand-in for a component
// layer: see docs/metrics.md). Returns the layer name used, or "" when there is none.
std::string variance_layer_for(const image::Image& reference, std::string_view layer);

// Variance of the luminance estimate from per-channel variances. The channels of one pixel
// come from the same light paths, so they are strongly positively correlated; the bound for
// perfect correlation, sigma_Y = sum_c w_c sigma_c (Minkowski), is used (docs/metrics.md).
inline float luminance_variance(float vr, float vg, float vb) {
  auto s = [](float v) { return v > 0.0f ? std::sqrt(v) : 0.0f; };
  const float sy = 0.2126f * s(vr) + 0.7152f * s(vg) + 0.0722f * s(vb);
  return sy * sy;
}

}  // namespace giq::metrics
