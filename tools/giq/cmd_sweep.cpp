// `giq sweep`: speed against accuracy. For each technique and each parameter setting it runs
// `giq realtime` (median GPU ms over the measured frames after warm-up) and `giq score` on the
// last frame against a reference, then writes sweep.csv, sweep.json and sweep.svg (error vs
// ms, Pareto front, defaults ringed). `giq sweep --convergence` does the same for the reference
// renderer: error against spp and seconds on log-log axes with the fitted slope.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "command.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/base/json.h"
#include "giq/gate/config.h"
#include "giq/gate/fit.h"
#include "giq/gate/metric_lookup.h"
#include "giq/gate/plot.h"
#include "giq/gate/sweep_table.h"
#include "giq/image/io.h"
#include "giq/metrics/catalogue.h"
#include "progress.h"
#include "subprocess.h"
#include "sweep_plan.h"
#include "technique_listing.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The per-image metrics of the catalogue, the sweep's error metric first: the sweep's columns.
std::vector<std::string> sweep_metrics(const std::string& error) {
  std::vector<std::string> names = {error};
  for (const metrics::MetricInfo& m : metrics::kMetricCatalogue)
    if (m.scope == metrics::Scope::Image && m.name != error) names.emplace_back(m.name);
  return names;
}

struct SweepArgs {
  std::string scene, view = "0", camera, ref, layer = "beauty", error, out = "sweep-out", device, giq, sampler = "sobol";
  std::vector<std::string> techniques, grid;
  std::vector<uint32_t> spp;
  int auto_steps = 0, width = 256, height = 256, warmup = 10, frames = 20, jobs = 1, timing_width = 0, timing_height = 0,
      max_settings = 64;
  uint32_t ref_spp = 1024;
  bool convergence = false, linear = false, quality = false;
};

// The view every render shares: --camera (world coordinates, docs/own-engine.md) when given,
// else --view.
std::vector<std::string> view_arguments(const SweepArgs& a) {
  if (!a.camera.empty()) return {"--camera", a.camera};
  return {"--view", a.view};
}


void must(const ProcessResult& r, const std::string& what, const fs::path& log) {
  if (r.exit_code != 0)
    throw InputError(log.string(), what,
                     "failed (exit " + std::to_string(r.exit_code) + "): " + r.log_tail);
}

// A reference: the given file, or one rendered by giq reference at --ref-spp.
fs::path reference(const SweepArgs& a, const fs::path& giq, const fs::path& out, uint32_t spp,
                   uint64_t seed, const std::string& name, double* seconds = nullptr) {
  const fs::path file = out / name;
  const fs::path log = out / "log.txt";
  const ProcessResult r = run_process(
      [&] {
        std::vector<std::string> ra = {giq.string(), "reference", "--scene", a.scene, "--spp", std::to_string(spp),
                                       "--seed", std::to_string(seed), "--width", std::to_string(a.width),
                                       "--height", std::to_string(a.height), "--sampler", a.sampler,
                                       "--record-time",
                                       // Its time is measured: an earlier, interrupted render's
                                       // samples must not count.
                                       "--overwrite", "--out", file.string()};
        const auto v = view_arguments(a);
        ra.insert(ra.begin() + 4, v.begin(), v.end());
        return ra;
      }(),
      log);
  must(r, "giq reference", log);
  if (seconds) {
    // The renderer's own time (without scene loading and BVH build) when it recorded it.
    *seconds = r.seconds;
    const image::Image img = image::read_image(file);
    if (auto it = img.metadata.find("giq.render_time"); it != img.metadata.end())
      *seconds = std::strtod(it->second.c_str(), nullptr);
  }
  return file;
}

std::map<std::string, std::optional<double>> score(const SweepArgs& a, const fs::path& giq,
                                                   const fs::path& ref, const fs::path& test,
                                                   const fs::path& timings, const fs::path& dir,
                                                   const fs::path& log) {
  std::vector<std::string> sc = {giq.string(), "score",       "--ref",   ref.string(),
                                 "--test",     test.string(), "--layer", a.layer,
                                 "--scene",    a.scene,       "--out",   dir.string()};
  if (!timings.empty()) sc.insert(sc.end(), {"--timings", timings.string()});
  must(run_process(sc, log), "giq score", log);
  const json m = read_json(dir / "metrics.json");
  std::map<std::string, std::optional<double>> out;
  for (const metrics::MetricInfo& info : metrics::kMetricCatalogue)
    if (info.scope == metrics::Scope::Image)
      if (const auto v = gate::find_metric(m, std::string(info.name))) out[std::string(info.name)] = v->value;
  return out;
}

int run_techniques(const SweepArgs& a, const fs::path& giq, const fs::path& out) {
  if (a.techniques.empty())
    throw InputError("", "--technique", "give at least one technique (giq realtime --list)");
  const std::string error = a.error.empty() ? "flip_mean" : a.error;
  const metrics::MetricInfo* error_info = metrics::find_metric_info(error);
  if (!error_info || error_info->scope != metrics::Scope::Image) {
    std::string names;
    for (const metrics::MetricInfo& m : metrics::kMetricCatalogue)
      if (m.scope == metrics::Scope::Image) names += (names.empty() ? "" : ", ") + std::string(m.name);
    throw InputError("", "--error", "unknown per-image metric '" + error + "'; expected one of: " + names);
  }
  const auto declared = list_techniques(giq, out / "techniques.json");

  struct Job {
    const TechniqueParameters* technique;
    Setting setting;
  };
  std::vector<const TechniqueParameters*> swept;
  for (const std::string& name : a.techniques) {
    const auto it = std::find_if(declared.begin(), declared.end(),
                                 [&](const auto& t) { return t.name == name; });
    if (it == declared.end())
      throw InputError("", "--technique", "'" + name + "' is not listed by giq realtime --list");
    swept.push_back(&*it);
  }
  check_grid(swept, a.grid);
  std::vector<Job> jobs;
  for (const TechniqueParameters* t : swept) {
    std::vector<std::string> grid = a.grid;
    if (a.quality) grid.push_back(quality_axis(*t));
    for (const Setting& s : plan_settings(*t, grid, a.auto_steps, a.max_settings)) jobs.push_back({t, s});
  }
  const fs::path ref =
      a.ref.empty() ? reference(a, giq, out, a.ref_spp, 1, "reference.exr") : fs::path(a.ref);
  if (!fs::exists(ref)) throw InputError(ref.string(), "--ref", "no such reference file");

  std::vector<gate::SweepRow> rows(jobs.size());
  // Progress on a terminal: settings done, and the time left at the mean pace so far.
  ProgressLine line;
  std::mutex progress;
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  line.show("giq sweep: 0/%zu settings", jobs.size());
  parallel_for(jobs.size(), a.jobs, [&](size_t i) {
    struct Report {  // when the setting ends, however it ends
      std::function<void()> f;
      ~Report() { f(); }
    } report{[&] {
      std::lock_guard<std::mutex> g(progress);
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++done;
      line.show("giq sweep: %zu/%zu settings  %s elapsed  ETA %s", done, jobs.size(), format_seconds(elapsed).c_str(),
                format_seconds(elapsed / double(done) * double(jobs.size() - done)).c_str());
    }};
    gate::SweepRow& row = rows[i];
    row.technique = jobs[i].technique->name;
    row.parameters = jobs[i].setting;
    row.is_default = is_default(*jobs[i].technique, jobs[i].setting);
    const fs::path dir = out / "runs" / row.technique / std::to_string(i);
    try {
      fs::remove_all(dir);
      fs::create_directories(dir);
      const fs::path log = dir / "log.txt";
      std::vector<std::string> rt = {giq.string(),  "realtime",
                                     "--scene",     a.scene,
                                     "--technique", row.technique,
                                     "--width",     std::to_string(a.width),
                                     "--height",    std::to_string(a.height),
                                     "--warmup",    std::to_string(a.warmup),
                                     "--frames",    std::to_string(a.frames),
                                     "--out",       (dir / "technique").string()};
      for (const std::string& v : view_arguments(a)) rt.push_back(v);
      for (const auto& [k, v] : row.parameters) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s=%.10g", k.c_str(), v);
        rt.insert(rt.end(), {"--param", buf});
      }
      if (!a.device.empty()) rt.insert(rt.end(), {"--device", a.device});
      must(run_process(rt, log), "giq realtime", log);
      fs::path timings = dir / "technique" / "timings.json";
      const fs::path scored_timings = timings;
      if (a.timing_width > 0) {
        // GPU time at another resolution than the scored images (e.g. 1080p on the GPU of
        // interest while the error is measured at the reference's resolution): the same
        // command without images.
        std::vector<std::string> tr = rt;
        for (size_t k = 0; k + 1 < tr.size(); ++k) {
          if (tr[k] == "--width") tr[k + 1] = std::to_string(a.timing_width);
          if (tr[k] == "--height") tr[k + 1] = std::to_string(a.timing_height);
          if (tr[k] == "--out") tr[k + 1] = (dir / "timing").string();
        }
        tr.push_back("--no-images");
        must(run_process(tr, log), "giq realtime (timing)", log);
        timings = dir / "timing" / "timings.json";
      }
      row.gpu_ms = gate::read_timings(timings).gpu_ms;
      row.metrics = score(a, giq, ref, dir / "technique" / frame_file(a.warmup + a.frames - 1), scored_timings,
                          dir / "score", log);
    } catch (const std::exception& e) {
      row.error = e.what();
    }
  });
  line.finish();
  gate::mark_front(rows, error);
  write_file_atomically(out / "sweep.csv", gate::sweep_csv(rows, sweep_metrics(error)));
  json run = {{"scene", a.scene},   {"view", a.view},     {"resolution", {a.width, a.height}},
              {"warmup", a.warmup}, {"frames", a.frames}, {"reference", ref.string()},
              {"layer", a.layer},
              {"timing_resolution", a.timing_width > 0 ? json::array({a.timing_width, a.timing_height})
                                                       : json::array({a.width, a.height})}};
  if (!a.camera.empty()) run["view"] = "camera", run["camera"] = a.camera;
  write_file_atomically(out / "sweep.json", gate::sweep_json(rows, error, run).dump(2) + "\n");
  write_file_atomically(out / "sweep.svg",
                        gate::sweep_svg(rows, error, !a.linear,
                                        fs::path(a.scene).stem().string() + " / " +
                                            (a.camera.empty() ? a.view : "camera") + ": " +
                                            error + " vs GPU ms"));
  int failed = 0;
  for (const auto& r : rows) {
    if (!r.error.empty())
      ++failed, std::cerr << "giq sweep: " << r.technique << " "
                          << gate::setting_label(r.parameters) << ": " << r.error << '\n';
  }
  std::cout << "giq sweep: " << rows.size() << " settings (" << failed
            << " failed), Pareto front on " << error << " -> " << (out / "sweep.csv").string()
            << ", sweep.json, sweep.svg\n";
  return failed ? 1 : 0;
}

int run_convergence(const SweepArgs& a, const fs::path& giq, const fs::path& out) {
  if (a.spp.size() < 2)
    throw InputError("", "--spp", "give at least two sample counts, e.g. --spp 1,4,16,64");
  const std::string error = a.error.empty() ? "rmse" : a.error;
  const fs::path truth =
      a.ref.empty() ? reference(a, giq, out, a.ref_spp, 1, "truth.exr") : fs::path(a.ref);
  std::vector<double> spp, seconds, err;
  json rows = json::array();
  ProgressLine line;
  const auto start = std::chrono::steady_clock::now();
  for (uint32_t n : a.spp) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    line.show("giq sweep: reference at %u spp (%zu/%zu)  %s elapsed", n, size_t(rows.size()) + 1, a.spp.size(),
              format_seconds(elapsed).c_str());
    double s = 0.0;
    // A seed other than the truth's, so the two estimates' noise is independent.
    const fs::path img = reference(a, giq, out, n, 2, "spp_" + std::to_string(n) + ".exr", &s);
    const auto m =
        score(a, giq, truth, img, {}, out / ("score_spp_" + std::to_string(n)), out / "log.txt");
    const auto it = m.find(error);
    const double e = it != m.end() && it->second ? *it->second : std::nan("");
    spp.push_back(n), seconds.push_back(s), err.push_back(e);
    rows.push_back(
        {{"spp", n}, {"seconds", s}, {error, std::isfinite(e) ? json(e) : json(nullptr)}});
  }
  line.finish();
  const gate::LineFit by_spp = gate::fit_log_log(spp, err),
                      by_seconds = gate::fit_log_log(seconds, err);
  auto fit_json = [](const gate::LineFit& f) {
    return json{
        {"slope", f.slope}, {"intercept_log10", f.intercept}, {"r2", f.r2}, {"points", f.points}};
  };
  write_file_atomically(out / "convergence.json", json{{"version", 1},
                                                       {"scene", a.scene},
                                                       {"view", a.view},
                                                       {"error_metric", error},
                                                       {"sampler", a.sampler},
                                                       {"truth", truth.string()},
                                                       {"rows", rows},
                                                       {"fit_spp", fit_json(by_spp)},
                                                       {"fit_seconds", fit_json(by_seconds)}}
                                                          .dump(2) +
                                                      "\n");
  std::ostringstream csv;
  csv << "spp,seconds," << error << '\n';
  for (size_t i = 0; i < spp.size(); ++i)
    csv << spp[i] << ',' << seconds[i] << ',' << err[i] << '\n';
  write_file_atomically(out / "convergence.csv", csv.str());
  for (const auto& [x, f, label, file] :
       {std::tuple{&spp, by_spp, std::string("samples per pixel"),
                   std::string("convergence_spp.svg")},
        std::tuple{&seconds, by_seconds, std::string("render seconds"),
                   std::string("convergence_seconds.svg")}}) {
    gate::PlotSeries s{"reference " + error, {}, true};
    for (size_t i = 0; i < x->size(); ++i) s.points.push_back({(*x)[i], err[i], false, ""});
    gate::PlotOptions o;
    o.title = "reference convergence: " + error + " vs " + label;
    o.x_label = label, o.y_label = error, o.log_x = o.log_y = true, o.fit = f;
    write_file_atomically(out / file, gate::svg_plot({s}, o));
  }
  std::printf("giq sweep --convergence: %s slope %.3f vs spp, %.3f vs seconds (R^2 %.3f) -> %s\n",
              error.c_str(), by_spp.slope, by_seconds.slope, by_spp.r2,
              (out / "convergence.json").c_str());
  return 0;
}

int run_sweep(const SweepArgs& a) {
  if (a.scene.empty()) throw InputError("", "--scene", "a scene is required");
  if (a.jobs < 1 || a.frames < 1 || a.warmup < 0)
    throw InputError("", "--jobs/--frames/--warmup", "must be positive");
  // An axis of more values than --max-settings cannot be run; refused before its values are
  // even listed (building a million of them takes minutes).
  if (a.auto_steps < 0 || a.auto_steps > a.max_settings)
    throw InputError("", "--auto", std::to_string(a.auto_steps) + " values per parameter; expected 0 to --max-settings (" +
                                       std::to_string(a.max_settings) + ")");
  if ((a.timing_width > 0) != (a.timing_height > 0) || a.timing_width < 0 || a.timing_height < 0)
    throw InputError("", "--timing-width/--timing-height",
                     std::to_string(a.timing_width) + "x" + std::to_string(a.timing_height) +
                         "; expected both positive, or neither");
  const fs::path giq = a.giq.empty() ? self_executable() : fs::absolute(a.giq);
  const fs::path out = fs::absolute(a.out);  // recorded in metrics.json: valid from anywhere
  fs::create_directories(out);
  return a.convergence ? run_convergence(a, giq, out) : run_techniques(a, giq, out);
}

}  // namespace

void add_sweep_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Speed against accuracy: techniques over parameter settings, or reference convergence");
  cmd->add_option("--scene", a->scene, "Scene (.gltf/.glb)");
  cmd->add_option("--view", a->view, "View name or index")->capture_default_str();
  cmd->add_option("--camera", a->camera,
                  "Camera in world coordinates instead of a view, one quoted argument as giq reference's "
                  "--camera takes it: \"eye=x,y,z target=x,y,z fov=deg [frame=...]\" (docs/own-engine.md)");
  cmd->add_option("--technique", a->techniques,
                  "Technique to sweep (repeatable; several share one plot)");
  cmd->add_option("--grid", a->grid, "Axis 'param=a,b,c' or 'technique.param=a,b,c' (repeatable)");
  cmd->add_flag("--quality", a->quality,
                "Sweep each technique's declared quality knob (giq realtime --list shows it)");
  cmd->add_option("--auto", a->auto_steps,
                  "Values per declared parameter range for parameters without --grid");
  cmd->add_option("--max-settings", a->max_settings,
                  "Refuse plans with more settings per technique")
      ->capture_default_str();
  cmd->add_option("--ref", a->ref,
                  "Reference EXR (default: rendered with giq reference at --ref-spp)");
  cmd->add_option("--ref-spp", a->ref_spp, "Samples per pixel of a rendered reference")
      ->capture_default_str();
  cmd->add_option("--layer", a->layer, "Layer scored")->capture_default_str();
  cmd->add_option(
      "--error", a->error,
      "Error metric of the front and plots (default flip_mean; rmse for --convergence)");
  cmd->add_option("--width", a->width, "Image width")->capture_default_str();
  cmd->add_option("--height", a->height, "Image height")->capture_default_str();
  cmd->add_option("--timing-width", a->timing_width,
                  "Measure GPU ms at this width in a separate run without images (default: --width)");
  cmd->add_option("--timing-height", a->timing_height, "Height of the timing run (with --timing-width)");
  cmd->add_option("--warmup", a->warmup, "Frames before the measured ones")->capture_default_str();
  cmd->add_option("--frames", a->frames, "Measured frames (median GPU ms)")->capture_default_str();
  cmd->add_option("--device", a->device, "Vulkan device for giq realtime");
  cmd->add_option("--jobs", a->jobs, "Settings run in parallel (GPU timings are cleaner with 1)")
      ->capture_default_str();
  cmd->add_option("--out", a->out, "Output folder")->capture_default_str();
  cmd->add_option("--giq", a->giq, "giq binary whose subcommands are run (default: this one)");
  cmd->add_flag("--linear", a->linear, "Linear axes instead of log-log");
  cmd->add_flag("--convergence", a->convergence,
                "Reference convergence: error vs spp and seconds (with --spp)");
  cmd->add_option("--spp", a->spp, "Sample counts for --convergence, e.g. 1,4,16,64")
      ->delimiter(',');
  cmd->add_option("--sampler", a->sampler, "giq reference's sampler for rendered references: sobol or independent")
      ->capture_default_str();
  cmd->footer("Example: two techniques' quality knobs on the Cornell box, error against GPU time:\n  giq sweep --scene scenes/cornell.gltf --technique rsm --technique vct --quality --out sweep-out");
  cmd->callback([a, &exit_code] { exit_code = run_sweep(*a); });
}

}  // namespace giq::cli
