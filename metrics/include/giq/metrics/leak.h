#pragma once
// Light leaking (docs/metrics.md, "Leaking"): light a technique puts where the truth has
// (almost) none, typically through a thin wall.
//   excess(p) = max(0, Y_T(p) - Y_R(p) - 3 sigma_Y,R(p))   brightening beyond the reference noise
//   leak      = sum_region excess / sum_image Y_R           share of the true light that leaked in
//   leak_pixels = |{p in region : excess(p) > 0}| / |region|
// over two kinds of region: declared (pixels whose reference objectId is one of the scene's
// leak-region objects) and automatic (pixels with Y_R <= 5% of the image's mean Y_R).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "giq/metrics/layer.h"
#include "giq/metrics/maps.h"

namespace giq::metrics {

struct LeakOptions {
  std::vector<uint32_t> declared_object_ids;  // the scene's leak regions (objectId values)
  double dark_fraction = 0.05;                // automatic region: Y_R <= 5% of mean Y_R
  double sigma_factor = 3.0;                  // excess counts beyond 3 sigma of the reference
};

struct LeakRegion {
  size_t pixels = 0;           // valid pixels in the region
  double excess_sum = 0.0;     // sum of excess over the region (radiance x pixels)
  double leak = 0.0;           // excess_sum / sum_image Y_R; NaN when the reference is black
  double leak_absolute = 0.0;  // excess_sum / valid image pixels: mean leaked radiance per pixel
  double leak_pixels = 0.0;    // share of region pixels with excess > 0; NaN for an empty region
};

struct LeakResult {
  double reference_luminance_sum = 0.0;   // sum_image Y_R over valid pixels
  double dark_threshold = 0.0;            // luminance bound of the automatic region
  size_t valid_pixels = 0;
  LeakRegion automatic;
  std::optional<LeakRegion> declared;     // when object ids and an objectId layer were given
};

// excess(p) at pixel i; variance may be nullptr (no reference noise known: sigma = 0).
float leak_excess(const RgbLayer& reference, const RgbLayer& test, const RgbLayer* variance, size_t i,
                  double sigma_factor = 3.0);

// object_id: the reference's objectId plane, or nullptr (then no declared region).
LeakResult leak(const RgbLayer& reference, const RgbLayer& test, const RgbLayer* variance, const float* object_id,
                const LeakOptions& options = {});

// The excess map (NaN where excluded).
Map leak_map(const RgbLayer& reference, const RgbLayer& test, const RgbLayer* variance, double sigma_factor = 3.0);

}  // namespace giq::metrics
