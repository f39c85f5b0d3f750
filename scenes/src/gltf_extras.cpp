#include "gltf_extras.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numbers>

#include "giq/base/error.h"
#include "giq/base/frames.h"

namespace giq::scenes::gltf {
namespace {

using nlohmann::json;

struct Reader {
  const std::string& file;

  [[noreturn]] void fail(const std::string& field, const std::string& message) const { throw InputError(file, field, message); }

  void only_keys(const json& o, const std::string& field, std::initializer_list<const char*> keys) const {
    if (!o.is_object()) fail(field, "must be a JSON object");
    for (const auto& item : o.items()) {
      const std::string& k = item.key();
      if (std::none_of(keys.begin(), keys.end(), [&](const char* s) { return k == s; })) {
        std::string allowed;
        for (const char* s : keys) allowed += std::string(allowed.empty() ? "" : ", ") + s;
        fail(field + "." + k, "unknown key \"" + k + "\"; expected one of: " + allowed);
      }
    }
  }

  double number(const json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "is " + v.dump() + "; expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(field, "expected a finite number");
    return x;
  }

  glm::dvec3 vec3(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != 3) fail(field, "is " + v.dump().substr(0, 80) + "; expected an array of 3 numbers");
    return {number(v[0], field + "[0]"), number(v[1], field + "[1]"), number(v[2], field + "[2]")};
  }
};

void parse_views(const Reader& r, const json& a, Extras& out) {
  const std::string base = "extras.giq.views";
  if (!a.is_array()) r.fail(base, "must be an array of view objects");
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string w = base + "[" + std::to_string(i) + "]";
    r.only_keys(a[i], w, {"name", "eye", "target", "up", "yfov_deg", "ymag"});
    ExtraView v;
    v.field = w;
    if (!a[i].contains("name") || !a[i]["name"].is_string() || a[i]["name"].get<std::string>().empty())
      r.fail(w + ".name", "missing or not a non-empty string");
    v.name = a[i]["name"].get<std::string>();
    if (!a[i].contains("eye")) r.fail(w + ".eye", "missing; expected [x, y, z] in world coordinates");
    if (!a[i].contains("target")) r.fail(w + ".target", "missing; expected [x, y, z] in world coordinates");
    v.eye = r.vec3(a[i]["eye"], w + ".eye");
    v.target = r.vec3(a[i]["target"], w + ".target");
    if (a[i].contains("up")) v.up = r.vec3(a[i]["up"], w + ".up");
    if (a[i].contains("yfov_deg")) v.yfov_deg = r.number(a[i]["yfov_deg"], w + ".yfov_deg");
    if (!(v.yfov_deg > 0.0 && v.yfov_deg < 180.0)) r.fail(w + ".yfov_deg", "is " + std::to_string(v.yfov_deg) + "; expected degrees in (0, 180)");
    if (a[i].contains("ymag")) {
      if (a[i].contains("yfov_deg")) r.fail(w + ".ymag", "given with yfov_deg; a view is orthographic (ymag) or perspective (yfov_deg), not both");
      v.ymag = r.number(a[i]["ymag"], w + ".ymag");
      if (!(v.ymag > 0.0 && v.ymag < 1e30)) r.fail(w + ".ymag", "is " + std::to_string(v.ymag) + "; expected an orthographic half height in metres, > 0");
    }
    out.views.push_back(std::move(v));
  }
}

void parse_sequence(const Reader& r, const json& o, const SceneSource& src, Extras& out, bool& frames_given) {
  const std::string base = "extras.giq.sequence";
  r.only_keys(o, base, {"frames", "fps", "animation", "step_frame", "flicker_frames", "lag_frames"});
  // Checked against the frame count once it is known (check_windows).
  if (o.contains("step_frame")) {
    const json& f = o["step_frame"];
    if (!f.is_number_integer() || f.get<long long>() < 1 || f.get<long long>() > 1000000)
      r.fail(base + ".step_frame", "is " + f.dump() + "; expected the integer frame of the step change, at least 1");
    out.sequence.step_frame = int(f.get<long long>());
  }
  for (auto [key, window] : {std::pair{"flicker_frames", &out.sequence.flicker_frames}, {"lag_frames", &out.sequence.lag_frames}}) {
    if (!o.contains(key)) continue;
    const json& w = o[key];
    *window = w.is_string() ? parse_frame_range(w.get<std::string>()) : std::nullopt;
    if (!*window) r.fail(base + "." + key, "is " + w.dump().substr(0, 80) + "; expected \"A:B\", the first and last frame");
  }
  if (o.contains("frames")) {
    const json& f = o["frames"];
    if (!f.is_number_integer() || f.get<long long>() < 1 || f.get<long long>() > 1000000)
      r.fail(base + ".frames", "is " + f.dump() + "; expected an integer from 1 to 1000000");
    out.sequence.frames = int(f.get<long long>());
    frames_given = true;
  }
  if (o.contains("fps")) {
    out.sequence.fps = r.number(o["fps"], base + ".fps");
    if (!(out.sequence.fps > 0.0 && out.sequence.fps <= 10000.0)) r.fail(base + ".fps", "is " + std::to_string(out.sequence.fps) + "; expected a number in (0, 10000]");
  }
  if (o.contains("animation")) {
    const json& a = o["animation"];
    if (a.is_string()) {
      const std::string name = a.get<std::string>();
      auto it = std::find_if(src.animations.begin(), src.animations.end(), [&](const AnimationSource& s) { return s.name == name; });
      if (it == src.animations.end()) r.fail(base + ".animation", "no animation named \"" + name + "\" (the file has " + std::to_string(src.animations.size()) + ")");
      out.sequence.animation = int(it - src.animations.begin());
    } else if (a.is_number_integer()) {
      const long long k = a.get<long long>();
      if (k < -1 || k >= (long long)src.animations.size())
        r.fail(base + ".animation", "is " + std::to_string(k) + "; the file has " + std::to_string(src.animations.size()) + " animations (-1 = none)");
      out.sequence.animation = int(k);
    } else {
      r.fail(base + ".animation", "is " + a.dump() + "; expected an animation name or index");
    }
  }
}

// The declared windows against the sequence: inside it, flicker's before or after the step
// (flicker across a step would measure the response to it), lag's around it.
void check_windows(const Reader& r, const Sequence& s) {
  const std::string base = "extras.giq.sequence";
  const int last = s.frames - 1;
  if (s.step_frame && *s.step_frame > last)
    r.fail(base + ".step_frame", "is " + std::to_string(*s.step_frame) + "; expected a frame from 1 to " + std::to_string(last) +
                                     " (the sequence has " + std::to_string(s.frames) + " frames)");
  auto inside = [&](const std::pair<int, int>& w, const std::string& key) {
    if (w.second > last)
      r.fail(base + "." + key, "is \"" + frame_range(w.first, w.second) + "\"; the sequence's frames are 0 to " + std::to_string(last));
  };
  if (const auto& w = s.flicker_frames) {
    inside(*w, "flicker_frames");
    if (w->second == w->first) r.fail(base + ".flicker_frames", "is \"" + frame_range(w->first, w->second) + "\"; expected at least two frames");
    if (s.step_frame && w->first < *s.step_frame && *s.step_frame <= w->second)
      r.fail(base + ".flicker_frames", "is \"" + frame_range(w->first, w->second) + "\", which contains the step change at frame " +
                                           std::to_string(*s.step_frame) + "; expected frames before it or from it on");
  }
  if (const auto& w = s.lag_frames) {
    inside(*w, "lag_frames");
    if (!s.step_frame) r.fail(base + ".lag_frames", "is declared without step_frame; expected the frame of the step change too");
    if (!(w->first < *s.step_frame && *s.step_frame <= w->second))
      r.fail(base + ".lag_frames", "is \"" + frame_range(w->first, w->second) + "\"; expected A:B with A < step_frame (" +
                                       std::to_string(*s.step_frame) + ") <= B, a frame before the step and the frames after it");
  }
}

void parse_leak_regions(const Reader& r, const json& a, const SceneSource& src, Extras& out) {
  const std::string base = "extras.giq.leak_regions";
  if (!a.is_array()) r.fail(base, "must be an array of node names");
  std::vector<uint32_t> ids;
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string w = base + "[" + std::to_string(i) + "]";
    if (!a[i].is_string()) r.fail(w, "is " + a[i].dump() + "; expected a node name");
    const std::string name = a[i].get<std::string>();
    bool found = false;
    for (size_t n = 0; n < src.nodes.size(); ++n) {
      if (src.nodes[n].name != name) continue;
      found = true;
      // A region covers the named node and everything below it, so a group node can name a
      // whole room.
      std::vector<int> stack{int(n)};
      while (!stack.empty()) {
        const int k = stack.back();
        stack.pop_back();
        ids.push_back(uint32_t(k) + 1);
        for (int c : src.nodes[size_t(k)].children) stack.push_back(c);
      }
    }
    if (!found) r.fail(w, "no node named \"" + name + "\"");
    out.leak_regions.push_back(name);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  out.leak_object_ids = std::move(ids);
}

void parse_emitters(const Reader& r, const json& a, const SceneSource& src, Extras& out) {
  const std::string base = "extras.giq.emitters";
  if (!a.is_array()) r.fail(base, "must be an array of emitter objects");
  for (size_t i = 0; i < a.size(); ++i) {
    const std::string w = base + "[" + std::to_string(i) + "]";
    const json& o = a[i];
    r.only_keys(o, w, {"name", "node", "rate", "lifetime", "speed", "spread_deg", "gravity", "drag", "size", "color", "emission", "strength",
                       "stages", "seed", "max_particles"});
    Emitter e;
    if (!o.contains("name") || !o["name"].is_string() || o["name"].get<std::string>().empty()) r.fail(w + ".name", "missing or not a non-empty string");
    e.name = o["name"].get<std::string>();
    for (const Emitter& other : out.emitters)
      if (other.name == e.name) r.fail(w + ".name", "duplicate emitter name \"" + e.name + "\"; emitter names must be unique");
    if (!o.contains("node") || !o["node"].is_string()) r.fail(w + ".node", "missing; expected the name of the node whose mesh emits");
    const std::string node = o["node"].get<std::string>();
    for (size_t n = 0; n < src.nodes.size(); ++n) {
      if (src.nodes[n].name != node) continue;
      if (e.node >= 0) r.fail(w + ".node", "\"" + node + "\" names more than one node; expected a unique node name");
      e.node = int(n);
    }
    if (e.node < 0) r.fail(w + ".node", "no node named \"" + node + "\"");
    if (src.nodes[size_t(e.node)].mesh < 0) r.fail(w + ".node", "node \"" + node + "\" has no mesh to emit from");
    // A number within [lo, hi] (open at lo when `open`).
    auto number = [&](const char* key, double fallback, double lo, double hi, bool open, const char* what) {
      if (!o.contains(key)) return fallback;
      const double x = r.number(o[key], w + "." + key);
      if (open ? !(x > lo && x <= hi) : !(x >= lo && x <= hi))
        r.fail(w + "." + key, "is " + o[key].dump() + "; expected " + what);
      return x;
    };
    if (!o.contains("rate")) r.fail(w + ".rate", "missing; expected particles per second");
    e.rate = number("rate", 0.0, 0.0, 1e7, true, "particles per second in (0, 1e7]");
    e.lifetime = number("lifetime", 1.0, 0.0, 1e4, true, "seconds in (0, 10000]");
    e.speed = number("speed", 0.0, 0.0, 1e6, false, "metres per second in [0, 1e6]");
    e.spread = number("spread_deg", 0.0, 0.0, 180.0, false, "degrees in [0, 180]") * std::numbers::pi / 180.0;
    e.drag = number("drag", 0.0, 0.0, 1e4, false, "a rate per second in [0, 10000]");
    e.size = number("size", 0.01, 0.0, 1e6, true, "metres in (0, 1e6]");
    e.stages = int(number("stages", 8.0, 1.0, 64.0, false, "an integer from 1 to 64"));
    if (o.contains("stages") && !o["stages"].is_number_integer()) r.fail(w + ".stages", "is " + o["stages"].dump() + "; expected an integer from 1 to 64");
    if (o.contains("gravity")) e.gravity = r.vec3(o["gravity"], w + ".gravity");
    if (glm::length(e.gravity) > 1e6) r.fail(w + ".gravity", "expected an acceleration below 1e6 m/s^2");
    if (o.contains("color")) {
      const glm::dvec3 c = r.vec3(o["color"], w + ".color");
      if (glm::any(glm::lessThan(c, glm::dvec3(0.0))) || glm::any(glm::greaterThan(c, glm::dvec3(1.0)))) r.fail(w + ".color", "expected a base colour in [0, 1]");
      e.color = glm::vec3(c);
    }
    if (o.contains("emission")) {
      const glm::dvec3 c = r.vec3(o["emission"], w + ".emission");
      if (glm::any(glm::lessThan(c, glm::dvec3(0.0))) || glm::any(glm::greaterThan(c, glm::dvec3(3e38)))) r.fail(w + ".emission", "expected a non-negative radiance");
      e.emission = glm::vec3(c);
    }
    if (o.contains("strength")) {
      const json& keys = o["strength"];
      if (!keys.is_array() || keys.empty()) r.fail(w + ".strength", "expected an array of [life fraction, strength] pairs");
      for (size_t k = 0; k < keys.size(); ++k) {
        const std::string kw = w + ".strength[" + std::to_string(k) + "]";
        if (!keys[k].is_array() || keys[k].size() != 2) r.fail(kw, "is " + keys[k].dump().substr(0, 80) + "; expected [life fraction, strength]");
        StrengthKey key{r.number(keys[k][0], kw + "[0]"), r.number(keys[k][1], kw + "[1]")};
        if (!(key.life >= 0.0 && key.life <= 1.0)) r.fail(kw + "[0]", "expected a fraction of the lifetime in [0, 1]");
        if (!e.strength.empty() && !(key.life > e.strength.back().life)) r.fail(kw + "[0]", "expected life fractions that increase");
        if (!(key.strength >= 0.0 && key.strength <= 1e30)) r.fail(kw + "[1]", "expected a strength >= 0");
        e.strength.push_back(key);
      }
    }
    if (o.contains("seed")) {
      if (!o["seed"].is_number_unsigned() || o["seed"].get<uint64_t>() > 0xffffffffull) r.fail(w + ".seed", "is " + o["seed"].dump() + "; expected an integer from 0 to 4294967295");
      e.seed = uint32_t(o["seed"].get<uint64_t>());
    }
    // The most alive at once: the ids born in any half-open window of `lifetime` seconds.
    const double most = std::floor(e.rate * e.lifetime) + 1.0;
    if (most > double(kMaxParticles))
      r.fail(w + ".rate", "rate x lifetime = " + std::to_string(e.rate * e.lifetime) + " particles alive at once; expected at most " + std::to_string(kMaxParticles));
    e.max_particles = uint32_t(most);
    if (o.contains("max_particles")) {
      const json& m = o["max_particles"];
      if (!m.is_number_unsigned() || m.get<uint64_t>() < uint64_t(most) || m.get<uint64_t>() > kMaxParticles)
        r.fail(w + ".max_particles", "is " + m.dump() + "; expected an integer from " + std::to_string(uint64_t(most)) + " (floor(rate x lifetime) + 1, the most alive at once) to " +
                                         std::to_string(kMaxParticles));
      e.max_particles = uint32_t(m.get<uint64_t>());
    }
    e.object_id = uint32_t(src.nodes.size() + 1 + i);
    out.emitters.push_back(std::move(e));
    out.emitter_fields.push_back(w);
  }
}

}  // namespace

Extras parse_extras(const Document& doc, const SceneSource& src) {
  Extras out;
  const Reader r{doc.file};
  bool frames_given = false;
  const json* giq = nullptr;
  if (auto e = doc.json.find("extras"); e != doc.json.end() && e->is_object()) {
    if (auto g = e->find("giq"); g != e->end()) giq = &*g;
  }
  if (!src.animations.empty()) out.sequence.animation = 0;  // the first clip plays unless told otherwise
  if (giq) {
    r.only_keys(*giq, "extras.giq", {"views", "sequence", "leak_regions", "environment", "emitters"});
    if (giq->contains("emitters")) parse_emitters(r, (*giq)["emitters"], src, out);
    if (giq->contains("views")) parse_views(r, (*giq)["views"], out);
    if (giq->contains("sequence")) parse_sequence(r, (*giq)["sequence"], src, out, frames_given);
    if (giq->contains("leak_regions")) parse_leak_regions(r, (*giq)["leak_regions"], src, out);
    if (giq->contains("environment")) {
      const json& env = (*giq)["environment"];
      r.only_keys(env, "extras.giq.environment", {"radiance"});
      if (!env.contains("radiance")) r.fail("extras.giq.environment.radiance", "missing; expected [r, g, b] radiance");
      const glm::dvec3 rad = r.vec3(env["radiance"], "extras.giq.environment.radiance");
      if (rad.x < 0 || rad.y < 0 || rad.z < 0) r.fail("extras.giq.environment.radiance", "expected non-negative radiance");
      out.environment = glm::vec3(rad);
    }
  }
  // Area light shapes on meshes: meshes[i].extras.giq.area_light.
  out.area_shapes.assign(src.meshes.size(), AreaShape::Mesh);
  if (auto meshes = doc.json.find("meshes"); meshes != doc.json.end() && meshes->is_array())
    for (size_t i = 0; i < meshes->size() && i < src.meshes.size(); ++i) {
      const json& m = (*meshes)[i];
      if (!m.is_object() || !m.contains("extras") || !m["extras"].is_object() || !m["extras"].contains("giq")) continue;
      const std::string base = "meshes[" + std::to_string(i) + "].extras.giq";
      r.only_keys(m["extras"]["giq"], base, {"area_light"});
      if (!m["extras"]["giq"].contains("area_light")) continue;
      const json& v = m["extras"]["giq"]["area_light"];
      // A declared shape is one of the names after "mesh" (which is what declaring none means).
      const auto first = std::begin(kAreaShapeNames) + 1, last = std::end(kAreaShapeNames);
      const auto it = std::find_if(first, last, [&](const char* n) { return v.is_string() && v.get<std::string>() == n; });
      if (it == last) {
        std::string expected;
        for (auto n = first; n != last; ++n) expected += std::string(expected.empty() ? "" : ", ") + "\"" + *n + "\"";
        r.fail(base + ".area_light", "is " + v.dump().substr(0, 80) + "; expected one of " + expected);
      }
      out.area_shapes[i] = AreaShape(it - std::begin(kAreaShapeNames));
    }
  // Without an explicit frame count the whole clip plays, both ends included.
  if (!frames_given && out.sequence.animation >= 0)
    out.sequence.frames = 1 + int(std::lround(std::min(src.animations[size_t(out.sequence.animation)].end * out.sequence.fps, 1e6)));
  check_windows(r, out.sequence);
  return out;
}

}  // namespace giq::scenes::gltf
