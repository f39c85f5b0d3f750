#include "scene_description.h"

#include <glm/glm.hpp>
#include <vector>

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

}  // namespace

json describe_scene(const sc::Scene& s) {
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
    json e = {{"name", s.meshes[m].name}, {"type", "emissive_mesh"}, {"radiance", vec(mat.emissive)}, {"area", area[m]}, {"power", power[m]}};
    // A declared shape (extras.giq.area_light) as fitted at this instant.
    for (const scenes::AreaLight& a : s.area_lights) {
      if (a.mesh != m || a.shape == scenes::AreaShape::Mesh) continue;
      e["shape"] = {{"kind", scenes::name(a.shape)}, {"centre", vec(glm::dvec3(a.shape_centre) + s.origin)}, {"radius", a.shape_radius},
                    {"u", vec(a.shape_u)}, {"v", vec(a.shape_v)}};
    }
    lights.push_back(e);
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
  // The declared measurement windows, null where the scene declares none.
  auto window = [](const std::optional<std::pair<int, int>>& w) { return w ? json::array({w->first, w->second}) : json(nullptr); };
  j["sequence"]["step_frame"] = s.sequence.step_frame ? json(*s.sequence.step_frame) : json(nullptr);
  j["sequence"]["flicker_frames"] = window(s.sequence.flicker_frames);
  j["sequence"]["lag_frames"] = window(s.sequence.lag_frames);
  json emitters = json::array();
  for (const scenes::Emitter& e : s.emitters)
    emitters.push_back({{"name", e.name},
                        {"rate", e.rate},
                        {"lifetime_s", e.lifetime},
                        {"stages", e.stages},
                        {"max_particles", e.max_particles},
                        {"alive", scenes::alive_range(e, s.time).count()},
                        {"object_id", e.object_id}});
  j["emitters"] = emitters;
  j["leak_regions"] = s.leak_regions;
  j["leak_object_ids"] = s.leak_object_ids;
  j["warnings"] = s.warnings;
  return j;
}

}  // namespace giq::cli
