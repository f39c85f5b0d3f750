#pragma once
// What `giq report DIR` finds under DIR: every metrics.json written by `giq score` (a
// comparison: reference, technique, error maps, sequence frames, metrics), gate.json written by
// `giq gate`, sweep.json and SVG plots written by `giq sweep`. Images are turned into PNG data
// URIs here, so the page needs nothing beside itself.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "giq/gate/metric_lookup.h"

namespace giq::cli {

struct ColourScale {
  std::string colormap;  // "magma" or "blue-white-red", as giq score's maps record it
  double lo = 0.0, hi = 1.0;
  std::string unit, rule;
};

struct Picture {
  std::string title;
  std::string data_uri;
  std::optional<ColourScale> scale;
};

struct Comparison {
  std::string scene;      // the scene file, from metrics.json or the reference's header
  std::string technique;  // from the technique's EXR header (giq.technique), else its folder
  std::string label;      // gate case name or the score folder
  std::string layer;
  std::string source;          // metrics.json, relative to DIR
  std::vector<Picture> panes;  // reference, technique (same exposure)
  std::vector<Picture> maps;   // error maps with their colour scales
  std::vector<std::string> reference_frames, technique_frames;  // flip-book (sequences)
  int first_frame = 0;
  std::vector<std::pair<std::string, std::string>> metrics;  // name, value (with notes)
  // The headline metrics of the catalogue present in metrics.json (short name -> value, with
  // its unresolved flag) and the technique's frame time, for the summary table.
  std::vector<std::pair<std::string, gate::MetricValue>> headline;
  std::optional<double> gpu_ms;
  std::vector<std::string> warnings;  // metrics.json's: why a score may be meaningless
  // The values under the pointer (the last frame's): the reference's and the technique's
  // R, G, B of the scored layer, then each error map's value, as the page's readout shows
  // them; empty above kReadoutPixels pixels, which would make the page too large.
  struct Readout {
    int width = 0, height = 0;
    std::vector<std::pair<std::string, std::vector<float>>> channels;  // label, values row by row
  } readout;
};

// The largest image whose values the page embeds for the pixel readout (512 x 512: 1 MiB of
// float32 per channel before base64).
inline constexpr size_t kReadoutPixels = 512 * 512;

struct Sweep {
  std::string source;
  nlohmann::json data;
};

struct ReportInputs {
  std::filesystem::path dir;
  std::vector<Comparison> comparisons;
  std::optional<nlohmann::json> gate;
  std::vector<Sweep> sweeps;
  std::vector<Picture> plots;         // *.svg written by giq sweep
  std::vector<std::string> warnings;  // files that could not be read, shown on the page
};

// Scans DIR recursively (files over `max_frames` sequence frames are sampled evenly). Throws
// InputError when DIR does not exist or holds nothing giq wrote.
ReportInputs scan_report_inputs(const std::filesystem::path& dir, int max_frames);

}  // namespace giq::cli
