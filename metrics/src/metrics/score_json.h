#pragma once
// Internal: how metrics.json writes a value. Every metric is an object
//   {"value": v, "definition": "<name in docs/metrics.md>", "inputs": [...], "unit": "..."}
// JSON has no NaN or infinity: NaN ("undefined", e.g. 0/0) is null, infinities are the strings
// "inf" and "-inf" (psnr of identical images).

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace giq::metrics::detail {

inline nlohmann::json number(double v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

inline nlohmann::json metric(double value, const std::string& definition, const nlohmann::json& inputs,
                             const std::string& unit) {
  return {{"value", number(value)}, {"definition", definition}, {"inputs", inputs}, {"unit", unit}};
}

}  // namespace giq::metrics::detail
