// `giq scene info <scene>`: what a scene contains and what a renderer will need for it.

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "scene_description.h"
#include "giq/scenes/scene.h"

namespace giq::cli {
namespace {

using nlohmann::json;
namespace sc = giq::scenes;

void print_table(const json& j) {
  auto row = [](const std::string& k, const std::string& v) {
    std::printf("  %-28s %s\n", k.c_str(), v.c_str());
  };
  auto v3 = [](const json& a) {
    char b[96];
    std::snprintf(b, sizeof b, "(%.4g, %.4g, %.4g)", a[0].get<double>(), a[1].get<double>(),
                  a[2].get<double>());
    return std::string(b);
  };
  std::printf("%s\n", j["path"].get<std::string>().c_str());
  row("content hash", j["content_hash"]);
  std::string feats;
  for (const auto& f : j["features"]) feats += (feats.empty() ? "" : ", ") + f.get<std::string>();
  row("features", feats.empty() ? "(none)" : feats);
  for (auto& [k, v] : j["counts"].items()) row(k, std::to_string(v.get<long long>()));
  row("bounds min", v3(j["bounds"]["min"]));
  row("bounds max", v3(j["bounds"]["max"]));
  std::printf("  lights\n");
  for (const auto& l : j["lights"]) {
    std::string d = l["type"].get<std::string>();
    if (l.contains("intensity")) d += "  intensity " + std::to_string(l["intensity"].get<double>());
    if (l.contains("power")) d += "  power " + std::to_string(l["power"].get<double>());
    if (l.contains("position")) d += "  at " + v3(l["position"]);
    if (l.contains("shape")) d += "  declared " + l["shape"]["kind"].get<std::string>() + " at " + v3(l["shape"]["centre"]);
    row("  " + l["name"].get<std::string>(), d);
  }
  std::printf("  views\n");
  for (const auto& v : j["views"]) {
    char b[64];
    if (v.contains("ymag")) std::snprintf(b, sizeof b, "  orthographic, half height %.4g m  ", v["ymag"].get<double>());
    else std::snprintf(b, sizeof b, "  fov %.2f deg  ", v["yfov_deg"].get<double>());
    row("  " + v["name"].get<std::string>(), v["source"].get<std::string>() + b + "from " + v3(v["position"]));
  }
  if (!j["emitters"].empty()) std::printf("  particle emitters\n");
  for (const auto& e : j["emitters"]) {
    char d[160];
    std::snprintf(d, sizeof d, "%.6g per s, %.6g s each, %d stages, at most %u alive (%llu now), objectId %u", e["rate"].get<double>(),
                  e["lifetime_s"].get<double>(), e["stages"].get<int>(), e["max_particles"].get<unsigned>(),
                  (unsigned long long)e["alive"].get<uint64_t>(), e["object_id"].get<unsigned>());
    row("  " + e["name"].get<std::string>(), d);
  }
  const auto& sq = j["sequence"];
  char b[128];
  std::snprintf(b, sizeof b, "%d frames at %.3g fps (animation %d, %.3g s)", sq["frames"].get<int>(),
                sq["fps"].get<double>(), sq["animation"].get<int>(), sq["duration_s"].get<double>());
  row("sequence", b);
  if (!sq["step_frame"].is_null()) row("  step change", "frame " + sq["step_frame"].dump());
  for (const auto& [key, label] : {std::pair{"flicker_frames", "  flicker measured over"}, {"lag_frames", "  lag measured over"}})
    if (!sq[key].is_null()) row(label, "frames " + sq[key][0].dump() + " to " + sq[key][1].dump());
  std::string leaks;
  for (const auto& l : j["leak_regions"]) leaks += (leaks.empty() ? "" : ", ") + l.get<std::string>();
  row("leak regions", leaks.empty() ? "(none)" : leaks);
  // What the file holds that giq dropped or approximated (Scene::warnings).
  if (!j["warnings"].empty()) std::printf("  warnings\n");
  for (const auto& w : j["warnings"]) std::printf("    %s\n", w.get<std::string>().c_str());
}

}  // namespace

void add_scene_command(CLI::App& app, int& exit_code) {
  auto* scene = app.add_subcommand("scene", "Inspect scenes");
  scene->require_subcommand(1);
  auto* info = scene->add_subcommand("info", "Print a scene's features, counts, bounds, lights and views");
  static std::string path;
  static bool as_json = false;
  info->add_option("scene", path, "glTF 2.0 scene (.gltf or .glb)")->required();
  info->add_flag("--json", as_json, "Print JSON instead of a table");
  info->footer("Example:\n  giq scene info scenes/atrium.gltf");
  info->callback([&exit_code] {
    const sc::Scene s = sc::load(path);
    const json j = describe_scene(s);
    if (as_json)
      std::cout << j.dump(2) << '\n';
    else
      print_table(j);
    exit_code = 0;
  });
}

}  // namespace giq::cli
