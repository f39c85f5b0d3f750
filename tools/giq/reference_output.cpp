#include "reference_output.h"

#include <cmath>
#include <cstdio>

namespace giq::cli {

// The output path of one frame: "#" runs are replaced by the zero-padded frame number;
// otherwise, when several frames are rendered, ".<frame>" goes before the extension.
std::filesystem::path frame_path(const std::string& pattern, int frame, bool several) {
  const size_t hash = pattern.find('#');
  if (hash != std::string::npos) {
    size_t n = 0;
    while (hash + n < pattern.size() && pattern[hash + n] == '#') ++n;
    std::string num = std::to_string(frame);
    if (num.size() < n) num.insert(0, n - num.size(), '0');
    return pattern.substr(0, hash) + num + pattern.substr(hash + n);
  }
  if (!several) return pattern;
  std::filesystem::path p(pattern);
  char num[16];
  std::snprintf(num, sizeof num, ".%04d", frame);
  return p.parent_path() / (p.stem().string() + num + p.extension().string());
}

// --half: the colour layers (beauty, direct, indirect, albedo) as float16, a third of the
// size of float32 with zip compression on noisy data. Half keeps 11 significant bits, a
// relative rounding error of at most 2^-11 (4.9e-4), far below the per-pixel noise of any
// finite-spp render (golden/README.md has the measured ratio). The variance layer stays
// float32: it spans many decades and is squared into z-scores and noise floors; so do depth,
// normals, object ids and the sample count. A channel with a finite value beyond half's range
// (65504) stays float32 rather than turn into infinity.
image::ExrOptions exr_options(const image::Image& img, bool half) {
  image::ExrOptions opts;
  if (!half) return opts;
  for (const char* layer : {"", "direct", "indirect", "albedo"}) {
    if (!img.has_layer(layer)) continue;
    for (const std::string& name : img.layer_channels(layer)) {
      const float* c = img.channel(name);
      bool fits = true;
      for (size_t i = 0; i < img.pixel_count() && fits; ++i) fits = !(std::fabs(c[i]) > 65504.0f);
      if (fits) opts.half_channels.insert(name);
    }
  }
  return opts;
}

}  // namespace giq::cli
