#include "sweep_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "giq/base/error.h"
#include "giq/base/json.h"

namespace giq::cli {
namespace {

double parse_number(const std::string& s, const std::string& field) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(v))
    throw InputError("", field, "'" + s + "' is not a number");
  return v;
}

}  // namespace

std::vector<TechniqueParameters> parse_technique_list(const std::string& listing) {
  const std::string source = "giq realtime --list --json";
  const nlohmann::json j = parse_json(listing, source);
  std::vector<TechniqueParameters> out;
  try {
    for (const auto& t : j.at("techniques")) {
      TechniqueParameters tp;
      tp.name = t.at("name").get<std::string>();
      for (const auto& p : t.at("parameters"))
        tp.parameters.push_back({p.at("name").get<std::string>(), p.at("default").get<double>(),
                                 p.at("min").get<double>(), p.at("max").get<double>(), p.at("integer").get<bool>()});
      tp.quality_parameter = t.at("quality").at("parameter").get<std::string>();
      tp.quality_values = t.at("quality").at("values").get<std::vector<double>>();
      out.push_back(std::move(tp));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source, "techniques", std::string("unexpected listing: ") + e.what());
  }
  return out;
}

std::string quality_axis(const TechniqueParameters& t) {
  std::string axis = t.name + "." + t.quality_parameter + "=";
  for (size_t i = 0; i < t.quality_values.size(); ++i) {
    char number[32];
    std::snprintf(number, sizeof number, "%.10g", t.quality_values[i]);
    axis += (i ? "," : "") + std::string(number);
  }
  return axis;
}

std::vector<Setting> plan_settings(const TechniqueParameters& t,
                                   const std::vector<std::string>& grid, int auto_steps,
                                   int max_settings) {
  std::map<std::string, std::vector<double>> axes;
  auto find = [&](const std::string& n) -> const ParameterInfo* {
    for (const auto& p : t.parameters)
      if (p.name == n) return &p;
    return nullptr;
  };
  for (const std::string& g : grid) {
    const size_t eq = g.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("", "--grid", "'" + g + "' is not param=a,b,c");
    std::string name = g.substr(0, eq);
    const size_t dot = name.find('.');
    if (dot != std::string::npos) {
      if (name.substr(0, dot) != t.name) continue;  // an axis of another technique
      name = name.substr(dot + 1);
    }
    const ParameterInfo* p = find(name);
    if (!p) {
      if (dot != std::string::npos)
        throw InputError(
            "", "--grid",
            "technique " + t.name + " has no parameter '" + name + "' (giq realtime --list)");
      continue;  // a bare axis applies to the techniques that declare it
    }
    std::vector<double> values;
    std::stringstream ss(g.substr(eq + 1));
    for (std::string v; std::getline(ss, v, ',');) {
      const double x = parse_number(v, "--grid " + name);
      if (x < p->min_value || x > p->max_value)
        throw InputError("", "--grid",
                         name + "=" + v + " is outside its declared range [" +
                             std::to_string(p->min_value) + ", " + std::to_string(p->max_value) +
                             "]");
      values.push_back(p->integer ? std::round(x) : x);
    }
    if (values.empty()) throw InputError("", "--grid", "'" + g + "' lists no values");
    axes[name] = values;
  }
  if (auto_steps > 0)
    for (const ParameterInfo& p : t.parameters) {
      if (axes.count(p.name) || p.max_value <= p.min_value) continue;
      std::vector<double> v;
      const bool geometric = p.min_value > 0.0 && p.max_value / p.min_value >= 10.0;
      for (int k = 0; k < auto_steps; ++k) {
        const double f = auto_steps == 1 ? 0.5 : double(k) / (auto_steps - 1);
        double x = geometric ? p.min_value * std::pow(p.max_value / p.min_value, f)
                             : p.min_value + f * (p.max_value - p.min_value);
        if (p.integer) x = std::round(x);
        if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
      }
      axes[p.name] = v;
    }
  std::vector<Setting> out = {{}};
  for (const auto& [name, values] : axes) {
    std::vector<Setting> next;
    for (const Setting& s : out)
      for (double v : values) {
        Setting n = s;
        n.emplace_back(name, v);
        next.push_back(n);
      }
    out = next;
    if (int(out.size()) > max_settings)
      throw InputError("", "--grid",
                       "technique " + t.name + " would run " + std::to_string(out.size()) +
                           "+ settings, more than --max-settings " + std::to_string(max_settings));
  }
  // The all-defaults setting, over the same parameters, so every technique shows its default.
  Setting defaults;
  for (const auto& [name, values] : axes) defaults.emplace_back(name, find(name)->default_value);
  if (std::find(out.begin(), out.end(), defaults) == out.end()) out.push_back(defaults);
  return out;
}

void check_grid(const std::vector<const TechniqueParameters*>& swept, const std::vector<std::string>& grid) {
  std::string names;
  for (const TechniqueParameters* t : swept) names += (names.empty() ? "" : ", ") + t->name;
  for (const std::string& g : grid) {
    const std::string name = g.substr(0, g.find('='));
    const size_t dot = name.find('.');
    const std::string technique = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string parameter = dot == std::string::npos ? name : name.substr(dot + 1);
    bool reached = false;
    for (const TechniqueParameters* t : swept) {
      if (!technique.empty() && t->name != technique) continue;
      for (const ParameterInfo& p : t->parameters) reached |= p.name == parameter;
    }
    if (reached) continue;
    const bool technique_swept = std::any_of(swept.begin(), swept.end(), [&](auto* t) { return t->name == technique; });
    if (!technique.empty() && !technique_swept)
      throw InputError("", "--grid", "'" + g + "' varies technique " + technique + ", which is not swept (--technique: " +
                                         names + ")");
    throw InputError("", "--grid", "'" + g + "': no swept technique (" + names + ") declares the parameter '" +
                                       parameter + "' (giq realtime --list)");
  }
}

bool is_default(const TechniqueParameters& t, const Setting& s) {
  for (const auto& [name, v] : s)
    for (const auto& p : t.parameters)
      if (p.name == name && p.default_value != v) return false;
  return true;
}

}  // namespace giq::cli
