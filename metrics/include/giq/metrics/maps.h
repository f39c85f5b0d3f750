#pragma once
// Per-pixel error maps (docs/metrics.md, "Error maps"). Each map is one float per pixel whose
// mean over valid pixels is the matching scalar metric (abs -> mae, relative -> relmse), NaN
// where a pixel was excluded (non-finite input). A map is written as a one-channel float EXR
// (channel "Y", with its definition in the header) and as a PNG heat map: magma for
// magnitudes, blue-white-red for signed maps, the colour scale recorded in the PNG's text
// chunks and returned for metrics.json.

#include <filesystem>
#include <string>
#include <vector>

#include "giq/metrics/layer.h"

namespace giq::metrics {

struct Map {
  std::string name;        // file stem: "abs_error", "relative_error", ...
  std::string definition;  // the formula, as in docs/metrics.md
  std::string unit;        // "radiance", "1" (dimensionless)...
  bool is_signed = false;  // diverging colour map around 0
  int width = 0, height = 0;
  std::vector<float> values;
};

struct MapRange {
  float lo = 0.0f, hi = 1.0f;
  std::string rule;  // how the range was chosen
};

// abs(p) = mean_c |T_c - R_c|
Map abs_error_map(const RgbLayer& reference, const RgbLayer& test);
// rel(p) = mean_c (T_c - R_c)^2 / (R_c^2 + 0.01)
Map relative_error_map(const RgbLayer& reference, const RgbLayer& test);
// signed(p) = Y_T(p) - Y_R(p): negative = too dark
Map signed_luminance_map(const RgbLayer& reference, const RgbLayer& test);

// Magnitude: [0, 99th percentile of the finite values]; signed: [-a, a] with a the 99th
// percentile of |value|. The percentile is exact on up to 2^20 values and taken on an evenly
// strided subsample above that. A zero or non-finite bound becomes 1.
MapRange auto_range(const Map& map);

// Heat-map colours, row-major RGB8.
std::vector<uint8_t> colourise(const Map& map, const MapRange& range);

struct WrittenMap {
  std::filesystem::path exr, png;
  MapRange range;
  std::string colormap;  // "magma" or "blue-white-red"
};
// Writes <dir>/<name>.exr and <dir>/<name>.png (atomically).
WrittenMap write_map(const Map& map, const std::filesystem::path& dir, const MapRange& range);

}  // namespace giq::metrics
