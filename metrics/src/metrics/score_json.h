#pragma once
// Internal: how metrics.json writes a value. Every metric is an object
//   {"value": v, "definition": "<name in docs/metrics.md>", "inputs": [...], "unit": "..."}
// JSON has no NaN or infinity: NaN ("undefined", e.g. 0/0) is null, infinities are the strings
// "inf" and "-inf" (psnr of identical images).

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace giq::metrics::detail {

inline nlohmann::json number(double v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

// `unit`: the catalogue's (unit_of(), giq/metrics/catalogue.h) for the metrics it lists.
inline nlohmann::json metric(double value, const std::string& definition, const nlohmann::json& inputs,
                             std::string_view unit) {
  return {{"value", number(value)}, {"definition", definition}, {"inputs", inputs}, {"unit", std::string(unit)}};
}

}  // namespace giq::metrics::detail
