#pragma once
// Synthetic images for the metric tests: values chosen so every expected number has a closed
// form.

#include <cstdint>
#include <functional>
#include <string>

#include "giq/image/image.h"

namespace giq::test {

// An image with an RGB layer (prefix "" = beauty) filled by f(x, y, channel).
inline image::Image rgb_image(int w, int h, const std::function<float(int, int, int)>& f,
                              const std::string& layer = "") {
  image::Image im(w, h);
  const std::string p = layer.empty() ? "" : layer + ".";
  const char* names[3] = {"R", "G", "B"};
  for (int k = 0; k < 3; ++k) {
    float* c = im.add_channel(p + names[k]);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) c[im.index(x, y)] = f(x, y, k);
  }
  return im;
}

inline void add_layer(image::Image& im, const std::string& layer, const std::function<float(int, int, int)>& f) {
  const char* names[3] = {"R", "G", "B"};
  for (int k = 0; k < 3; ++k) {
    float* c = im.add_channel(layer + "." + names[k]);
    for (int y = 0; y < im.height(); ++y)
      for (int x = 0; x < im.width(); ++x) c[im.index(x, y)] = f(x, y, k);
  }
}

// Deterministic pseudo-random value in [0, 1) of (x, y, k, seed) (integer hash, not a sampler).
inline float hash01(int x, int y, int k, uint32_t seed = 1) {
  uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u ^ uint32_t(k) * 0xcb1ab31fu ^ seed * 0x9e3779b9u;
  h ^= h >> 16, h *= 0x7feb352du, h ^= h >> 15, h *= 0x846ca68bu, h ^= h >> 16;
  return float(h >> 8) * (1.0f / 16777216.0f);
}

}  // namespace giq::test
