// `giq score`: scores a technique's image (or sequence) against the reference and writes
// metrics.json, the error maps (EXR + PNG heat maps) and a side-by-side strip.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "integer_check.h"
#include "output_guard.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/base/json.h"
#include "giq/gate/evaluation.h"
#include "giq/gate/metric_lookup.h"
#include "giq/metrics/catalogue.h"
#include "giq/metrics/score.h"
#include "giq/scenes/scene.h"

namespace giq::cli {
namespace {

using nlohmann::json;

struct ScoreArgs {
  std::string reference, test, layer, ref_layer, test_layer, scene, out, frames, timings;
  std::string tonemap = "none", test_encoding = "srgb", crop;
  double exposure = 0.0;
  std::vector<std::string> fail, warn;
  int step_frame = -1;
  bool json_output = false;
};

std::string beauty_as_empty(const std::string& layer) { return layer == "beauty" ? "" : layer; }

metrics::Crop parse_crop(const std::string& s) {
  metrics::Crop c;
  char tail = 0;
  if (std::sscanf(s.c_str(), "%d,%d,%d,%d%c", &c.x, &c.y, &c.width, &c.height, &tail) != 4 || c.x < 0 || c.y < 0 ||
      c.width <= 0 || c.height <= 0)
    throw InputError("", "--crop", "'" + s + "'; expected x,y,width,height in pixels (x, y >= 0, width, height >= 1)");
  return c;
}

// "--fail relmse<=0.05" / "--warn ssim>=0.9" into bounds, one per metric (a fail and a warn
// level for the same metric become one bound, as in a gate config).
std::vector<gate::Bound> parse_bounds(const std::vector<std::string>& fail, const std::vector<std::string>& warn) {
  std::vector<gate::Bound> bounds;
  auto add = [&](const std::string& text, bool is_fail) {
    const std::string flag = is_fail ? "--fail" : "--warn";
    const size_t op = text.find_first_of("<>");
    double v = 0.0;
    char tail = 0;
    if (op == std::string::npos || op == 0 || op + 1 >= text.size() || text[op + 1] != '=' ||
        std::sscanf(text.c_str() + op + 2, "%lf%c", &v, &tail) != 1 || !std::isfinite(v))
      throw InputError("", flag, "'" + text + "'; expected METRIC<=VALUE or METRIC>=VALUE, e.g. relmse<=0.05");
    const std::string name = text.substr(0, op);
    if (const std::string why = gate::unknown_metric(name); !why.empty()) throw InputError("", flag, why);
    const auto better = text[op] == '<' ? metrics::Better::Lower : metrics::Better::Higher;
    auto it = std::find_if(bounds.begin(), bounds.end(), [&](const gate::Bound& b) { return b.metric == name; });
    if (it == bounds.end()) {
      bounds.push_back({name, std::nullopt, std::nullopt, better, ""});
      it = bounds.end() - 1;
    } else if (it->better != better) {
      throw InputError("", flag, "'" + text + "' bounds " + name + " from the other side than its other bound");
    }
    (is_fail ? it->fail : it->warn) = v;
    if (it->fail && it->warn && (better == metrics::Better::Lower ? *it->warn > *it->fail : *it->warn < *it->fail))
      throw InputError("", "--warn", name + ": the warn level must be stricter than the fail level");
  };
  for (const auto& f : fail) add(f, true);
  for (const auto& w : warn) add(w, false);
  return bounds;
}

std::pair<int, int> parse_frames(const std::string& s) {
  if (const auto range = parse_frame_range(s)) return *range;
  throw InputError("", "--frames", "'" + s + "' is not A:B (first and last frame numbers, 0 <= A <= B, e.g. 0:59)");
}

int run_score(const ScoreArgs& a) {
  check_output_folder(a.out, {a.reference, a.test, a.scene, a.timings}, "--out");
  const std::vector<gate::Bound> bounds = parse_bounds(a.fail, a.warn);
  metrics::ScoreRequest req;
  req.reference = a.reference;
  req.test = a.test;
  // Each side: its own layer option, else --layer, else the beauty.
  req.layer = beauty_as_empty(a.ref_layer.empty() ? a.layer : a.ref_layer);
  req.test_layer = beauty_as_empty(a.test_layer.empty() ? a.layer : a.test_layer);
  req.out_dir = a.out;
  if (!a.crop.empty()) req.crop = parse_crop(a.crop);
  if (a.test_encoding != "srgb" && a.test_encoding != "linear")
    throw InputError("", "--test-encoding", "'" + a.test_encoding + "'; expected srgb or linear");
  req.test_encoding = a.test_encoding == "linear" ? metrics::TestEncoding::Linear : metrics::TestEncoding::Srgb;
  const auto curve = metrics::tone_curve_from_name(a.tonemap);
  if (!curve)
    throw InputError("", "--tonemap", "'" + a.tonemap + "'; expected one of " + std::string(metrics::kToneCurveNames));
  req.display.curve = *curve;
  if (!std::isfinite(a.exposure) || std::abs(a.exposure) > 64.0)
    throw InputError("", "--exposure", std::to_string(a.exposure) + "; expected stops in [-64, 64]");
  req.display.exposure_ev = a.exposure;
  if (!a.frames.empty()) req.frames = parse_frames(a.frames);
  if (a.step_frame >= 0) req.step_frame = a.step_frame;
  if (!a.scene.empty()) {
    const scenes::Scene scene = scenes::load(a.scene);
    req.scene = a.scene;
    req.leak_object_ids = scene.leak_object_ids;
    // The step the scene declares, where the scored frames hold it, unless one is given.
    const auto& step = scene.sequence.step_frame;
    if (!req.step_frame && step && req.frames && req.frames->first < *step && *step <= req.frames->second) {
      req.step_frame = *step;
      req.step_frame_source = "declared by the scene (extras.giq.sequence.step_frame)";
    }
  }
  if (!a.timings.empty()) {
    const gate::FrameTime t = gate::read_timings(a.timings);
    req.frame_ms = *t.gpu_ms;
    req.timings = a.timings + ":" + t.key;
  }
  json result = metrics::score(req);
  for (const auto& w : result.value("warnings", json::array()))
    std::cerr << "giq score: warning: " << w.get<std::string>() << '\n';
  std::vector<gate::Outcome> outcomes;
  if (!bounds.empty()) {
    gate::Case c;
    c.name = "score";
    c.bounds = bounds;
    gate::Evidence ev;
    ev.metrics = result;
    if (!a.timings.empty()) ev.timings = read_json(a.timings);
    outcomes = gate::evaluate(c, ev);
  }
  if (a.json_output) {
    if (!outcomes.empty()) {
      json list = json::array();
      for (const auto& o : outcomes)
        list.push_back({{"metric", o.metric}, {"bound", o.bound}, {"status", gate::to_string(o.status)},
                        {"value", o.value ? json(*o.value) : json(nullptr)}, {"message", o.message}});
      result["bounds"] = list;
    }
    std::cout << result.dump(2) << '\n';
  } else {
    // The table names the inputs as typed; metrics.json holds them relative to itself.
    json shown = result;
    shown["inputs"]["reference"] = a.reference;
    shown["inputs"]["test"] = a.test;
    std::cout << metrics::format_table(shown);
    if (!outcomes.empty()) std::cout << " bounds\n";
    for (const auto& o : outcomes) {
      char value[32] = "n/a";
      if (o.value) std::snprintf(value, sizeof value, "%.6g", *o.value);
      std::cout << "  " << std::left << std::setw(30) << (o.metric + " " + o.bound) << std::setw(16) << value
                << gate::to_string(o.status) << (o.message.empty() ? "" : "  " + o.message) << '\n';
    }
    std::cout << "  written: " << (req.out_dir / "metrics.json").string() << '\n';
  }
  return gate::exit_code(outcomes);
}

}  // namespace

void add_score_command(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ScoreArgs>();
  CLI::App* cmd = app.add_subcommand(
      "score", "Score a technique's image or sequence against the reference (metrics.json, error maps, strip)");
  cmd->add_option("--ref", args->reference, "Reference EXR, or a pattern such as ref_%04d.exr")->required();
  cmd->add_option("--test", args->test, "Technique image, or a pattern such as tech_%04d.exr")->required();
  cmd->add_option("--layer", args->layer, "RGB layer to compare in both images (beauty, indirect, direct, ...)");
  cmd->add_option("--ref-layer", args->ref_layer, "The reference's layer, when the test's differs (default: --layer)");
  cmd->add_option("--test-layer", args->test_layer, "The test's layer, e.g. an engine's indirect-only buffer (default: --layer)");
  cmd->add_option("--tonemap", args->tonemap,
                  "Tone curve applied to the reference (and an HDR test) before comparing: " +
                      std::string(metrics::kToneCurveNames) + " (docs/own-engine.md)");
  cmd->add_option("--exposure", args->exposure, "Exposure in stops applied to the reference (and an HDR test) before the tone curve");
  cmd->add_option("--test-encoding", args->test_encoding, "How an 8-bit test image stores colour: srgb (screenshots) or linear");
  cmd->add_option("--crop", args->crop, "Score only the region x,y,width,height (pixels from the top left) of both images");
  cmd->add_option("--fail", args->fail, "Exit 1 unless METRIC<=V (or >=V) holds; repeatable, any metric of docs/metrics.md");
  cmd->add_option("--warn", args->warn, "Mark METRIC<=V (or >=V) when it does not hold; repeatable");
  cmd->add_option("--scene", args->scene, "Scene (.gltf/.glb) whose leak regions are scored and whose declared step frame lag takes");
  cmd->add_option("--out", args->out, "Output folder for metrics.json and the maps")->required();
  cmd->add_option("--frames", args->frames, "First and last frame A:B for patterns");
  cmd->add_option("--timings", args->timings, "timings.json of the technique (frame time for lag in ms)");
  cmd->add_option("--step-frame", args->step_frame, "Frame of the step change for lag (default: the scene's declared step_frame, else detected)")
      ->check(integer_in(0.0L, 2147483647.0L));
  cmd->add_flag("--json", args->json_output, "Print metrics.json on stdout instead of a table");
  cmd->footer(
      "Example: an engine's tone-mapped screenshot against the reference, failing above 10% FLIP:\n"
      "  giq score --ref ref.exr --test shot.png --tonemap aces --exposure -1 --fail 'flip_mean<=0.1' --out score/");
  cmd->callback([args, &exit_code] { exit_code = run_score(*args); });
}

}  // namespace giq::cli
