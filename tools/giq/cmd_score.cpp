// `giq score`: scores a technique's image (or sequence) against the reference and writes
// metrics.json, the error maps (EXR + PNG heat maps) and a side-by-side strip.

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "giq/base/error.h"
#include "giq/metrics/score.h"
#include "giq/scenes/scene.h"

namespace giq::cli {
namespace {

using nlohmann::json;

struct ScoreArgs {
  std::string reference, test, layer, scene, out, frames, timings;
  int step_frame = -1;
  bool json_output = false;
};

std::pair<int, int> parse_frames(const std::string& s) {
  const size_t colon = s.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    size_t used_a = 0, used_b = 0;
    const int a = std::stoi(s.substr(0, colon), &used_a);
    const int b = std::stoi(s.substr(colon + 1), &used_b);
    if (used_a != colon || used_b != s.size() - colon - 1) throw std::invalid_argument("trailing characters");
    return {a, b};
  } catch (const std::exception&) {
    throw InputError("", "--frames", "'" + s + "' is not A:B (first and last frame numbers, e.g. 0:59)");
  }
}

// The technique's frame time: frame_ms.median, or frame_gpu_ms.median as `giq realtime` writes.
std::pair<double, std::string> read_frame_ms(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open timings file");
  json j;
  try {
    in >> j;
  } catch (const json::exception& e) {
    throw InputError(path, "", std::string("not valid JSON: ") + e.what());
  }
  for (const char* key : {"frame_ms", "frame_gpu_ms"}) {
    if (!j.is_object() || !j.contains(key)) continue;
    const json& m = j[key];
    if (!m.is_object() || !m.contains("median") || !m["median"].is_number())
      throw InputError(path, std::string(key) + ".median", "missing or not a number; expected milliseconds");
    const double v = m["median"].get<double>();
    if (!std::isfinite(v) || v <= 0.0)
      throw InputError(path, std::string(key) + ".median", std::to_string(v) + " ms; expected a positive frame time");
    return {v, std::string(key) + ".median"};
  }
  throw InputError(path, "frame_ms.median", "missing; expected {\"frame_ms\": {\"median\": <ms>}}");
}

int run_score(const ScoreArgs& a) {
  metrics::ScoreRequest req;
  req.reference = a.reference;
  req.test = a.test;
  req.layer = a.layer == "beauty" ? "" : a.layer;
  req.out_dir = a.out;
  if (!a.frames.empty()) req.frames = parse_frames(a.frames);
  if (a.step_frame >= 0) req.step_frame = a.step_frame;
  if (!a.scene.empty()) {
    const scenes::Scene scene = scenes::load(a.scene);
    req.scene = a.scene;
    req.leak_object_ids = scene.leak_object_ids;
  }
  if (!a.timings.empty()) {
    const auto [ms, key] = read_frame_ms(a.timings);
    req.frame_ms = ms;
    req.timings = a.timings + ":" + key;
  }
  const json result = metrics::score(req);
  if (a.json_output) std::cout << result.dump(2) << '\n';
  else std::cout << metrics::format_table(result) << "  written: " << (req.out_dir / "metrics.json").string() << '\n';
  return 0;
}

}  // namespace

void add_score_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ScoreArgs>();
  CLI::App* cmd = app.add_subcommand(
      "score", "Score a technique's image or sequence against the reference (metrics.json, error maps, strip)");
  cmd->add_option("--ref", args->reference, "Reference EXR, or a pattern such as ref_%04d.exr")->required();
  cmd->add_option("--test", args->test, "Technique image, or a pattern such as tech_%04d.exr")->required();
  cmd->add_option("--layer", args->layer, "RGB layer to compare (beauty, indirect, direct, ...)");
  cmd->add_option("--scene", args->scene, "Scene (.gltf/.glb) whose leak regions are scored");
  cmd->add_option("--out", args->out, "Output folder for metrics.json and the maps")->required();
  cmd->add_option("--frames", args->frames, "First and last frame A:B for patterns");
  cmd->add_option("--timings", args->timings, "timings.json of the technique (frame time for lag in ms)");
  cmd->add_option("--step-frame", args->step_frame, "Frame of the step change for lag (default: detected)");
  cmd->add_flag("--json", args->json_output, "Print metrics.json on stdout instead of a table");
  cmd->callback([args, &exit_code] { exit_code = run_score(*args); });
}

}  // namespace giq::cli
