#pragma once
// The FLIP error map of an image pair: LDR-FLIP for one display image pair, or HDR-FLIP's
// per-pixel maximum of LDR-FLIP over the tone-mapped exposures of an HDR pair.

#include <vector>

namespace giq::metrics::flip {

struct RgbPlanes {
  const float* r = nullptr;
  const float* g = nullptr;
  const float* b = nullptr;
};

struct ImagePair {
  RgbPlanes reference, test;
  int width = 0, height = 0;
};

// How the linear RGB input becomes display values in [0, 1] before LDR-FLIP.
struct DisplayMapping {
  bool hdr = false;                  // false: clamp to [0, 1] (LDR-FLIP input)
  std::vector<float> exposure_stops; // hdr: scale by 2^stop, ACES tone map, clamp; one pass each
};

// Writes width x height values in [0, 1] to `map`. Non-finite input values are sanitised per
// channel before anything else: a non-finite reference value becomes 0 and a non-finite test
// value takes the (sanitised) reference value, so it adds no error of its own.
void compute_error_map(const ImagePair& pair, float pixels_per_degree, const DisplayMapping& mapping,
                       float* map);

}  // namespace giq::metrics::flip
