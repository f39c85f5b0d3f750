#include "giq/metrics/flip.h"

#include <cmath>
#include <string>

#include "evaluator.h"
#include "exposure.h"
#include "giq/base/error.h"
#include "pooling.h"

namespace giq::metrics {
namespace flip {

FlipResult evaluate(const ImagePair& pair, bool hdr, const FlipOptions& options) {
  if (!(options.pixels_per_degree > 0.0) || !std::isfinite(options.pixels_per_degree))
    throw InputError("", "pixels_per_degree",
                     "FLIP needs a positive, finite number of pixels per degree, got " +
                         std::to_string(options.pixels_per_degree));
  FlipResult result;
  result.width = pair.width;
  result.height = pair.height;
  const size_t n = size_t(pair.width) * size_t(pair.height);
  result.map.assign(n, 0.0f);
  if (n == 0) return result;

  DisplayMapping mapping;
  mapping.hdr = hdr;
  if (hdr) {
    // The range is chosen from the sanitised reference (non-finite values count as 0), the same
    // values the error map sees.
    std::vector<float> r, g, b;
    const float* planes[3] = {pair.reference.r, pair.reference.g, pair.reference.b};
    bool finite = true;
    for (size_t i = 0; i < n && finite; ++i)
      finite = std::isfinite(planes[0][i]) && std::isfinite(planes[1][i]) && std::isfinite(planes[2][i]);
    if (!finite) {
      std::vector<float>* copies[3] = {&r, &g, &b};
      for (int c = 0; c < 3; ++c) {
        copies[c]->resize(n);
        for (size_t i = 0; i < n; ++i) (*copies[c])[i] = std::isfinite(planes[c][i]) ? planes[c][i] : 0.0f;
        planes[c] = copies[c]->data();
      }
    }
    const ExposureRange range = choose_exposure_range(planes[0], planes[1], planes[2], n, options.start_exposure,
                                                      options.stop_exposure, options.exposures);
    result.start_exposure = range.start;
    result.stop_exposure = range.stop;
    result.exposures = range.count;
    mapping.exposure_stops = range.stops();
  }
  compute_error_map(pair, float(options.pixels_per_degree), mapping, result.map.data());

  const PooledErrors pooled = pool_errors(result.map.data(), n);
  result.mean = pooled.mean;
  result.weighted_median = pooled.weighted_median;
  result.weighted_q1 = pooled.weighted_q1;
  result.weighted_q3 = pooled.weighted_q3;
  result.max = pooled.max;
  return result;
}

}  // namespace flip

namespace {

flip::ImagePair unpack(const image::Image& reference, const image::Image& test, std::string_view layer) {
  if (reference.width() != test.width() || reference.height() != test.height())
    throw InputError("", "test", "FLIP needs images of equal size: reference " + std::to_string(reference.width()) +
                                     "x" + std::to_string(reference.height()) + ", test " +
                                     std::to_string(test.width()) + "x" + std::to_string(test.height()));
  const auto ref_names = reference.layer_channels(layer);
  const auto test_names = test.layer_channels(layer);
  flip::ImagePair pair;
  pair.width = reference.width();
  pair.height = reference.height();
  // Image::channel throws InputError naming the missing channel and the ones present.
  pair.reference = {reference.channel(ref_names[0]), reference.channel(ref_names[1]), reference.channel(ref_names[2])};
  pair.test = {test.channel(test_names[0]), test.channel(test_names[1]), test.channel(test_names[2])};
  return pair;
}

}  // namespace

FlipResult hdr_flip(const image::Image& reference, const image::Image& test, std::string_view layer,
                    const FlipOptions& options) {
  return flip::evaluate(unpack(reference, test, layer), true, options);
}

FlipResult ldr_flip(const image::Image& reference, const image::Image& test, std::string_view layer,
                    const FlipOptions& options) {
  return flip::evaluate(unpack(reference, test, layer), false, options);
}

}  // namespace giq::metrics
