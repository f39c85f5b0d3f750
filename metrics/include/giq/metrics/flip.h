#pragma once
// FLIP, the perceptual difference evaluator for alternating images:
//   LDR-FLIP: Andersson, Nilsson, Akenine-Moeller, Oskarsson, Astroem, Fairchild,
//             "FLIP: A Difference Evaluator for Alternating Images", HPG 2020.
//   HDR-FLIP: Andersson, Nilsson, Shirley, Akenine-Moeller, "Visualizing and Communicating
//             Errors in Rendered Images", Ray Tracing Gems II, ch. 19, 2021.
// The maps agree with NVIDIA's reference implementation (tests/metrics/flip_*).

#include <optional>
#include <string_view>
#include <vector>

#include "giq/image/image.h"

namespace giq::metrics {

struct FlipOptions {
  // 0.7 m from a 0.7 m wide 4K monitor (the papers' default): 0.7 m * (3840 px / 0.7 m) * pi / 180
  // = 67.0206 pixels per degree, the value NVIDIA's implementation uses by default.
  double pixels_per_degree = 67.02064327658226;
  // HDR only: exposure range in stops; when unset, chosen from the reference as HDR-FLIP does.
  std::optional<float> start_exposure;
  std::optional<float> stop_exposure;
  std::optional<int> exposures;  // number of exposures; default max(2, ceil(stop - start))
};

struct FlipResult {
  std::vector<float> map;  // per pixel in [0, 1], row-major, width x height
  int width = 0;
  int height = 0;
  double mean = 0.0;
  // Weighted percentiles as the FLIP tool reports them (each pixel weighted by its error).
  double weighted_median = 0.0;
  double weighted_q1 = 0.0;
  double weighted_q3 = 0.0;
  double max = 0.0;
  // HDR only: the exposure range actually used.
  float start_exposure = 0.0f;
  float stop_exposure = 0.0f;
  int exposures = 0;
};

// Linear HDR radiance in, as stored in giq's EXR files: RGB layer `layer` of each image.
FlipResult hdr_flip(const image::Image& reference, const image::Image& test, std::string_view layer,
                    const FlipOptions& options = {});

// Display-referred input: the RGB layer is taken as linear values in [0, 1] (8-bit images are
// decoded from sRGB to linear by image::read_image), clamped to [0, 1].
FlipResult ldr_flip(const image::Image& reference, const image::Image& test, std::string_view layer,
                    const FlipOptions& options = {});

// FLIP as giq score computes it, on a pair that may hold NaN/Inf: HDR-FLIP when `hdr`, else
// LDR-FLIP. FLIP's filters spread a non-finite value over its neighbourhood, so such pixels
// are first set to 0 in both images (no difference of their own), and the mean and max are
// taken over the valid pixels only (NaN in the map). The weighted median and quartiles weight
// each pixel by its own FLIP value, so the zeroed pixels carry ~no weight.
FlipResult flip_valid(const image::Image& reference, const image::Image& test, std::string_view layer, bool hdr,
                      const FlipOptions& options = {});

}  // namespace giq::metrics
