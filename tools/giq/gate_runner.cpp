#include "gate_runner.h"

#include "scene_setup.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/suggest.h"
#include "giq/base/frames.h"
#include "giq/base/json.h"
#include "giq/base/version.h"
#include "giq/image/io.h"
#include "giq/metrics/score.h"
#include "giq/scenes/scene.h"
#include "scene_setup.h"
#include "subprocess.h"
#include "technique_listing.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Whether `dir` holds the outputs of exactly this command (same arguments, same giq binary,
// same golden files), so the gate renders only what is missing.
bool up_to_date(const fs::path& dir, const json& stamp) {
  try {
    return fs::exists(dir / "stamp.json") && read_json(dir / "stamp.json") == stamp;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace

std::string run_cached_step(const std::vector<std::string>& argv, const fs::path& dir, const fs::path& log,
                            const std::string& what, const json& stamp, bool rerender) {
  if (!rerender && up_to_date(dir, stamp)) return "";
  std::error_code ec;
  fs::remove_all(dir, ec);
  fs::create_directories(dir);
  const ProcessResult r = run_process(argv, log);
  if (r.exit_code != 0)
    return what + " failed (exit " + std::to_string(r.exit_code) + "; log " + log.string() +
           "): " + r.log_tail;
  write_file_atomically(dir / "stamp.json", stamp.dump(2) + "\n");
  return "";
}

namespace {

// giq score's display options for the case (gate::DisplaySpec).
std::vector<std::string> display_args(const gate::Case& c) {
  std::vector<std::string> a;
  if (!c.display.tonemap.empty()) a.insert(a.end(), {"--tonemap", c.display.tonemap});
  if (c.display.exposure != 0.0) {
    char ev[32];
    std::snprintf(ev, sizeof ev, "%.17g", c.display.exposure);
    a.insert(a.end(), {"--exposure", ev});
  }
  if (!c.display.test_encoding.empty()) a.insert(a.end(), {"--test-encoding", c.display.test_encoding});
  return a;
}

std::vector<std::string> realtime_args(const Toolchain& t, const gate::Case& c) {
  std::vector<std::string> a = {t.giq.string(),          "realtime",  "--scene",
                                c.scene.string(),        c.camera.empty() ? "--view" : "--camera",
                                c.camera.empty() ? c.view : c.camera,
                                "--technique",           c.technique, "--width",
                                std::to_string(c.width), "--height",  std::to_string(c.height)};
  for (const std::string& p : gate::parameter_arguments(c)) a.insert(a.end(), {"--param", p});
  if (!t.device.empty()) a.insert(a.end(), {"--device", t.device});
  return a;
}

}  // namespace

std::string scene_hash(const fs::path& scene) {
  return scenes::load(scene).content_hash;
}

namespace {

// The scene's content hash, after checking that a still golden is asked for a static scene
// only: one image cannot stand for the frames of an animation.
std::string checked_scene_hash(const gate::Case& c) {
  const scenes::Scene scene = scenes::load(c.scene);
  if (c.golden.still && scene.features.animation)
    throw InputError(c.scene.string(), "cases." + c.name + ".golden.still",
                     "the scene is animated; a still golden serves static scenes only");
  return scene.content_hash;
}

}  // namespace

CaseRun run_case(const Toolchain& t, const gate::Case& c, const gate::Config& config,
                 const gate::Manifest& manifest, const fs::path& out_dir) {
  CaseRun run;
  // Absolute paths, so metrics.json and the logs stay valid wherever they are read from.
  run.dir = fs::absolute(out_dir / "cases" / c.name);
  const auto start = std::chrono::steady_clock::now();
  try {
    fs::create_directories(run.dir);
    const fs::path log = run.dir / "log.txt";
    std::ofstream(log, std::ios::trunc) << "giq gate: case " << c.name << '\n';
    const std::string hash = checked_scene_hash(c);
    const gate::Freshness fresh = gate::check_golden(manifest, config.golden_dir, c, hash);
    if (fresh.state != gate::Freshness::State::Fresh)
      throw InputError(c.scene.string(), "golden", fresh.reason);
    const fs::path golden = fs::absolute(config.golden_dir / gate::golden_key(c));
    json golden_files = json::object();
    for (const auto& [name, h] : manifest.entries.at(gate::golden_key(c)).files)
      golden_files[name] = h;
    const std::string binary_hash = gate::file_hash(t.giq);

    const fs::path score = run.dir / "score";
    std::vector<std::string> sc = {t.giq.string(), "score"};
    // A still golden is one image that giq score compares with every frame of the range.
    const std::string ref_frames = c.golden.still ? frame_file(c.first_frame) : kFramePattern;
    const std::string ref = (golden / (c.sequence() ? ref_frames : frame_file(c.first_frame))).string();
    if (!c.test.empty()) {
      // Images from outside giq: scored as they are; a changed file scores again.
      json test_files = json::object();
      for (int f = c.first_frame; f <= c.last_frame; ++f) {
        const fs::path p = c.sequence() ? fs::path(metrics::frame_path(c.test.string(), f)) : c.test;
        if (!fs::is_regular_file(p)) throw InputError(p.string(), "test", "no such image file");
        test_files[p.string()] = gate::file_hash(p);
      }
      sc.insert(sc.end(), {"--ref", ref, "--test", c.test.string()});
      if (c.sequence()) sc.insert(sc.end(), {"--frames", frame_range(c.first_frame, c.last_frame)});
      sc.insert(sc.end(), {"--layer", c.layer, "--scene", c.scene.string(), "--out", score.string()});
      for (const std::string& d : display_args(c)) sc.push_back(d);
      const std::string problem = run_cached_step(
          sc, score, log, "giq score", {{"argv", sc}, {"giq", binary_hash}, {"golden", golden_files}, {"test", test_files}},
          t.rerender);
      if (!problem.empty()) throw InputError("", "score", problem);
      run.evidence.metrics = read_json(score / "metrics.json");
      run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return run;
    }

    // Technique images: frames A..B are the measured frames after A warm-up frames.
    std::vector<std::string> rt = realtime_args(t, c);
    const fs::path tech = run.dir / "technique";
    rt.insert(rt.end(), {"--warmup", std::to_string(c.first_frame), "--frames",
                         std::to_string(c.last_frame - c.first_frame + 1), "--out", tech.string()});
    std::string problem =
        run_cached_step(rt, tech, log, "giq realtime", {{"argv", rt}, {"giq", binary_hash}}, t.rerender);
    if (!problem.empty()) throw InputError("", "realtime", problem);
    fs::path timings = tech / "timings.json";
    if (c.needs_timing()) {
      std::vector<std::string> tm = realtime_args(t, c);
      const fs::path timing = run.dir / "timing";
      tm.insert(tm.end(), {"--no-images", "--warmup", std::to_string(c.timing.warmup), "--frames",
                           std::to_string(c.timing.frames), "--out", timing.string()});
      problem = run_cached_step(tm, timing, log, "giq realtime (timing)", {{"argv", tm}, {"giq", binary_hash}},
                     t.rerender);
      if (!problem.empty()) throw InputError("", "realtime", problem);
      timings = timing / "timings.json";
    }
    for (int f = c.first_frame; f <= c.last_frame; ++f)
      if (!fs::exists(tech / frame_file(f)))
        throw InputError((tech / frame_file(f)).string(), "",
                         "giq realtime did not write this frame");

    if (c.sequence())
      sc.insert(sc.end(), {"--ref", ref, "--test", (tech / kFramePattern).string(), "--frames",
                           frame_range(c.first_frame, c.last_frame)});
    else
      sc.insert(sc.end(), {"--ref", ref, "--test", (tech / frame_file(c.first_frame)).string()});
    sc.insert(sc.end(), {"--layer", c.layer, "--scene", c.scene.string(), "--timings",
                         (tech / "timings.json").string(), "--out", score.string()});
    for (const std::string& d : display_args(c)) sc.push_back(d);
    problem = run_cached_step(sc, score, log, "giq score",
                   {{"argv", sc},
                    {"giq", binary_hash},
                    {"golden", golden_files},
                    {"technique", read_json(tech / "stamp.json")}},
                   t.rerender);
    if (!problem.empty()) throw InputError("", "score", problem);
    run.evidence.metrics = read_json(score / "metrics.json");
    run.evidence.timings = read_json(timings);
  } catch (const std::exception& e) {
    run.evidence.problem = e.what();
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

GoldenRun update_golden(const Toolchain& t, const gate::Case& c, const gate::Config& config,
                        bool force, gate::Manifest& manifest, std::mutex& lock) {
  GoldenRun g;
  g.key = gate::golden_key(c);
  try {
    const std::string hash = checked_scene_hash(c);
    {
      std::lock_guard<std::mutex> guard(lock);
      const gate::Freshness f = gate::check_golden(manifest, config.golden_dir, c, hash);
      if (f.state == gate::Freshness::State::Fresh && !force) {
        g.action = "fresh";
        return g;
      }
    }
    const fs::path dir = config.golden_dir / g.key;
    std::error_code ec;
    fs::remove_all(dir, ec);
    fs::create_directories(dir);
    // giq reference runs in the config's folder with the scene path relative to it, the path
    // the manifest records: the EXR header names the scene by that path, so the golden files
    // are the same bytes whatever the checkout's location or the directory update runs in.
    const fs::path config_dir = fs::absolute(config.file).parent_path();
    const std::string scene = fs::absolute(c.scene).lexically_relative(config_dir).generic_string();
    std::vector<std::string> a = t.launcher;
    a.insert(a.end(), {t.giq.string(), "reference",
                                  "--scene",      scene,
                                  c.camera.empty() ? "--view" : "--camera",
                                  c.camera.empty() ? c.view : c.camera,
                                  "--frames",     frame_range(c.first_frame, c.golden_last_frame()),
                                  "--width",      std::to_string(c.width),
                                  "--height",     std::to_string(c.height),
                                  "--seed",       std::to_string(c.golden.seed),
                                  "--sampler",    c.golden.sampler});
    if (c.golden.spp)
      a.insert(a.end(), {"--spp", std::to_string(*c.golden.spp)});
    else
      a.insert(a.end(), {"--rel-error", std::to_string(*c.golden.rel_error)});
    if (c.golden.half) a.push_back("--half");
    // An interrupted golden render continues where it stopped (the checkpoint names its scene,
    // camera and settings, so a stale one is refused, not mixed in).
    a.push_back("--resume");
    a.insert(a.end(), {"--out", (fs::absolute(dir) / "frame_####.exr").string()});
    const fs::path log = config.golden_dir / (g.key + ".log");
    std::ofstream(log, std::ios::trunc) << "giq golden update: " << g.key << '\n';
    const ProcessResult r = run_process(a, log, config_dir);
    if (r.exit_code != 0)
      throw InputError(c.scene.string(), "golden",
                       "giq reference failed (exit " + std::to_string(r.exit_code) + "; log " +
                           log.string() + "): " + r.log_tail);
    fs::remove(log, ec);
    gate::GoldenEntry e;
    e.scene = scene;
    e.scene_hash = hash;
    e.settings = gate::golden_settings(c);
    e.render_seconds = r.seconds;
    e.giq_version = giq::version();
    for (int f = c.first_frame; f <= c.golden_last_frame(); ++f) {
      const fs::path p = dir / frame_file(f);
      if (!fs::exists(p))
        throw InputError(p.string(), "", "giq reference did not write this frame");
      e.files[p.filename().string()] = gate::file_hash(p);
      // The achieved spp (minimum over pixels and frames) and the renderer's version come from
      // the EXR header that giq reference writes.
      const image::Image img = image::read_image(p);
      if (auto it = img.metadata.find("giq.version"); it != img.metadata.end())
        e.giq_version = it->second;
      if (auto it = img.metadata.find("giq.spp"); it != img.metadata.end()) {
        const uint32_t spp = uint32_t(std::stoul(it->second));
        e.spp = e.spp ? std::min(*e.spp, spp) : spp;
      }
    }
    std::lock_guard<std::mutex> guard(lock);
    manifest.entries[g.key] = e;
    gate::write_manifest(config.golden_dir / "manifest.json", manifest);
    g.action = "rendered";
    char buf[64];
    std::snprintf(buf, sizeof buf, " in %.1f s", r.seconds);
    g.message = dir.string() + buf;
  } catch (const std::exception& e) {
    g.action = "failed";
    g.message = e.what();
  }
  return g;
}

void add_case_options(CLI::App* cmd, CaseOptions& o) {
  cmd->add_option("--config", o.config, "Gate config (JSON, docs/gate.md)")->capture_default_str();
  cmd->add_option("--only", o.only, "Only the cases whose name matches this glob ('*', '?')");
  cmd->add_option("--jobs", o.jobs, "Cases run in parallel")->capture_default_str();
  cmd->add_option("--giq", o.giq, "giq binary whose reference/realtime/score subcommands are run (default: this one)");
}

Toolchain toolchain(const CaseOptions& o) {
  Toolchain t;
  t.giq = o.giq.empty() ? self_executable() : fs::absolute(o.giq);
  if (!fs::exists(t.giq)) throw InputError(o.giq, "--giq", "no such program; expected the path of a giq binary");
  t.device = o.device;
  t.rerender = o.rerender;
  return t;
}

void check_cases(const Toolchain& t, const std::vector<const gate::Case*>& cases, const fs::path& log) {
  std::vector<TechniqueParameters> registered;
  bool listed = false;
  std::map<fs::path, scenes::Scene> scenes_by_path;
  for (const gate::Case* c : cases) {
    const std::string at = "cases." + c->name;
    if (!c->technique.empty()) {
      if (!listed) registered = list_techniques(t.giq, log), listed = true;
      const auto tech = std::find_if(registered.begin(), registered.end(),
                                     [&](const TechniqueParameters& p) { return p.name == c->technique; });
      if (tech == registered.end()) {
        std::string names;
        std::vector<std::string> known;
        for (const auto& r : registered) names += (names.empty() ? "" : ", ") + r.name, known.push_back(r.name);
        throw InputError("", at + ".technique",
                         "'" + c->technique + "' is not registered; expected one of " + names + did_you_mean(c->technique, known));
      }
      for (const auto& [name, value] : c->parameters) {
        const auto p = std::find_if(tech->parameters.begin(), tech->parameters.end(),
                                    [&](const ParameterInfo& i) { return i.name == name; });
        if (p == tech->parameters.end()) {
          std::string names;
          std::vector<std::string> known;
          for (const auto& i : tech->parameters) names += (names.empty() ? "" : ", ") + i.name, known.push_back(i.name);
          throw InputError("", at + ".parameters." + name,
                           "'" + c->technique + "' has no such parameter; it has " + names + did_you_mean(name, known));
        }
        if (value < p->min_value || value > p->max_value || (p->integer && value != std::floor(value)))
          throw InputError("", at + ".parameters." + name,
                           std::to_string(value) + " is outside its range [" + std::to_string(p->min_value) + ", " +
                               std::to_string(p->max_value) + "]" + (p->integer ? " of integers" : ""));
      }
    }
    auto it = scenes_by_path.find(c->scene);
    if (it == scenes_by_path.end()) it = scenes_by_path.emplace(c->scene, scenes::load(c->scene)).first;
    try {
      if (c->camera.empty()) it->second.view(c->view);
      else camera_from_arguments({c->camera}, it->second, double(c->width) / double(c->height));
    } catch (const InputError& e) {
      throw InputError(c->scene.string(), at + (c->camera.empty() ? ".view" : ".camera"), e.message());
    }
  }
}

std::vector<const gate::Case*> load_cases(const CaseOptions& o, gate::Config& config) {
  if (o.jobs < 1) throw InputError("", "--jobs", std::to_string(o.jobs) + "; expected at least 1");
  config = gate::read_config(o.config);
  gate::check_golden_conflicts(config);
  auto cases = gate::select_cases(config, o.only);
  if (cases.empty()) throw InputError(o.config, "--only", "'" + o.only + "' matches no case name");
  return cases;
}

}  // namespace giq::cli
