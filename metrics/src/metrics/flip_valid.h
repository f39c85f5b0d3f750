#pragma once
// Internal: FLIP on a pair that may hold NaN/Inf. FLIP filters spread a non-finite value over
// its neighbourhood, so such pixels are first set to 0 in both images (no difference of their
// own), and the mean and max are taken over the valid pixels only. The weighted median and
// quartiles weight each pixel by its own FLIP value, so the zeroed pixels carry ~no weight.

#include <string_view>

#include "giq/image/image.h"
#include "giq/metrics/flip.h"

namespace giq::metrics::detail {

FlipResult flip_valid(const image::Image& reference, const image::Image& test, std::string_view layer, bool hdr);

}  // namespace giq::metrics::detail
