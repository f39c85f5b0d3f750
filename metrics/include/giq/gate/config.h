#pragma once
// The gate config: a JSON file listing cases (scene, view, technique, parameters, frames,
// layer, resolution, golden reference settings) and bounds on their metrics. docs/gate.md
// describes the format. JSON rather than TOML: it is the format of every other giq file
// (metrics.json, timings.json, the golden manifest), it needs no extra dependency, and a
// config can be generated or checked by the same tools that read giq's outputs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "giq/metrics/catalogue.h"

namespace giq::gate {

// How a golden reference is rendered: stop at `spp` samples per pixel or at a mean relative
// standard error `rel_error` (exactly one of the two), with a fixed seed so that re-rendering
// gives the same file. `half` stores the colour layers as float16 (`giq reference --half`:
// the variance, depth and id channels stay float32). `still` renders one image, of the
// case's first frame, for a static scene and camera; a frame range is then scored against
// that one image, which is the right comparison for flicker: identical golden frames would
// share one noise sample, and subtracting their noise from the technique's temporal variance
// as if it were independent every frame would hide real flicker (docs/metrics.md,
// "Sequences").
struct GoldenSpec {
  std::optional<uint32_t> spp;
  std::optional<double> rel_error;
  uint64_t seed = 1;
  bool half = false;
  bool still = false;
  // giq reference's --sampler. Independent by default: the gate's per-pixel noise tests (leak
  // beyond 3 sigma, z-scores) want a per-pixel variance with a degree of freedom per sample,
  // which the Sobol sampler's blocks do not give at golden sample counts.
  std::string sampler = "independent";
};

using Better = metrics::Better;  // the catalogue's (giq/metrics/catalogue.h)

// One bound: the metric must stay at or below `fail` (at or above for higher-is-better
// metrics such as ssim and psnr); beyond `warn` it is reported as WARN. A bound with a
// `device` applies only where the device name contains it (case-insensitive); elsewhere it is
// reported as SKIP. gpu_ms bounds must name a device: a time means nothing on another one.
struct Bound {
  std::string metric;
  std::optional<double> fail;
  std::optional<double> warn;
  Better better = Better::Lower;
  std::string device;
};

// Timing run for gpu_ms bounds: median over `frames` measured frames after `warmup`.
struct TimingSpec {
  int warmup = 10;
  int frames = 20;
};

// How giq score shows the reference before comparing (docs/own-engine.md): an engine's
// exposure and tone curve for its tone-mapped screenshots, and how an 8-bit test stores
// colour. Empty strings and 0 stops: giq score's defaults.
struct DisplaySpec {
  std::string tonemap;        // giq score --tonemap
  double exposure = 0.0;      // giq score --exposure, stops
  std::string test_encoding;  // giq score --test-encoding
};

struct Case {
  std::string name;
  std::filesystem::path scene;  // resolved against the config file's folder
  std::string view;
  // Instead of a view: a camera in world coordinates, as giq's --camera takes it
  // ("eye=x,y,z target=x,y,z fov=deg [frame=unity ...]", docs/own-engine.md).
  std::string camera;
  std::string technique;
  // Instead of a technique: image files from outside giq (an engine's), one file or a frame
  // pattern (%04d) for a range, resolved against the config file's folder.
  std::filesystem::path test;
  std::vector<std::pair<std::string, double>> parameters;  // sorted by name
  int first_frame = 0, last_frame = 0;
  std::string layer = "beauty";
  int width = 256, height = 256;  // the size every giq command renders by default
  GoldenSpec golden;
  DisplaySpec display;
  TimingSpec timing;
  std::vector<Bound> bounds;

  bool sequence() const { return last_frame > first_frame; }
  // The frames the golden holds: [first, last], or [first, first] for a still golden.
  int golden_last_frame() const { return golden.still ? first_frame : last_frame; }
  bool needs_timing() const;
};

struct Config {
  std::filesystem::path file;
  std::filesystem::path golden_dir;  // default: <config folder>/refs
  std::vector<Case> cases;
};

// Reads and validates a config. Throws InputError(file, field, message) naming the JSON path
// of the first problem (e.g. "cases[2].bounds.flip_mean.warn") and what was expected.
Config read_config(const std::filesystem::path& file);
Config parse_config(const std::string& text, const std::filesystem::path& file);

// The better direction of a metric when the config does not say: ssim and psnr grow with
// quality, every other metric giq writes is an error.
Better default_direction(const std::string& metric);

// Cases whose name matches a glob pattern ('*' any run, '?' one character); "" selects all.
std::vector<const Case*> select_cases(const Config& config, const std::string& pattern);
bool glob_match(const std::string& pattern, const std::string& text);

// "name=value" for each parameter, values printed with up to 10 significant digits.
std::vector<std::string> parameter_arguments(const Case& c);

}  // namespace giq::gate
