#include "giq/gate/sweep_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "giq/base/error.h"
#include "giq/gate/pareto.h"
#include "giq/gate/plot.h"

namespace giq::gate {
namespace {

using nlohmann::json;

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

// RFC 4180: a field holding a comma, quote or line break is quoted, quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

json opt(const std::optional<double>& v) {
  return v && std::isfinite(*v) ? json(*v) : json(nullptr);
}

}  // namespace

std::string setting_label(const std::vector<std::pair<std::string, double>>& parameters) {
  std::string s;
  for (const auto& [k, v] : parameters) s += (s.empty() ? "" : " ") + k + "=" + num(v);
  return s;
}

void mark_front(std::vector<SweepRow>& rows, const std::string& error_metric) {
  std::vector<CostError> pts;
  for (const SweepRow& r : rows) {
    const auto it = r.metrics.find(error_metric);
    const double nan = std::nan("");
    pts.push_back(
        {r.gpu_ms.value_or(nan), it != r.metrics.end() && it->second ? *it->second : nan});
  }
  const std::vector<bool> on = pareto_front(pts);
  for (size_t i = 0; i < rows.size(); ++i) rows[i].on_front = on[i];
}

std::string sweep_csv(const std::vector<SweepRow>& rows,
                      const std::vector<std::string>& metric_names) {
  std::ostringstream s;
  s << "technique,parameters,default,gpu_ms";
  for (const auto& m : metric_names) s << ',' << csv_field(m);
  s << ",pareto_front,error\n";
  for (const SweepRow& r : rows) {
    s << csv_field(r.technique) << ',' << csv_field(setting_label(r.parameters)) << ','
      << (r.is_default ? 1 : 0) << ',' << (r.gpu_ms ? num(*r.gpu_ms) : "");
    for (const auto& m : metric_names) {
      const auto it = r.metrics.find(m);
      s << ',' << (it != r.metrics.end() && it->second ? num(*it->second) : "");
    }
    s << ',' << (r.on_front ? 1 : 0) << ',' << csv_field(r.error) << '\n';
  }
  return s.str();
}

json sweep_json(const std::vector<SweepRow>& rows, const std::string& error_metric,
                const json& run) {
  json out = {
      {"version", 1}, {"error_metric", error_metric}, {"run", run}, {"rows", json::array()}};
  for (const SweepRow& r : rows) {
    json params = json::object(), metrics = json::object();
    for (const auto& [k, v] : r.parameters) params[k] = v;
    for (const auto& [k, v] : r.metrics) metrics[k] = opt(v);
    json row = {{"technique", r.technique}, {"parameters", params}, {"default", r.is_default},
                {"gpu_ms", opt(r.gpu_ms)},  {"metrics", metrics},   {"pareto_front", r.on_front}};
    if (!r.error.empty()) row["error"] = r.error;
    out["rows"].push_back(row);
  }
  return out;
}

std::vector<SweepRow> sweep_rows(const json& sweep, const std::string& file) {
  std::vector<SweepRow> rows;
  try {
    for (const json& j : sweep.at("rows")) {
      SweepRow r;
      r.technique = j.at("technique").get<std::string>();
      for (const auto& [k, v] : j.at("parameters").items())
        r.parameters.emplace_back(k, v.get<double>());
      r.is_default = j.value("default", false);
      if (j.contains("gpu_ms") && j["gpu_ms"].is_number()) r.gpu_ms = j["gpu_ms"].get<double>();
      for (const auto& [k, v] : j.at("metrics").items())
        r.metrics[k] = v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt;
      r.on_front = j.value("pareto_front", false);
      r.error = j.value("error", "");
      rows.push_back(std::move(r));
    }
  } catch (const json::exception& e) {
    throw InputError(file, "rows", std::string("not a giq sweep.json: ") + e.what());
  }
  return rows;
}

std::string sweep_svg(const std::vector<SweepRow>& rows, const std::string& error_metric,
                      bool log_axes, const std::string& title) {
  std::vector<PlotSeries> series;
  PlotOptions o;
  o.title = title;
  o.x_label = "GPU ms per frame (median)";
  o.y_label = error_metric;
  o.log_x = o.log_y = log_axes;
  for (const SweepRow& r : rows) {
    const auto it = r.metrics.find(error_metric);
    if (!r.gpu_ms || it == r.metrics.end() || !it->second) continue;
    auto s = std::find_if(series.begin(), series.end(),
                          [&](const PlotSeries& x) { return x.name == r.technique; });
    if (s == series.end()) {
      series.push_back({r.technique, {}, false});
      s = series.end() - 1;
    }
    s->points.push_back({*r.gpu_ms, *it->second, r.is_default, setting_label(r.parameters)});
    if (r.on_front) o.front.emplace_back(*r.gpu_ms, *it->second);
  }
  return svg_plot(series, o);
}

}  // namespace giq::gate
