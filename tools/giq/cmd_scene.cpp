// `giq scene info <scene>`: what a scene contains and what a renderer will need for it.

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "command.h"
#include "giq/image/image.h"
#include "giq/scenes/scene.h"

namespace giq::cli {
namespace {

using nlohmann::json;
namespace sc = giq::scenes;

json vec(glm::vec3 v) { return json::array({v.x, v.y, v.z}); }
json vec(glm::dvec3 v) { return json::array({v.x, v.y, v.z}); }

const char* light_type_name(sc::LightType t) {
  switch (t) {
    case sc::LightType::Directional: return "directional";
    case sc::LightType::Point: return "point";
    case sc::LightType::Spot: return "spot";
  }
  return "?";
}

json describe(const sc::Scene& s) {
  json j;
  j["path"] = s.path.string();
  j["content_hash"] = s.content_hash;
  j["features"] = s.features.names();
  j["counts"] = {{"meshes", s.meshes.size()},
                 {"triangles", s.stats.triangles},
                 {"vertices", s.stats.vertices},
                 {"materials", s.materials.size()},
                 {"textures", s.textures.size()},
                 {"punctual_lights", s.lights.size()},
                 {"emissive_triangles", s.emissive_triangles.size()},
                 {"degenerate_triangles_dropped", s.stats.degenerate_triangles_dropped}};
  glm::dvec3 lo = s.origin + glm::dvec3(s.bounds.lo), hi = s.origin + glm::dvec3(s.bounds.hi);
  j["bounds"] = {{"min", vec(lo)}, {"max", vec(hi)}, {"extent", vec(s.bounds.extent())}};
  j["origin"] = vec(s.origin);

  json lights = json::array();
  for (const auto& l : s.lights) {
    json e = {{"name", l.name}, {"type", light_type_name(l.type)}, {"color", vec(l.color)},
              {"intensity", l.intensity}};
    if (l.type != sc::LightType::Directional) e["position"] = vec(s.origin + glm::dvec3(l.position));
    if (l.type != sc::LightType::Point) e["direction"] = vec(l.direction);
    if (l.range > 0) e["range"] = l.range;
    if (l.type == sc::LightType::Spot) {
      e["inner_cone_deg"] = glm::degrees(l.inner_cone);
      e["outer_cone_deg"] = glm::degrees(l.outer_cone);
    }
    lights.push_back(e);
  }
  // Emissive meshes are area lights: one entry per mesh, with its summed power.
  std::vector<double> power(s.meshes.size(), 0.0), area(s.meshes.size(), 0.0);
  for (const auto& t : s.emissive_triangles) power[t.mesh] += t.power, area[t.mesh] += t.area;
  for (size_t m = 0; m < s.meshes.size(); ++m) {
    if (power[m] <= 0.0 && area[m] <= 0.0) continue;
    const auto& mat = s.materials[s.meshes[m].material];
    lights.push_back({{"name", s.meshes[m].name}, {"type", "emissive_mesh"},
                      {"radiance", vec(mat.emissive)}, {"area", area[m]}, {"power", power[m]}});
  }
  j["lights"] = lights;
  if (s.features.environment) j["environment_radiance"] = vec(s.environment);

  json views = json::array();
  for (const auto& v : s.views) {
    json view = {{"name", v.name},
                 {"source", v.node >= 0 ? "gltf_camera" : "extras"},
                 {"projection", v.camera.orthographic() ? "orthographic" : "perspective"},
                 {"position", vec(s.origin + glm::dvec3(v.camera.position))},
                 {"forward", vec(v.camera.forward)},
                 {"up", vec(v.camera.up)}};
    if (v.camera.orthographic()) view["ymag"] = v.camera.ymag;
    else view["yfov_deg"] = glm::degrees(v.camera.yfov);
    views.push_back(std::move(view));
  }
  j["views"] = views;
  j["sequence"] = {{"frames", s.sequence.frames},
                   {"fps", s.sequence.fps},
                   {"animation", s.sequence.animation},
                   {"duration_s", s.duration()}};
  j["leak_regions"] = s.leak_regions;
  j["leak_object_ids"] = s.leak_object_ids;
  j["warnings"] = s.warnings;
  return j;
}

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
    row("  " + l["name"].get<std::string>(), d);
  }
  std::printf("  views\n");
  for (const auto& v : j["views"]) {
    char b[64];
    if (v.contains("ymag")) std::snprintf(b, sizeof b, "  orthographic, half height %.4g m  ", v["ymag"].get<double>());
    else std::snprintf(b, sizeof b, "  fov %.2f deg  ", v["yfov_deg"].get<double>());
    row("  " + v["name"].get<std::string>(), v["source"].get<std::string>() + b + "from " + v3(v["position"]));
  }
  const auto& sq = j["sequence"];
  char b[128];
  std::snprintf(b, sizeof b, "%d frames at %.3g fps (animation %d, %.3g s)", sq["frames"].get<int>(),
                sq["fps"].get<double>(), sq["animation"].get<int>(), sq["duration_s"].get<double>());
  row("sequence", b);
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
    const json j = describe(s);
    if (as_json)
      std::cout << j.dump(2) << '\n';
    else
      print_table(j);
    exit_code = 0;
  });
}

}  // namespace giq::cli
