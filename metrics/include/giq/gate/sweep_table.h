#pragma once
// The rows of a speed/accuracy sweep: one per (technique, parameter setting), with the
// median GPU ms and every metric, the Pareto front marked on a chosen error metric. Written as
// sweep.csv (RFC 4180) and sweep.json, plotted as error-vs-ms SVG; `giq report` reads
// sweep.json back.

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace giq::gate {

struct SweepRow {
  std::string technique;
  std::vector<std::pair<std::string, double>> parameters;
  bool is_default = false;
  std::optional<double> gpu_ms;
  std::map<std::string, std::optional<double>> metrics;  // by gate metric name
  bool on_front = false;
  std::string error;  // why this setting has no numbers (render or score failed), else empty
};

// Marks on_front over rows that have gpu_ms and the error metric (see pareto.h).
void mark_front(std::vector<SweepRow>& rows, const std::string& error_metric);

std::string sweep_csv(const std::vector<SweepRow>& rows,
                      const std::vector<std::string>& metric_names);
nlohmann::json sweep_json(const std::vector<SweepRow>& rows, const std::string& error_metric,
                          const nlohmann::json& run);
// Throws InputError(file, ...) on a malformed sweep.json.
std::vector<SweepRow> sweep_rows(const nlohmann::json& sweep, const std::string& file);

// Error against GPU ms, one series per technique, defaults ringed, the front drawn.
std::string sweep_svg(const std::vector<SweepRow>& rows, const std::string& error_metric,
                      bool log_axes, const std::string& title);

// "name=value name=value", values with up to 10 significant digits.
std::string setting_label(const std::vector<std::pair<std::string, double>>& parameters);

}  // namespace giq::gate
