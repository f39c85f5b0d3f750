#include "giq/gate/config.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "giq/base/error.h"
#include "giq/base/json.h"
#include "giq/base/frames.h"
#include "giq/gate/metric_lookup.h"
#include "giq/metrics/display.h"

namespace giq::gate {
namespace {

namespace fs = std::filesystem;
// ordered_json keeps the file's order, so cases and bounds are reported in the order written.
using json = nlohmann::ordered_json;

const std::set<std::string> kCaseKeys = {"name",       "scene",  "view",  "camera", "technique",  "test",
                                         "parameters", "frames", "layer", "resolution",
                                         "golden",     "display", "timing", "bounds"};

class Parser {
 public:
  explicit Parser(fs::path file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(file_.string(), field, message);
  }

  static std::string show(const json& v) {
    std::string s = v.dump();
    return s.size() > 60 ? s.substr(0, 57) + "..." : s;
  }

  void only_keys(const json& obj, const std::set<std::string>& keys,
                 const std::string& field) const {
    for (const auto& [k, v] : obj.items())
      if (!keys.count(k)) {
        std::string list;
        for (const auto& key : keys) list += (list.empty() ? "" : ", ") + key;
        fail(field.empty() ? k : field + "." + k, "unknown key; expected one of " + list);
      }
  }

  const json& object(const json& v, const std::string& field) const {
    if (!v.is_object()) fail(field, show(v) + " is not an object");
    return v;
  }

  std::string string(const json& v, const std::string& field) const {
    if (!v.is_string() || v.get<std::string>().empty())
      fail(field, show(v) + " is not a non-empty string");
    return v.get<std::string>();
  }

  double number(const json& v, const std::string& field) const {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      fail(field, show(v) + " is not a finite number");
    return v.get<double>();
  }

  int integer(const json& v, const std::string& field, int lo, int hi) const {
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
      fail(field, show(v) + " is not an integer in [" + std::to_string(lo) + ", " +
                      std::to_string(hi) + "]");
    return int(v.get<long long>());
  }

  // frames: 7, "7", or "A:B" (inclusive, A <= B).
  std::pair<int, int> frames(const json& v, const std::string& field) const {
    if (v.is_number_integer()) {
      const int f = integer(v, field, 0, 1 << 24);
      return {f, f};
    }
    if (v.is_string()) {
      const std::string s = v.get<std::string>();
      if (const auto range = parse_frame_range(s)) return *range;
      if (!s.empty() && s.size() <= 8 && s.find_first_not_of("0123456789") == std::string::npos) {
        const int f = std::stoi(s);
        return {f, f};
      }
    }
    fail(field, show(v) + " is not a frame number or a range \"A:B\" with 0 <= A <= B");
  }

  void apply(Case& c, const json& obj, const std::string& at) const {
    for (const auto& [key, v] : obj.items()) {
      const std::string f = at + "." + key;
      if (key == "name") {
        c.name = string(v, f);
      } else if (key == "scene") {
        const fs::path p = string(v, f);
        c.scene = p.is_absolute() ? p : (file_.parent_path() / p).lexically_normal();
      } else if (key == "view") {
        c.view = v.is_number_integer() ? std::to_string(integer(v, f, 0, 1 << 20)) : string(v, f);
      } else if (key == "camera") {
        c.camera = string(v, f);
        if (c.camera.find_first_not_of(" \t") == std::string::npos)
          fail(f, "is empty; expected \"eye=x,y,z target=x,y,z fov=deg\" as giq's --camera takes it");
      } else if (key == "technique") {
        c.technique = string(v, f);
      } else if (key == "test") {
        // An image file, or a frame pattern such as shots/frame_%04d.exr, from outside giq.
        const fs::path p = string(v, f);
        c.test = p.is_absolute() ? p : (file_.parent_path() / p).lexically_normal();
      } else if (key == "parameters") {
        c.parameters.clear();
        for (const auto& [pk, pv] : object(v, f).items())
          c.parameters.emplace_back(pk, number(pv, f + "." + pk));
      } else if (key == "frames") {
        std::tie(c.first_frame, c.last_frame) = frames(v, f);
      } else if (key == "layer") {
        c.layer = string(v, f);
      } else if (key == "resolution") {
        if (!v.is_array() || v.size() != 2) fail(f, show(v) + " is not [width, height]");
        c.width = integer(v[0], f + "[0]", 1, 16384);
        c.height = integer(v[1], f + "[1]", 1, 16384);
      } else if (key == "golden") {
        golden(c.golden, object(v, f), f);
      } else if (key == "display") {
        only_keys(object(v, f), {"tonemap", "exposure", "test_encoding"}, f);
        if (v.contains("tonemap")) {
          c.display.tonemap = string(v["tonemap"], f + ".tonemap");
          // The names giq score knows (display.h's list; the gate library does not link the
          // metrics library, which giq score runs as a separate process).
          bool known = false;
          for (std::string_view names = metrics::kToneCurveNames; !names.empty();) {
            const size_t comma = names.find(", ");
            known |= names.substr(0, comma) == c.display.tonemap;
            names = comma == std::string_view::npos ? std::string_view() : names.substr(comma + 2);
          }
          if (!known)
            fail(f + ".tonemap", "'" + c.display.tonemap + "' is not a tone curve; expected one of " +
                                     std::string(metrics::kToneCurveNames));
        }
        if (v.contains("exposure")) c.display.exposure = number(v["exposure"], f + ".exposure");
        if (v.contains("test_encoding")) {
          c.display.test_encoding = string(v["test_encoding"], f + ".test_encoding");
          if (c.display.test_encoding != "srgb" && c.display.test_encoding != "linear")
            fail(f + ".test_encoding", "'" + c.display.test_encoding + "'; expected srgb or linear");
        }
      } else if (key == "timing") {
        only_keys(object(v, f), {"warmup", "frames"}, f);
        if (v.contains("warmup")) c.timing.warmup = integer(v["warmup"], f + ".warmup", 0, 100000);
        if (v.contains("frames")) c.timing.frames = integer(v["frames"], f + ".frames", 1, 100000);
      } else if (key == "bounds") {
        for (const auto& [metric, b] : object(v, f).items()) {
          Bound bound = this->bound(metric, b, f + "." + metric);
          auto it = std::find_if(c.bounds.begin(), c.bounds.end(),
                                 [&](const Bound& x) { return x.metric == bound.metric; });
          if (it != c.bounds.end())
            *it = bound;
          else
            c.bounds.push_back(bound);
        }
      } else {
        std::string list;
        for (const auto& k : kCaseKeys) list += (list.empty() ? "" : ", ") + k;
        fail(f, "unknown key; expected one of " + list);
      }
    }
  }

  void golden(GoldenSpec& g, const json& v, const std::string& f) const {
    only_keys(v, {"spp", "rel_error", "seed", "half", "still", "sampler"}, f);
    if (v.contains("spp") || v.contains("rel_error")) g.spp.reset(), g.rel_error.reset();
    if (v.contains("spp")) g.spp = uint32_t(integer(v["spp"], f + ".spp", 1, 1 << 30));
    if (v.contains("rel_error")) {
      const double e = number(v["rel_error"], f + ".rel_error");
      if (!(e > 0.0 && e < 1.0))
        fail(f + ".rel_error", show(v["rel_error"]) + " is not a fraction in (0, 1)");
      g.rel_error = e;
    }
    if (g.spp && g.rel_error) fail(f, "give spp or rel_error, not both");
    if (v.contains("seed")) g.seed = uint64_t(integer(v["seed"], f + ".seed", 0, 2147483647));
    if (v.contains("half")) g.half = boolean(v["half"], f + ".half");
    if (v.contains("still")) g.still = boolean(v["still"], f + ".still");
    if (v.contains("sampler")) {
      g.sampler = string(v["sampler"], f + ".sampler");
      if (g.sampler != "independent" && g.sampler != "sobol")
        fail(f + ".sampler", show(v["sampler"]) + " is not \"independent\" or \"sobol\"");
    }
  }

  bool boolean(const json& v, const std::string& field) const {
    if (!v.is_boolean()) fail(field, show(v) + " is not true or false");
    return v.get<bool>();
  }

  Bound bound(const std::string& metric, const json& v, const std::string& f) const {
    if (const std::string why = unknown_metric(metric); !why.empty()) fail(f, why);
    Bound b;
    b.metric = metric;
    b.better = default_direction(metric);
    if (v.is_number()) {  // "flip_mean": 0.08 is short for {"fail": 0.08}
      b.fail = number(v, f);
    } else {
      only_keys(object(v, f), {"fail", "warn", "better", "device"}, f);
      if (v.contains("fail")) b.fail = number(v["fail"], f + ".fail");
      if (v.contains("warn")) b.warn = number(v["warn"], f + ".warn");
      if (v.contains("device")) b.device = string(v["device"], f + ".device");
      if (v.contains("better")) {
        const std::string d = v["better"].is_string() ? v["better"].get<std::string>() : "";
        if (d == "lower")
          b.better = Better::Lower;
        else if (d == "higher")
          b.better = Better::Higher;
        else
          fail(f + ".better", show(v["better"]) + " is not \"lower\" or \"higher\"");
      }
    }
    if (!b.fail && !b.warn) fail(f, "a bound needs a fail level, a warn level or both");
    if (b.fail && b.warn) {
      const bool ordered = b.better == Better::Lower ? *b.warn <= *b.fail : *b.warn >= *b.fail;
      if (!ordered)
        fail(f + ".warn", std::to_string(*b.warn) + " is beyond the fail level " +
                              std::to_string(*b.fail) +
                              "; the warn level must be stricter than the fail level");
    }
    if (metric == "gpu_ms" && b.device.empty())
      fail(f + ".device",
           "a gpu_ms bound must name the device it was measured on (part of timings.json "
           "device.name)");
    return b;
  }

  void finish(Case& c, const std::string& at) const {
    if (c.name.empty()) fail(at + ".name", "missing; every case needs a unique name");
    if (c.scene.empty()) fail(at + ".scene", "missing; expected a .gltf/.glb path");
    if (c.technique.empty() == c.test.empty())
      fail(at + (c.technique.empty() ? ".technique" : ".test"),
           c.technique.empty() ? "missing; expected a technique name (giq realtime --list) or test, an image file or pattern"
                               : "a case has a technique or test images, not both");
    if (!c.test.empty()) {
      if (!c.parameters.empty()) fail(at + ".parameters", "technique parameters need a technique; this case scores test images");
      if (c.needs_timing()) fail(at + ".bounds.gpu_ms", "a frame time needs a technique to render; this case scores test images");
      const bool pattern = c.test.string().find('%') != std::string::npos;
      if (pattern != c.sequence())
        fail(at + ".test", pattern ? "a frame pattern needs a frame range \"A:B\" (frames)"
                                   : "a frame range needs a frame pattern such as shot_%04d.exr");
    }
    if (!c.camera.empty() && !c.view.empty()) fail(at + ".camera", "a case has a view or a camera, not both");
    if (!c.camera.empty()) c.view = "camera";  // the view --camera adds
    if (c.view.empty()) c.view = "0";
    if (!c.golden.spp && !c.golden.rel_error) c.golden.spp = 256;
    if (c.bounds.empty())
      fail(at + ".bounds", "missing or empty; a case must bound at least one metric");
    std::sort(c.parameters.begin(), c.parameters.end());
  }

 private:
  fs::path file_;
};

}  // namespace

bool Case::needs_timing() const {
  return std::any_of(bounds.begin(), bounds.end(),
                     [](const Bound& b) { return b.metric == "gpu_ms"; });
}

Better default_direction(const std::string& metric) { return metrics::better_direction(metric); }

Config parse_config(const std::string& text, const fs::path& file) {
  Parser p(file);
  const json root = parse_ordered_json(text, file.string());
  p.object(root, "(top level)");
  p.only_keys(root, {"version", "golden_dir", "defaults", "cases"}, "");
  if (!root.contains("version") || root["version"] != 1)
    p.fail("version",
           (root.contains("version") ? Parser::show(root["version"]) : std::string("missing")) +
               "; expected 1");
  Config config;
  config.file = file;
  config.golden_dir = file.parent_path() / "refs";
  if (root.contains("golden_dir")) {
    const fs::path g = p.string(root["golden_dir"], "golden_dir");
    config.golden_dir = g.is_absolute() ? g : (file.parent_path() / g).lexically_normal();
  }
  Case defaults;
  if (root.contains("defaults")) {
    const json& d = p.object(root["defaults"], "defaults");
    if (d.contains("name"))
      p.fail("defaults.name", "a name belongs to one case, not to the defaults");
    p.apply(defaults, d, "defaults");
  }
  if (!root.contains("cases") || !root["cases"].is_array() || root["cases"].empty())
    p.fail("cases", "missing or empty; expected an array of cases");
  std::set<std::string> names;
  for (size_t i = 0; i < root["cases"].size(); ++i) {
    const std::string at = "cases[" + std::to_string(i) + "]";
    Case c = defaults;
    p.apply(c, p.object(root["cases"][i], at), at);
    p.finish(c, at);
    if (!names.insert(c.name).second)
      p.fail(at + ".name", "'" + c.name + "' is used by an earlier case; names must be unique");
    // A folder name of at most 255 bytes, with room for the suffixes the gate adds.
    if (c.name.size() > 128)
      p.fail(at + ".name", std::to_string(c.name.size()) + " characters; expected at most 128 (it names folders)");
    for (char ch : c.name)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.'))
        p.fail(
            at + ".name",
            "'" + c.name + "' may only hold letters, digits, '-', '_' and '.' (it names folders)");
    config.cases.push_back(std::move(c));
  }
  return config;
}

Config read_config(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot open the gate config");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_config(ss.str(), file);
}

bool glob_match(const std::string& pattern, const std::string& text) {
  // Iterative wildcard matching with backtracking to the last '*' (linear in practice).
  size_t p = 0, t = 0, star = std::string::npos, mark = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p, ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      star = p++, mark = t;
    } else if (star != std::string::npos) {
      p = star + 1, t = ++mark;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

std::vector<const Case*> select_cases(const Config& config, const std::string& pattern) {
  std::vector<const Case*> out;
  for (const Case& c : config.cases)
    if (pattern.empty() || glob_match(pattern, c.name)) out.push_back(&c);
  return out;
}

std::vector<std::string> parameter_arguments(const Case& c) {
  std::vector<std::string> out;
  for (const auto& [name, value] : c.parameters) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", value);
    out.push_back(name + "=" + buf);
  }
  return out;
}

}  // namespace giq::gate
