#include "giq/gate/metric_lookup.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "giq/base/error.h"
#include "giq/base/suggest.h"
#include "giq/base/json.h"
#include "giq/metrics/catalogue.h"

namespace giq::gate {
namespace {

using nlohmann::json;

const json* walk(const json& root, const std::string& dotted) {
  const json* j = &root;
  size_t start = 0;
  while (start <= dotted.size()) {
    const size_t dot = dotted.find('.', start);
    const std::string key =
        dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start);
    if (!j->is_object() || !j->contains(key)) return nullptr;
    j = &(*j)[key];
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return j;
}

// A number, "inf"/"-inf" (how metrics.json writes infinities) or null.
std::optional<MetricValue> as_value(const json& j, const std::string& path) {
  MetricValue m;
  m.path = path;
  const json* v = &j;
  if (j.is_object()) {
    if (!j.contains("value")) {
      if (j.contains("value_frames"))
        v = &j["value_frames"];
      else
        return std::nullopt;
    } else {
      v = &j["value"];
    }
    m.unresolved = j.value("unresolved", false);
    if (j.contains("note") && j["note"].is_string())
      m.note = j["note"];
    else if (j.contains("reason") && j["reason"].is_string())
      m.note = j["reason"];
  }
  if (v->is_number())
    m.value = v->get<double>();
  else if (v->is_string() && *v == "inf")
    m.value = std::numeric_limits<double>::infinity();
  else if (v->is_string() && *v == "-inf")
    m.value = -std::numeric_limits<double>::infinity();
  else if (!v->is_null())
    return std::nullopt;
  return m;
}

// A catalogue name's paths in metrics.json (leak prefers the regions the scene declares over
// the automatic dark region, as the scene author's regions are the ones meant); any other name
// is a dotted path itself.
std::vector<std::string> expand(const std::string& name) {
  const metrics::MetricInfo* m = metrics::find_metric_info(name);
  if (!m || m->scope == metrics::Scope::Timing) return {name};
  std::vector<std::string> paths;
  for (std::string_view p : m->paths)
    if (!p.empty()) paths.emplace_back(p);
  return paths;
}

}  // namespace

std::optional<MetricValue> find_metric(const json& metrics, const std::string& name) {
  for (const std::string& rel : expand(name))
    for (const char* section : {"metrics", "sequence", "last_frame.metrics"}) {
      const json* s = walk(metrics, section);
      if (!s) continue;
      if (const json* j = walk(*s, rel))
        if (auto v = as_value(*j, std::string(section) + "." + rel)) return v;
    }
  if (const json* j = walk(metrics, name)) return as_value(*j, name);
  return std::nullopt;
}

FrameTime frame_time(const json& timings) {
  FrameTime t;
  for (const char* key : {"frame_gpu_ms", "frame_ms"}) {
    const json* m = walk(timings, std::string(key) + ".median");
    if (m && m->is_number()) {
      t.gpu_ms = m->get<double>();
      t.key = std::string(key) + ".median";
      break;
    }
  }
  if (const json* d = walk(timings, "device.name"); d && d->is_string())
    t.device = *d;
  else if (const json* d2 = walk(timings, "device"); d2 && d2->is_string())
    t.device = *d2;
  return t;
}

FrameTime read_timings(const std::filesystem::path& file) {
  const FrameTime t = frame_time(read_json(file));
  if (!t.gpu_ms)
    throw InputError(file.string(), "frame_gpu_ms.median",
                     "missing; expected {\"frame_gpu_ms\": {\"median\": <ms>}} or {\"frame_ms\": {\"median\": <ms>}}");
  if (!std::isfinite(*t.gpu_ms) || *t.gpu_ms <= 0.0)
    throw InputError(file.string(), t.key, std::to_string(*t.gpu_ms) + " ms; expected a positive frame time");
  return t;
}

std::string unknown_metric(const std::string& name) {
  if (name.find('.') != std::string::npos || metrics::find_metric_info(name)) return "";
  std::string known;
  std::vector<std::string> names;
  for (const auto& m : metrics::kMetricCatalogue) known += (known.empty() ? "" : ", ") + std::string(m.name), names.emplace_back(m.name);
  return "'" + name + "' is not a metric; expected one of " + known + ", or a dotted path in metrics.json (docs/metrics.md)" +
         did_you_mean(name, names);
}

}  // namespace giq::gate
