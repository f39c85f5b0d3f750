#include "giq/gate/metric_lookup.h"

#include <cmath>
#include <limits>
#include <vector>

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

// Short names for the headline metrics of docs/metrics.md. leak prefers the regions the scene
// declares over the automatic dark region, as the scene author's regions are the ones meant.
std::vector<std::string> expand(const std::string& name) {
  if (name == "flip_mean") return {"flip.mean"};
  if (name == "flip_median") return {"flip.weighted_median"};
  if (name == "flip_max") return {"flip.max"};
  if (name == "leak") return {"leak.declared.leak", "leak.automatic.leak"};
  if (name == "leak_pixels") return {"leak.declared.leak_pixels", "leak.automatic.leak_pixels"};
  return {name};
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
      break;
    }
  }
  if (const json* d = walk(timings, "device.name"); d && d->is_string())
    t.device = *d;
  else if (const json* d2 = walk(timings, "device"); d2 && d2->is_string())
    t.device = *d2;
  return t;
}

}  // namespace giq::gate
