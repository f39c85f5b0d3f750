#include "giq/realtime/technique.h"

#include <cmath>
#include <set>
#include <sstream>

#include "giq/base/error.h"
#include "giq/base/suggest.h"

namespace giq::realtime {

ParameterValues::ParameterValues(const std::vector<Parameter>& declared, const std::vector<std::string>& assignments) {
  for (const auto& p : declared) values_[p.name] = p.default_value;
  std::set<std::string> assigned;
  for (const auto& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("", "--param", "expected name=value, got '" + a + "'");
    const std::string name = a.substr(0, eq), text = a.substr(eq + 1);
    // Two values for one parameter: which one was meant cannot be known.
    if (!assigned.insert(name).second)
      throw InputError("", "--param " + name, "given more than once; expected one value per parameter");
    const Parameter* p = nullptr;
    for (const auto& d : declared)
      if (d.name == name) p = &d;
    if (!p) {
      std::string names;
      std::vector<std::string> known;
      for (const auto& d : declared) names += (names.empty() ? "" : ", ") + d.name, known.push_back(d.name);
      throw InputError("", "--param", "unknown parameter '" + name + "'; expected one of: " + (names.empty() ? "(none)" : names) +
                                          did_you_mean(name, known));
    }
    double v = 0.0;
    size_t used = 0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(v))
      throw InputError("", "--param " + name, "'" + text + "' is not a finite number");
    if (p->integer && v != std::floor(v))
      throw InputError("", "--param " + name, "'" + text + "' is not an integer");
    if (v < p->min_value || v > p->max_value) {
      std::ostringstream m;
      m << text << " is outside [" << p->min_value << ", " << p->max_value << "]";
      throw InputError("", "--param " + name, m.str());
    }
    values_[name] = v;
  }
}

double ParameterValues::get(std::string_view name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("undeclared parameter '" + std::string(name) + "'");
  return it->second;
}

nlohmann::json techniques_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& t : techniques()) {
    nlohmann::json params = nlohmann::json::array();
    for (const auto& p : t.parameters)
      params.push_back({{"name", p.name},
                        {"default", p.default_value},
                        {"min", p.min_value},
                        {"max", p.max_value},
                        {"integer", p.integer},
                        {"description", p.description}});
    list.push_back({{"name", t.name},
                    {"description", t.description},
                    {"parameters", params},
                    {"quality", {{"parameter", t.quality.parameter}, {"values", t.quality.values}}}});
  }
  return {{"version", 1}, {"techniques", list}};
}

const TechniqueInfo& find_technique(std::string_view name) {
  for (const auto& t : techniques())
    if (t.name == name) return t;
  std::string names;
  std::vector<std::string> known;
  for (const auto& t : techniques()) names += (names.empty() ? "" : ", ") + t.name, known.push_back(t.name);
  throw InputError("", "--technique", "unknown technique '" + std::string(name) + "'; expected one of: " + names +
                                          did_you_mean(name, known));
}

}  // namespace giq::realtime
