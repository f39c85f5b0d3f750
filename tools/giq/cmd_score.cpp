// `giq score`: scores a technique's image (or sequence) against the reference and writes
// metrics.json, the error maps (EXR + PNG heat maps) and a side-by-side strip.

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "integer_check.h"
#include "output_guard.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/gate/metric_lookup.h"
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
  if (const auto range = parse_frame_range(s)) return *range;
  throw InputError("", "--frames", "'" + s + "' is not A:B (first and last frame numbers, 0 <= A <= B, e.g. 0:59)");
}

int run_score(const ScoreArgs& a) {
  check_output_folder(a.out, {a.reference, a.test, a.scene, a.timings}, "--out");
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
    const gate::FrameTime t = gate::read_timings(a.timings);
    req.frame_ms = *t.gpu_ms;
    req.timings = a.timings + ":" + t.key;
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
  cmd->add_option("--step-frame", args->step_frame, "Frame of the step change for lag (default: detected)")
      ->check(integer_in(0.0L, 2147483647.0L));
  cmd->add_flag("--json", args->json_output, "Print metrics.json on stdout instead of a table");
  cmd->callback([args, &exit_code] { exit_code = run_score(*args); });
}

}  // namespace giq::cli
