#pragma once
// What `giq sweep` runs: the techniques' declared parameters and quality knobs (read from
// `giq realtime --list --json`, so a new technique or parameter needs no change here) and the
// settings to try, from --grid axes, the quality knobs (--quality) or, with --auto, from each
// parameter's declared range.

#include <string>
#include <utility>
#include <vector>

namespace giq::cli {

struct ParameterInfo {
  std::string name;
  double default_value = 0.0, min_value = 0.0, max_value = 0.0;
  bool integer = false;
};

struct TechniqueParameters {
  std::string name;
  std::vector<ParameterInfo> parameters;
  std::string quality_parameter;  // the knob a speed-for-accuracy sweep varies
  std::vector<double> quality_values;
};

// Reads the listing `giq realtime --list --json` prints (realtime::techniques_json()). Throws
// InputError when it is not that JSON.
std::vector<TechniqueParameters> parse_technique_list(const std::string& listing);
// The technique's quality knob as a --grid axis, "technique.param=a,b,c".
std::string quality_axis(const TechniqueParameters& technique);

using Setting = std::vector<std::pair<std::string, double>>;  // sorted by name

// Grid axes "param=a,b,c" or "technique.param=a,b,c"; with `auto_steps` > 0 every declared
// parameter without a grid axis gets that many values across its range (geometric when the
// range is positive and spans a factor of 10 or more, else evenly spaced; integers rounded).
// The cartesian product of the axes, plus the all-defaults setting. Throws InputError for an
// axis naming no declared parameter, a value outside its range, or more than `max_settings`.
std::vector<Setting> plan_settings(const TechniqueParameters& technique,
                                   const std::vector<std::string>& grid, int auto_steps,
                                   int max_settings);

// Every --grid axis must reach one of the swept techniques: a bare "param=..." one that
// declares it, a "technique.param=..." a technique that is swept. Throws InputError naming the
// axis otherwise (an axis that reaches nothing would leave the sweep silently without it).
void check_grid(const std::vector<const TechniqueParameters*>& swept, const std::vector<std::string>& grid);

bool is_default(const TechniqueParameters& technique, const Setting& s);

}  // namespace giq::cli
