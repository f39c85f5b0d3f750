// `giq results`: scores every real-time technique on every built-in scene and writes
// docs/results.md, the page that puts each technique's error beside its GPU time.
//
// For each scene in scenes/*.gltf (its first view): the path-traced reference (every frame of
// an animated scene), each technique's sequence on the local Vulkan device (static scenes:
// --frames measured frames after 2 warm-up frames; animated scenes: every frame of the
// animation), and `giq score` of the beauty and of the indirect layer against the reference.
// Static scenes are scored as sequences against their single reference, which is what flicker
// measures; animated ones frame by frame, which is what lag measures, and again over the
// frames the scene declares for flicker and lag (scenes::Sequence).
//
// --gpu DIR adds GPU time and memory at 1920x1080 measured on a GPU machine
// (DIR/results/<scene>/<technique>/timings.json) and its speed-for-accuracy sweeps
// (DIR/sweeps/<scene>/<technique>/sweep.json), as bench/realtime/device-run writes them; the
// page names the device those timings.json name.
//
// Every number in the page comes from results.json, written next to the renders and beside the
// page (docs/results.json), so the page can be regenerated without the renders (--page-only),
// and one technique can be added or redone without rendering the others again (--update).
// Renders, references and scores are reused when the same giq binary ran the same command
// (the gate's stamps, gate_runner.h), so a second run only redoes what changed.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "command.h"
#include "gate_runner.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/base/json.h"
#include "giq/gate/golden_manifest.h"
#include "giq/gate/metric_lookup.h"
#include "giq/scenes/scene.h"
#include "subprocess.h"
#include "technique_listing.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ordered = nlohmann::ordered_json;

struct ResultsArgs {
  std::string out = "out/results", gpu, doc = "docs/results.md", giq;
  std::vector<std::string> techniques, scenes;
  int size = 256, spp = 256, sequence_spp = 64, frames = 32;
  bool references_only = false, page_only = false, rerender = false, update = false;
};

// metrics.json stores each metric as {"value": ...} (lag as {"value_frames": ...}); null when
// absent or undefined.
json value(const json& m, std::initializer_list<const char*> path) {
  const json* j = &m;
  for (const char* key : path) {
    if (!j->is_object() || !j->contains(key)) return nullptr;
    j = &(*j)[key];
  }
  if (j->is_object()) return j->contains("value") ? (*j)["value"] : j->value("value_frames", json(nullptr));
  return *j;
}

// The numbers the page shows, from one sequence's metrics.json: FLIP of the last frame, relMSE
// averaged over the frames, leak in the scene's declared region (share of the image's
// reference luminance, or absolute radiance per pixel where the reference region is black;
// undefined where the view shows none of it), flicker and lag of the sequence.
ordered score_row(const json& metrics) {
  const json last = metrics.contains("last_frame") ? metrics["last_frame"].value("metrics", json::object()) : json::object();
  const json seq = metrics.value("sequence", json::object());
  double sum = 0.0;
  int n = 0;
  for (const auto& f : metrics.value("per_frame", json::array()))
    if (f.contains("relmse") && f["relmse"].is_number()) sum += f["relmse"].get<double>(), ++n;
  ordered row;
  row["flip_mean"] = value(last, {"flip", "mean"});
  row["relmse"] = n > 0 ? json(sum / n) : value(last, {"relmse"});
  // A view that shows none of the declared region measures no leak there: undefined, not 0.
  const json region_pixels = value(last, {"leak", "declared", "pixels"});
  const bool region_seen = region_pixels.is_number() && region_pixels.get<double>() > 0.0;
  row["leak"] = region_seen ? value(last, {"leak", "declared", "leak"}) : json(nullptr);
  row["leak_absolute"] = region_seen ? value(last, {"leak", "declared", "leak_absolute"}) : json(nullptr);
  row["flicker"] = value(seq, {"flicker"});
  row["lag90_frames"] = value(seq, {"lag"});
  return row;
}

// A number as the page prints it: "–" for undefined, integers as they are, large values
// without decimals, the rest with 3 significant digits (trailing zeros kept).
std::string fmt(const ordered& v) {
  if (v.is_null()) return "–";
  if (v.is_number_float()) {
    const double x = v.get<double>();
    char text[64];
    if (std::abs(x) >= 1000.0) {
      std::snprintf(text, sizeof text, "%.0f", x);
      return text;
    }
    std::snprintf(text, sizeof text, "%#.3g", x);
    std::string s = text;
    if (!s.empty() && s.back() == '.') s.pop_back();
    return s;
  }
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

// Below these a metric is zero for every purpose of the page: flicker of a deterministic
// technique on a static scene is float rounding (1e-9), not temporal noise.
double page_floor(const std::string& metric) { return metric == "flicker" ? 1e-4 : 0.0; }

// Sentences saying which technique beats `direct` on a metric (lower is better), and by how much.
std::vector<std::string> comparison(const ordered& rows, const std::string& scene, const std::string& layer,
                                    const std::string& name) {
  const ordered* base = nullptr;
  for (const auto& r : rows)
    if (r["scene"] == scene && r["technique"] == "direct") base = &r;
  if (!base || !(*base)[layer].contains(name) || (*base)[layer][name].is_null()) return {};
  const double floor = page_floor(name);
  auto clip = [&](const ordered& x) {
    const double v = x.get<double>();
    return std::abs(v) < floor ? ordered(0.0) : x;
  };
  const ordered b = clip((*base)[layer][name]);
  std::vector<std::string> out;
  for (const auto& r : rows) {
    if (r["scene"] != scene || r["technique"] == "direct" || !r[layer].contains(name) || r[layer][name].is_null())
      continue;
    const ordered v = clip(r[layer][name]);
    const std::string tech = "`" + r["technique"].get<std::string>() + "`";
    const double vd = v.get<double>(), bd = b.get<double>();
    if (bd == 0.0 && vd == 0.0) {
      out.push_back(tech + " equals `direct` (" + fmt(v) + ")");
      continue;
    }
    const bool better = vd < bd;
    const std::string word = better ? "better" : "worse";
    if (std::min(std::abs(vd), std::abs(bd)) > 0.0) {
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, "%.2f", better ? bd / vd : vd / bd);
      out.push_back(tech + " is " + word + " than `direct` (" + fmt(v) + " vs " + fmt(b) + ", " + ratio + "× " + word +
                    ")");
    } else {
      out.push_back(tech + " is " + word + " than `direct` (" + fmt(v) + " vs " + fmt(b) + ")");
    }
  }
  return out;
}

// Sentences placing every technique but `direct` against the best of them on a metric (lower
// is better): the best first, then each other one as a ratio to it.
std::vector<std::string> against_best(const ordered& rows, const std::string& scene, const std::string& layer,
                                      const std::string& name) {
  const double floor = page_floor(name);
  std::vector<std::pair<double, std::string>> ranked;
  for (const auto& r : rows) {
    if (r["scene"] != scene || r["technique"] == "direct" || !r[layer].contains(name) || r[layer][name].is_null())
      continue;
    const double v = r[layer][name].get<double>();
    ranked.emplace_back(std::abs(v) < floor ? 0.0 : v, "`" + r["technique"].get<std::string>() + "`");
  }
  if (ranked.size() < 2) return {};
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const auto& [best, best_name] = ranked[0];
  if (ranked.back().first == best) return {"all equal (" + fmt(ordered(best)) + ")"};
  auto versus = [&](double v) {
    if (v == best) return std::string("equals it");
    if (best == 0.0) return std::string("worse");
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.2f× worse", v / best);
    return std::string(ratio);
  };
  std::vector<std::string> out = {best_name + " is the best (" + fmt(ordered(best)) + ")"};
  for (size_t i = 1; i < ranked.size(); ++i)
    out.push_back(ranked[i].second + " " + versus(ranked[i].first) + " (" + fmt(ordered(ranked[i].first)) + ")");
  return out;
}

std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string s;
  for (size_t i = 0; i < parts.size(); ++i) s += (i ? sep : "") + parts[i];
  return s;
}

// The GPU machine's device and resolution, from the rows that have its timings: "NVIDIA H200,
// 1920×1080" ("" when none has).
std::string gpu_run_name(const ordered& rows) {
  std::set<std::string> names;
  for (const auto& r : rows) {
    const ordered g = r.value("gpu", ordered::object());
    if (!g.contains("device")) continue;
    std::string name = g["device"].get<std::string>();
    if (g.contains("resolution") && g["resolution"].is_array() && g["resolution"].size() == 2)
      name += ", " + g["resolution"][0].dump() + "×" + g["resolution"][1].dump();
    names.insert(name);
  }
  return join({names.begin(), names.end()}, "; ");
}

std::string page(const ordered& results) {
  const ordered& s = results["settings"];
  const ordered& rows = results["rows"];
  const std::string gpu = gpu_run_name(rows);
  const std::string gpu_column = gpu.empty() ? "GPU ms (GPU machine)" : "GPU ms (" + gpu + ")";
  std::vector<std::string> lines = {
      "# Results: each technique against the path-traced truth",
      "",
      "Generated by `giq results` from `results.json`; do not edit by hand. Resolution " + s["size"].dump() + "×" +
          s["size"].dump() + ", references at " + s["reference_spp"].dump() + " spp (" +
          s["sequence_reference_spp"].dump() +
          " spp per frame of an animated scene; the metrics are noise-corrected, docs/metrics.md), static scenes "
          "scored over " +
          s["static_frames"].dump() +
          " frames after 2 warm-up frames, animated scenes over every frame (flicker and lag over the frames the scene "
          "declares for them, where it does). Lower is better for every metric shown. "
          "FLIP is the mean HDR-FLIP of the last frame; relMSE is averaged over the frames; leak is light in the "
          "scene's declared leak region as a share of the reference image's luminance (– where the reference is "
          "black there or the view shows none of the region), leak (abs.) the same in radiance per pixel; flicker is "
          "the relative temporal noise of the error, of the beauty and of the indirect light (below 1e-4 it is float "
          "rounding of a deterministic technique and counts as 0 in the comparisons); "
          "lag90 is in frames after the scene's step change. GPU ms (local) is the median frame time on the device "
          "that rendered the images; " + gpu_column + " and memory MB (the technique's resident GPU memory, shared "
          "passes included) come from the run on the GPU machine with the same default parameters.",
      ""};
  std::set<std::string> devices, scenes;
  for (const auto& r : rows) devices.insert(r["device"].get<std::string>()), scenes.insert(r["scene"].get<std::string>());
  lines.push_back("Local device: " + join({devices.begin(), devices.end()}, ", ") +
                  " (its GPU ms are for this device only).");
  lines.push_back("");
  for (const std::string& scene : scenes) {
    lines.insert(lines.end(), {"## " + scene, ""});
    const auto first_row = std::find_if(rows.begin(), rows.end(), [&](const ordered& r) { return r["scene"] == scene; });
    std::vector<std::string> windows;
    for (const auto& [key, metric] : {std::pair{"flicker_frames", "flicker"}, std::pair{"lag_frames", "lag"}})
      if (first_row->contains(key)) {
        const ordered& w = (*first_row)[key];
        const auto range = w.is_string() ? parse_frame_range(w.get<std::string>()) : std::nullopt;
        if (!range) throw InputError("results.json", std::string("rows[].") + key, w.dump() + "; expected \"A:B\"");
        windows.push_back(std::string(metric) + " over frames " + std::to_string(range->first) + "–" + std::to_string(range->second));
      }
    if (!windows.empty())
      lines.insert(lines.end(), {join(windows, ", ") + ", as the scene declares (`extras.giq.sequence`).", ""});
    lines.push_back(
        "| technique | FLIP (beauty) | relMSE (beauty) | FLIP (indirect) | relMSE (indirect) | leak | leak (abs.) | "
        "flicker (beauty) | flicker (indirect) | lag90 (frames) | GPU ms (local) | " + gpu_column + " | memory MB |");
    lines.push_back("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (const auto& r : rows) {
      if (r["scene"] != scene) continue;
      const ordered h = r.value("gpu", ordered::object());
      const ordered memory = h.value("gpu_memory_mb", ordered(nullptr)).is_object() ? h["gpu_memory_mb"]
                             : r.value("gpu_memory_mb", ordered(nullptr)).is_object() ? r["gpu_memory_mb"]
                                                                                       : ordered::object();
      lines.push_back("| " +
                      join({"`" + r["technique"].get<std::string>() + "`", fmt(r["beauty"]["flip_mean"]),
                            fmt(r["beauty"]["relmse"]), fmt(r["indirect"]["flip_mean"]), fmt(r["indirect"]["relmse"]),
                            fmt(r["beauty"]["leak"]), fmt(r["beauty"]["leak_absolute"]), fmt(r["beauty"]["flicker"]),
                            fmt(r["indirect"]["flicker"]), fmt(r["beauty"]["lag90_frames"]), fmt(r["gpu_ms"]),
                            fmt(h.value("gpu_ms", ordered(nullptr))),
                            fmt(memory.value("technique", ordered(nullptr)))},
                           " | ") +
                      " |");
    }
    lines.push_back("");
    const std::vector<std::array<std::string, 3>> said_of = {
        {"beauty", "flip_mean", "FLIP of the beauty"},   {"beauty", "relmse", "relMSE of the beauty"},
        {"indirect", "relmse", "relMSE of the indirect light"}, {"beauty", "leak", "leak"},
        {"beauty", "leak_absolute", "absolute leak"},    {"beauty", "flicker", "flicker of the beauty"},
        {"indirect", "flicker", "flicker of the indirect light"}, {"beauty", "lag90_frames", "lag"}};
    for (const auto& [layer, name, label] : said_of) {
      const auto said = comparison(rows, scene, layer, name);
      if (!said.empty()) lines.push_back("- " + label + ": " + join(said, "; ") + ".");
      const auto ranked = against_best(rows, scene, layer, name);
      if (!ranked.empty()) lines.push_back("- " + label + ", against the best other technique: " + join(ranked, "; ") + ".");
    }
    lines.push_back("");
  }
  const ordered sweeps = results.value("sweeps", ordered::array());
  if (!sweeps.empty()) {
    const ordered& r0 = sweeps[0];
    lines.insert(lines.end(),
                 {"## Speed for accuracy (" + gpu + ")", "",
                  "Each technique's main quality knob, cheapest to best: GPU ms at " + r0["timing_resolution"][0].dump() +
                      "×" + r0["timing_resolution"][1].dump() +
                      " on the GPU machine (median of 20 frames after 10 warm-up frames), error of the beauty at " +
                      r0["resolution"][0].dump() + "×" + r0["resolution"][1].dump() +
                      " against the reference (last of those frames). ★ marks the Pareto front within the technique (no "
                      "other setting of it both faster and more accurate by FLIP); (default) the technique's default. "
                      "The plots are " + s.value("gpu_dir", std::string("<gpu>")) +
                      "/sweeps/<scene>/<technique>/sweep.svg.",
                  ""});
    std::set<std::string> sweep_scenes;
    for (const auto& r : sweeps) sweep_scenes.insert(r["scene"].get<std::string>());
    for (const std::string& scene : sweep_scenes) {
      lines.insert(lines.end(), {"### " + scene, "", "| technique | setting | GPU ms | FLIP | relMSE | front |",
                                 "|---|---|---|---|---|---|"});
      for (const auto& r : sweeps) {
        if (r["scene"] != scene) continue;
        std::vector<std::string> settings;
        for (const auto& [k, v] : r["parameters"].items()) {
          char number[32];
          std::snprintf(number, sizeof number, "%g", v.get<double>());
          settings.push_back(k + "=" + number);
        }
        std::string setting = settings.empty() ? "defaults" : join(settings, ", ");
        if (r.value("default", false)) setting += " (default)";
        lines.push_back("| `" + r["technique"].get<std::string>() + "` | " + setting + " | " + fmt(r["gpu_ms"]) + " | " +
                        fmt(r["flip_mean"]) + " | " + fmt(r["relmse"]) + " | " +
                        (r.value("pareto_front", false) ? "★" : "") + " |");
      }
      lines.push_back("");
    }
  }
  return join(lines, "\n");
}

// Rows of every sweep.json under folder/<scene>/<technique>/ (bench/realtime/device-run).
ordered sweep_rows(const fs::path& folder) {
  std::vector<fs::path> files;
  if (fs::is_directory(folder))
    for (const auto& s : fs::directory_iterator(folder))
      if (s.is_directory())
        for (const auto& t : fs::directory_iterator(s.path()))
          if (fs::exists(t.path() / "sweep.json")) files.push_back(t.path() / "sweep.json");
  std::sort(files.begin(), files.end());
  ordered found = ordered::array();
  for (const fs::path& p : files) {
    const ordered d = read_ordered_json(p);
    for (const auto& r : d["rows"]) {
      const ordered metrics = r.value("metrics", ordered::object());
      ordered row;
      row["scene"] = p.parent_path().parent_path().filename().string();
      row["technique"] = p.parent_path().filename().string();
      row["parameters"] = r["parameters"];
      row["default"] = r.value("default", false);
      row["gpu_ms"] = r.value("gpu_ms", ordered(nullptr));
      row["flip_mean"] = metrics.value("flip_mean", ordered(nullptr));
      row["relmse"] = metrics.value("relmse", ordered(nullptr));
      row["pareto_front"] = r.value("pareto_front", ordered(nullptr));
      row["resolution"] = d["run"]["resolution"];
      row["timing_resolution"] = d["run"].value("timing_resolution", ordered(nullptr));
      row["error"] = r.value("error", std::string());
      found.push_back(row);
    }
  }
  return found;
}

// Runs a step of the page unless its folder holds the outputs of this very command.
void run_step(const std::vector<std::string>& argv, const fs::path& dir, const std::string& giq_hash, bool rerender) {
  const std::string problem = run_cached_step(argv, dir, dir.parent_path() / (dir.filename().string() + ".log"),
                                              argv[1], {{"argv", argv}, {"giq", giq_hash}}, rerender);
  if (!problem.empty()) throw InputError("", argv[1], problem);
}

// --update: the rows of the page's .json that this run did not render again (other techniques
// or scenes) join this run's, in the page's order (scenes by name, techniques as registered);
// the page must have been made with the same settings, so that every row is comparable.
void keep_other_rows(ordered& results, const fs::path& page_json, const fs::path& giq, const fs::path& out) {
  const ordered old = read_ordered_json(page_json);
  for (const char* k : {"size", "reference_spp", "sequence_reference_spp", "static_frames"})
    if (old.at("settings").value(k, json()) != results["settings"][k])
      throw InputError(page_json.string(), std::string("settings.") + k,
                       old["settings"].value(k, json()).dump() + " differs from this run's " +
                           results["settings"][k].dump() + "; --update keeps rows only from a page made with the same "
                           "--size, --spp, --sequence-spp and --frames");
  std::vector<std::string> order;
  for (const TechniqueParameters& t : list_techniques(giq, out / "techniques.json")) order.push_back(t.name);
  auto rank = [&](const ordered& row) {
    const std::string t = row.at("technique").get<std::string>();
    const auto it = std::find(order.begin(), order.end(), t);
    return std::make_pair(row.at("scene").get<std::string>(), it - order.begin());
  };
  ordered rows = results["rows"];
  std::set<std::pair<std::string, long>> fresh;
  for (const auto& r : rows) fresh.insert(rank(r));
  for (const auto& r : old.at("rows"))
    if (!fresh.count(rank(r))) rows.push_back(r);
  std::vector<ordered> sorted(rows.begin(), rows.end());
  std::stable_sort(sorted.begin(), sorted.end(), [&](const ordered& x, const ordered& y) { return rank(x) < rank(y); });
  results["rows"] = sorted;
  if (!results.contains("sweeps") && old.contains("sweeps")) results["sweeps"] = old["sweeps"];
  if (!results["settings"].contains("gpu_dir") && old["settings"].contains("gpu_dir"))
    results["settings"]["gpu_dir"] = old["settings"]["gpu_dir"];
}

// The GPU machine's figures of one row (bench/realtime/device-run's
// DIR/results/<scene>/<technique>/timings.json); null when it measured none.
ordered gpu_row(const fs::path& gpu, const std::string& scene, const std::string& technique) {
  const fs::path h = gpu / "results" / scene / technique / "timings.json";
  if (!fs::exists(h)) return nullptr;
  const json ht = read_json(h);
  ordered passes = ordered::object();
  for (const auto& p : ht.at("passes")) passes[p.at("name").get<std::string>()] = p["gpu_ms"]["median"];
  return {{"device", ht["device"]["name"]},
          {"resolution", ht["resolution"]},
          {"gpu_ms", ht["frame_gpu_ms"]["median"]},
          {"passes", passes},
          {"gpu_memory_mb", ht.value("gpu_memory_mb", json(nullptr))}};
}

int run_results(const ResultsArgs& a) {
  const fs::path out = fs::absolute(a.out), doc = a.doc;
  if (a.page_only) {
    const fs::path data = doc.parent_path() / (doc.stem().string() + ".json");
    ordered results = read_ordered_json(data);
    // With --gpu, the GPU machine's figures are read again (a new measurement there, the
    // local renders unchanged): the rows it measured, and its sweeps where it has some.
    if (!a.gpu.empty()) {
      for (auto& row : results["rows"]) {
        const ordered g = gpu_row(a.gpu, row.at("scene").get<std::string>(), row.at("technique").get<std::string>());
        if (!g.is_null()) row["gpu"] = g;
      }
      if (fs::is_directory(fs::path(a.gpu) / "sweeps")) results["sweeps"] = sweep_rows(fs::path(a.gpu) / "sweeps");
      results["settings"]["gpu_dir"] = a.gpu;
      write_file_atomically(data, results.dump(1));
    }
    write_file_atomically(doc, page(results));
    std::cout << "giq results: " << doc.string() << " from " << (doc.parent_path() / (doc.stem().string() + ".json")).string() << '\n';
    return 0;
  }
  const fs::path giq = a.giq.empty() ? self_executable() : fs::absolute(a.giq);
  const std::string giq_hash = gate::file_hash(giq);
  fs::create_directories(out);
  std::vector<std::string> techs = a.techniques;
  if (techs.empty())
    for (const TechniqueParameters& t : list_techniques(giq, out / "techniques.json"))
      if (t.name != "pt") techs.push_back(t.name);
  std::vector<fs::path> scene_files;
  for (const auto& e : fs::directory_iterator("scenes"))
    if (e.path().extension() == ".gltf" &&
        (a.scenes.empty() || std::count(a.scenes.begin(), a.scenes.end(), e.path().stem().string())))
      scene_files.push_back(fs::absolute(e.path()));
  std::sort(scene_files.begin(), scene_files.end());
  for (const std::string& name : a.scenes)
    if (std::none_of(scene_files.begin(), scene_files.end(), [&](const fs::path& p) { return p.stem() == name; }))
      throw InputError("scenes/" + name + ".gltf", "--scene", "no such built-in scene (run from the repository root)");
  if (scene_files.empty()) throw InputError("scenes", "--scene", "no built-in scene found (run from the repository root)");
  const std::string size = std::to_string(a.size);

  ordered results;
  results["settings"] = {{"size", a.size}, {"reference_spp", a.spp}, {"sequence_reference_spp", a.sequence_spp},
                         {"static_frames", a.frames}};
  if (!a.gpu.empty()) results["settings"]["gpu_dir"] = a.gpu;
  results["rows"] = ordered::array();
  for (const fs::path& scene : scene_files) {
    const scenes::Scene loaded = scenes::load(scene);
    const int n = loaded.features.animation ? loaded.sequence.frames : 1;
    const bool animated = n > 1;
    const std::string stem = scene.stem().string();
    const fs::path ref_dir = out / stem / "reference";
    // The independent sampler, as for the goldens: leak counts light beyond 3 sigma per pixel,
    // which wants a per-pixel variance with a degree of freedom per sample (docs/gate.md).
    std::vector<std::string> ref = {giq.string(), "reference", "--scene", scene.string(), "--view", "0"};
    if (animated) ref.insert(ref.end(), {"--frames", frame_range(0, n - 1)});
    else ref.insert(ref.end(), {"--frame", "0"});
    // --resume: an interrupted reference continues where it stopped.
    ref.insert(ref.end(), {"--resume", "--spp", std::to_string(animated ? a.sequence_spp : a.spp), "--seed", "1", "--width", size,
                           "--height", size, "--sampler", "independent", "--out",
                           (ref_dir / (animated ? "frame_#.exr" : frame_file(0))).string()});
    run_step(ref, ref_dir, giq_hash, a.rerender);
    if (a.references_only) continue;
    for (const std::string& tech : techs) {
      const fs::path tdir = out / stem / tech;
      std::vector<std::string> rt = {giq.string(), "realtime", "--scene", scene.string(), "--view", "0",
                                     "--technique", tech};
      if (animated) rt.insert(rt.end(), {"--warmup", "0", "--frames", std::to_string(n)});
      else rt.insert(rt.end(), {"--warmup", "2", "--frames", std::to_string(a.frames)});
      rt.insert(rt.end(), {"--width", size, "--height", size, "--out", (tdir / "frames").string()});
      run_step(rt, tdir / "frames", giq_hash, a.rerender);
      const int first = animated ? 0 : 2, last = animated ? n - 1 : a.frames + 1;
      const gate::FrameTime t = gate::read_timings(tdir / "frames" / "timings.json");
      const json timings = read_json(tdir / "frames" / "timings.json");
      ordered row;
      row["scene"] = stem;
      row["technique"] = tech;
      row["device"] = t.device;
      row["gpu_ms"] = *t.gpu_ms;
      row["gpu_memory_mb"] = timings.value("gpu_memory_mb", json(nullptr));
      auto score = [&](const std::string& layer, std::pair<int, int> frames, const std::string& name) {
        const fs::path sdir = tdir / name;
        run_step({giq.string(), "score", "--ref", (ref_dir / (animated ? "frame_%d.exr" : frame_file(0))).string(),
                  "--test", (tdir / "frames" / kFramePattern).string(), "--frames", frame_range(frames.first, frames.second),
                  "--layer", layer, "--scene", scene.string(), "--timings", (tdir / "frames" / "timings.json").string(),
                  "--out", sdir.string()},
                 sdir, giq_hash, a.rerender);
        return score_row(read_json(sdir / "metrics.json"));
      };
      // Flicker and lag over the frames the scene declares for them, the rest over every
      // frame; lag of the beauty only (the page shows no other).
      const scenes::Sequence& sq = loaded.sequence;
      for (const std::string layer : {"beauty", "indirect"}) {
        row[layer] = score(layer, {first, last}, "score-" + layer);
        if (animated && sq.flicker_frames) row[layer]["flicker"] = score(layer, *sq.flicker_frames, "score-" + layer + "-flicker")["flicker"];
        if (animated && sq.lag_frames && layer == "beauty")
          row[layer]["lag90_frames"] = score(layer, *sq.lag_frames, "score-" + layer + "-lag")["lag90_frames"];
      }
      if (animated && sq.flicker_frames) row["flicker_frames"] = frame_range(sq.flicker_frames->first, sq.flicker_frames->second);
      if (animated && sq.lag_frames) row["lag_frames"] = frame_range(sq.lag_frames->first, sq.lag_frames->second);
      if (!a.gpu.empty())
        if (const ordered g = gpu_row(a.gpu, stem, tech); !g.is_null()) row["gpu"] = g;
      results["rows"].push_back(row);
    }
  }
  if (a.references_only) return 0;
  if (!a.gpu.empty()) results["sweeps"] = sweep_rows(fs::path(a.gpu) / "sweeps");
  if (a.update) keep_other_rows(results, doc.parent_path() / (doc.stem().string() + ".json"), giq, out);
  write_file_atomically(out / "results.json", results.dump(1));
  // The page's data beside it, so that every number can be checked and the page regenerated
  // without the renders (--page-only).
  write_file_atomically(doc.parent_path() / (doc.stem().string() + ".json"), results.dump(1));
  write_file_atomically(doc, page(results));
  std::cout << "giq results: " << (out / "results.json").string() << "; page: " << doc.string() << '\n';
  return 0;
}

}  // namespace

void add_results_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<ResultsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "results", "Score every technique on every built-in scene and write docs/results.md (run from the repository root)");
  cmd->add_option("--out", a->out, "Folder for references, renders, scores and results.json")->capture_default_str();
  cmd->add_option("--size", a->size, "Width and height of every render")->capture_default_str();
  cmd->add_option("--spp", a->spp, "Reference samples per pixel")->capture_default_str();
  cmd->add_option("--sequence-spp", a->sequence_spp, "Reference samples per pixel of each frame of an animated scene")
      ->capture_default_str();
  cmd->add_option("--frames", a->frames, "Measured frames of a static scene")->capture_default_str();
  cmd->add_option("--technique", a->techniques, "Techniques (repeatable; default: every registered one but pt)");
  cmd->add_option("--scene", a->scenes, "Built-in scenes by name (repeatable; default: every scenes/*.gltf)");
  cmd->add_option("--gpu", a->gpu, "Folder of 1080p timings and sweeps measured on a GPU machine (bench/realtime/device-run)");
  cmd->add_option("--doc", a->doc, "The page written; its data goes beside it as .json")->capture_default_str();
  cmd->add_option("--giq", a->giq, "giq binary whose subcommands are run (default: this one)");
  cmd->add_flag("--references-only", a->references_only, "Render the references and stop");
  cmd->add_flag("--page-only", a->page_only,
                "Regenerate the page from its .json beside it, rendering nothing (with --gpu, its GPU figures read again)");
  cmd->add_flag("--rerender", a->rerender, "Render and score again even where outputs of an identical run exist");
  cmd->add_flag("--update", a->update,
                "Keep the page's rows of the techniques and scenes not rendered in this run (same settings required)");
  cmd->footer("Examples, from the repository root:\n  giq results\n"
              "  giq results --technique hybrid --update --gpu bench/results/h200   (add one technique to the page)");
  cmd->callback([a, &exit_code] { exit_code = run_results(*a); });
}

}  // namespace giq::cli
