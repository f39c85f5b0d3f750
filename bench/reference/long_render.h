#pragma once
// The long render that the benchmarks measure error against, and the error measure.
//
// relMSE = mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01). The long render is
// itself a noisy estimate: for an independent, unbiased test image x,
//   E[(x - ref)^2] = Var(x) + Var(ref) + bias(x)^2,
// so the long render's own contribution, mean of Var(ref) / (ref^2 + 0.01) with Var(ref) the
// per-pixel variance of its mean (Welford, reference/film.h), is subtracted: what remains
// estimates the test image's own error, whatever the long render's spp.

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "giq/image/image.h"
#include "giq/reference/film.h"

namespace giq::bench {

struct LongRender {
  int width = 0;
  int height = 0;
  std::vector<double> mean;      // 3 per pixel, row-major, top row first
  std::vector<double> variance;  // of the mean, 3 per pixel
  double variance_term = 0.0;    // its own contribution to relMSE (subtracted)
  double spp = 0.0;
  std::string scene_hash, view, settings;  // of a file: giq.scene_hash, giq.view, giq.settings

  static LongRender from_film(const reference::Film& film);
  // A reference EXR (R,G,B, variance.R/G/B, spp) as `giq reference` writes it.
  static LongRender from_exr(const std::filesystem::path& path);

  // relMSE of test(pixel, channel) against this render, its own variance term subtracted.
  template <class Test>
  double rel_mse_of(Test&& test) const {
    double sum = 0.0;
    const size_t n = mean.size() / 3;
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        const double r = mean[3 * i + size_t(c)], d = double(test(i, c)) - r;
        sum += d * d / (r * r + 0.01);
      }
    return sum / double(mean.size()) - variance_term;
  }
  double rel_mse(const reference::Film& film) const {
    return rel_mse_of([&](size_t i, int c) { return film.pixels[i].mean[c]; });
  }
  // The beauty (R,G,B) of an image of the same size; throws InputError otherwise.
  double rel_mse(const image::Image& image, const std::filesystem::path& file) const;
};

}  // namespace giq::bench
