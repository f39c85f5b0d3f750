// `giq gate calibrate`: writes golden/gate.json, every registered technique (`giq realtime
// --list --json`) on every case template of golden/gate-plan.json, with bounds set from
// measured values plus the plan's margin.
//
//   giq gate calibrate                    cases and bounds for every technique (renders the
//                                         missing goldens first)
//   giq gate calibrate --technique rsm    measure only rsm's cases; keep the others' bounds
//   giq gate calibrate --scene dynamic    measure only the cases of scenes/dynamic.gltf
//   giq gate calibrate --check            exit 1 when gate.json lacks a case the plan and the
//                                         registered techniques call for (a CI test runs it)
//
// The gate runs once per entry of the plan's "runs": lavapipe with different thread counts,
// and for techniques that declare the parameter, other values of their random `seed` (a
// different driver's rounding sends a stochastic technique's paths elsewhere, which moves its
// error the way another seed does). The measured value of a bound is the largest over the
// runs, and
//
//   fail = value x (1 + margin.fail) + floor,   warn = value x (1 + margin.warn) + floor / 2
//
// with the floor per metric from the plan ("noise": the golden's own noise floor of the
// metric, read from the case's metrics.json). The runs' spread is printed and kept with every
// value in golden/calibration.json. A value the golden cannot resolve (flagged "unresolved")
// stops the calibration: the golden needs more samples. golden/README.md states and justifies
// the margin.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "command.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/frames.h"
#include "giq/base/json.h"
#include "giq/scenes/scene.h"
#include "subprocess.h"
#include "technique_listing.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ordered = nlohmann::ordered_json;

constexpr double kHuge = 1e300;  // the bound of a measuring run: reports every value, fails none

struct CalibrateArgs {
  std::string plan = "golden/gate-plan.json";
  std::string config = "golden/gate.json";
  std::string out = "build/gate-calibrate";
  std::string device = "llvmpipe";  // as tools/test runs the gate
  std::string giq;
  std::vector<std::string> techniques;
  std::vector<std::string> scenes;  // scene file stems
  int jobs = int(std::max(1L, sysconf(_SC_NPROCESSORS_ONLN)));
  bool check = false;
};

void write_json_file(const fs::path& p, const ordered& j) { write_file_atomically(p, j.dump(2) + "\n"); }

template <class Json>
const Json* walk(const Json& root, const std::string& dotted) {
  const Json* j = &root;
  for (size_t start = 0; start <= dotted.size();) {
    const size_t dot = std::min(dotted.find('.', start), dotted.size());
    const std::string key = dotted.substr(start, dot - start);
    if (!j->is_object() || !j->contains(key)) return nullptr;
    j = &(*j)[key];
    start = dot + 1;
  }
  return j;
}

// {technique: its parameter names}, in registration order.
std::vector<std::pair<std::string, std::set<std::string>>> registered(const fs::path& giq, const fs::path& out) {
  std::vector<std::pair<std::string, std::set<std::string>>> names;
  for (const TechniqueParameters& t : list_techniques(giq, out / "techniques.json")) {
    std::set<std::string> parameters;
    for (const ParameterInfo& p : t.parameters) parameters.insert(p.name);
    names.emplace_back(t.name, parameters);
  }
  return names;
}

struct PlannedCase {
  ordered json;  // the case as gate.json holds it, without bounds
  std::vector<std::string> metrics;
  std::string name() const { return json["name"].get<std::string>(); }
  std::string technique() const { return json["technique"].get<std::string>(); }
  std::string scene() const { return fs::path(json["scene"].get<std::string>()).stem().string(); }
};

// A case template's frames as gate.json holds them: as written (N or "A:B"), or for "flicker"
// and "lag" the window the scene declares for that metric (scenes::Sequence), so that the gate
// measures over the same frames as every other command. `sequence`: the scene's, loaded by the
// first template that names a window.
ordered case_frames(const fs::path& plan_path, const ordered& scene, const ordered& frames, const std::string& field,
                    std::optional<scenes::Sequence>& sequence) {
  if (!frames.is_string() || (frames != "flicker" && frames != "lag")) return frames;
  const std::string text = frames.get<std::string>();
  const fs::path file = plan_path.parent_path() / scene.at("scene").get<std::string>();
  if (!sequence) sequence = scenes::load(file).sequence;
  const auto& w = text == "flicker" ? sequence->flicker_frames : sequence->lag_frames;
  if (!w) throw InputError(plan_path.string(), field, "\"" + text + "\", but " + file.string() + " declares no extras.giq.sequence." + text + "_frames");
  return frame_range(w->first, w->second);
}

// The cases the plan asks for, in a stable order: scene by scene, technique by technique.
std::vector<PlannedCase> planned_cases(const fs::path& plan_path, const ordered& plan, const std::vector<std::string>& techniques) {
  std::vector<PlannedCase> cases;
  const ordered no_indirect = plan.value("no_indirect_light", ordered::array());
  for (const auto& scene : plan.at("scenes")) {
    const std::string stem = fs::path(scene.at("scene").get<std::string>()).stem().string();
    std::vector<ordered> frames;
    std::optional<scenes::Sequence> sequence;
    for (size_t i = 0; i < scene.at("cases").size(); ++i) {
      const ordered& t = scene["cases"][i];
      const std::string field = "scenes[" + stem + "].cases[" + std::to_string(i) + "].frames";
      frames.push_back(t.contains("frames") ? case_frames(plan_path, scene, t["frames"], field, sequence) : ordered());
    }
    for (const std::string& tech : techniques)
      for (size_t i = 0; i < scene.at("cases").size(); ++i) {
        const ordered& t = scene["cases"][i];
        if (t.value("needs_indirect", false) &&
            std::find(no_indirect.begin(), no_indirect.end(), tech) != no_indirect.end())
          continue;
        std::string name = stem + "-" + tech;
        if (!t.value("suffix", std::string()).empty()) name += "-" + t["suffix"].get<std::string>();
        PlannedCase c;
        c.json["name"] = name;
        c.json["scene"] = scene["scene"];
        c.json["technique"] = tech;
        if (scene.contains("view")) c.json["view"] = scene["view"];
        // Parameters in name order (a json object's order), as the gate writes them back.
        if (const ordered* params = walk(plan, "technique_parameters." + tech)) c.json["parameters"] = json(*params);
        if (!frames[i].is_null()) c.json["frames"] = frames[i];
        if (t.value("layer", std::string("beauty")) != "beauty") c.json["layer"] = t["layer"];
        ordered golden = scene.value("golden", ordered::object());
        const ordered case_golden = t.value("golden", ordered::object());
        for (const auto& [k, v] : case_golden.items()) golden[k] = v;
        if (!golden.empty()) c.json["golden"] = golden;
        c.metrics = t.at("metrics").get<std::vector<std::string>>();
        cases.push_back(std::move(c));
      }
  }
  return cases;
}

// A gate config (docs/gate.md) with `bounds` per case name.
ordered config_json(const ordered& plan, const std::vector<PlannedCase>& cases, const std::map<std::string, ordered>& bounds) {
  ordered list = ordered::array();
  for (const PlannedCase& c : cases) {
    ordered o = c.json;
    o["bounds"] = bounds.at(c.name());
    list.push_back(o);
  }
  ordered defaults;
  defaults["resolution"] = plan.at("resolution");
  defaults["golden"] = plan.at("golden");
  ordered out;
  out["version"] = 1;
  out["golden_dir"] = "refs";
  out["defaults"] = defaults;
  out["cases"] = list;
  return out;
}

// x rounded up to 3 significant digits, so that bounds read well and never undercut x.
double round_up(double x) {
  if (x <= 0.0) return 0.0;
  const double e = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  const double r = std::ceil(x / e - 1e-9) * e;
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", r);
  if (std::strtod(text, nullptr) >= x) return std::strtod(text, nullptr);
  std::snprintf(text, sizeof text, "%.4g", r);
  return std::strtod(text, nullptr);
}

// The golden's noise floor of a metric as giq score reports it (docs/metrics.md).
double noise_floor(const json& metrics, const std::string& metric) {
  for (const char* section : {"metrics", "sequence", "last_frame.metrics"})
    if (const json* m = walk(metrics, std::string(section) + "." + metric))
      if (m->is_object() && m->contains("noise_floor") && (*m)["noise_floor"].is_number())
        return (*m)["noise_floor"].get<double>();
  throw InputError("metrics.json", metric, "has no noise_floor");
}

struct Measured {
  std::optional<double> value;
  bool unresolved = false;
};
struct GateRun {
  std::map<std::string, std::map<std::string, Measured>> values;  // case -> metric
  std::map<std::string, json> metrics;                           // case -> its metrics.json
};

// Runs the gate once with `env` set; fails on any case that did not render or score.
GateRun measure(const CalibrateArgs& a, const fs::path& giq, const fs::path& config, const fs::path& out,
                const json& env) {
  std::vector<std::pair<std::string, std::optional<std::string>>> saved;
  for (const auto& [k, v] : env.items()) {
    const char* old = std::getenv(k.c_str());
    saved.emplace_back(k, old ? std::optional<std::string>(old) : std::nullopt);
    setenv(k.c_str(), v.get<std::string>().c_str(), 1);
  }
  fs::create_directories(out);
  const ProcessResult r =
      run_process({giq.string(), "gate", "--config", config.string(), "--out", out.string(), "--jobs",
                   std::to_string(a.jobs), "--rerender", "--device", a.device},
                  out / "gate.log");
  for (const auto& [k, v] : saved)
    if (v) setenv(k.c_str(), v->c_str(), 1);
    else unsetenv(k.c_str());
  if (r.exit_code != 0 && r.exit_code != 1)
    throw InputError((out / "gate.log").string(), "giq gate", "failed (exit " + std::to_string(r.exit_code) + "): " + r.log_tail);
  const json result = read_json(out / "gate.json");
  std::string problems;
  for (const auto& c : result.at("cases"))
    if (!c.at("problem").get<std::string>().empty())
      problems += "\n  " + c["name"].get<std::string>() + ": " + c["problem"].get<std::string>();
  if (!problems.empty()) throw InputError((out / "gate.json").string(), "cases", "failed to render or score:" + problems);
  GateRun run;
  for (const auto& c : result["cases"])
    run.metrics[c.at("name").get<std::string>()] =
        read_json(out / c.at("dir").get<std::string>() / "score" / "metrics.json");
  for (const auto& o : result.at("outcomes")) {
    Measured m;
    if (o["value"].is_number()) m.value = o["value"].get<double>();
    m.unresolved = o["status"] == "UNRESOLVED";
    run.values[o.at("case").get<std::string>()][o.at("metric").get<std::string>()] = m;
  }
  return run;
}

int check(const ordered& plan, const std::vector<PlannedCase>& cases, const json& existing,
          const std::vector<std::string>& names) {
  std::map<std::string, json> old;
  for (const auto& c : existing.value("cases", json::array())) old[c.value("name", "")] = c;
  std::vector<std::string> missing, differ, extra;
  std::set<std::string> planned, uncalibrated, uncalibrated_scenes;
  for (const PlannedCase& c : cases) {
    planned.insert(c.name());
    const auto it = old.find(c.name());
    if (it == old.end()) {
      missing.push_back(c.name());
      uncalibrated.insert(c.technique());
      uncalibrated_scenes.insert(c.scene());
      continue;
    }
    json without_bounds = it->second;
    without_bounds.erase("bounds");
    if (without_bounds != json(c.json)) {
      differ.push_back(c.name());
      uncalibrated.insert(c.technique());
      uncalibrated_scenes.insert(c.scene());
    }
  }
  for (const auto& [name, c] : old)
    if (!planned.count(name)) extra.push_back(name);
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  };
  if (!missing.empty()) std::cerr << "gate.json: cases missing: " << list(missing) << '\n';
  if (!differ.empty()) std::cerr << "gate.json: cases different from the plan: " << list(differ) << '\n';
  if (!extra.empty()) std::cerr << "gate.json: cases not in the plan: " << list(extra) << '\n';
  const json defaults = {{"resolution", json(plan.at("resolution"))}, {"golden", json(plan.at("golden"))}};
  if (!missing.empty() || !differ.empty() || !extra.empty() || existing.value("defaults", json()) != defaults) {
    std::string command = "giq gate calibrate";
    // A new scene touches every technique's cases: name the scene rather than them all.
    if (uncalibrated.size() == names.size() && uncalibrated_scenes.size() < uncalibrated.size())
      for (const auto& sc : uncalibrated_scenes) command += " --scene " + sc;
    else
      for (const auto& t : uncalibrated) command += " --technique " + t;
    std::cerr << "gate.json does not match golden/gate-plan.json and the registered techniques (" << list(names)
              << "); run: " << command << '\n';
    return 1;
  }
  std::cout << "gate.json: " << cases.size() << " cases cover techniques " << list(names) << " on "
            << plan.at("scenes").size() << " scenes\n";
  return 0;
}

int run_calibrate(const CalibrateArgs& a) {
  const fs::path giq = a.giq.empty() ? self_executable() : fs::absolute(a.giq);
  const fs::path plan_path = a.plan, config_path = a.config;
  // Read in the file's key order, which the written config and record keep.
  const ordered plan = read_ordered_json(plan_path);
  const auto declared = registered(giq, a.out);
  std::vector<std::string> names;
  for (const auto& [n, p] : declared) names.push_back(n);
  const auto cases = planned_cases(plan_path, plan, names);
  const json existing = fs::exists(config_path) ? read_json(config_path) : json{{"cases", json::array()}};

  // Every built-in scene has its cases.
  std::set<fs::path> in_plan;
  for (const auto& s : plan.at("scenes"))
    in_plan.insert(fs::weakly_canonical(plan_path.parent_path() / s.at("scene").get<std::string>()));
  const fs::path scenes_dir = fs::weakly_canonical(plan_path.parent_path() / ".." / "scenes");
  if (fs::is_directory(scenes_dir))
    for (const auto& e : fs::directory_iterator(scenes_dir))
      if (e.path().extension() == ".gltf" && !in_plan.count(fs::weakly_canonical(e.path())))
        throw InputError(plan_path.string(), "scenes", "the plan has no case for " + e.path().filename().string());

  if (a.check) return check(plan, cases, existing, names);

  std::map<std::string, json> old;
  for (const auto& c : existing.value("cases", json::array())) old[c.value("name", "")] = c;
  for (const auto& t : a.techniques)
    if (std::find(names.begin(), names.end(), t) == names.end())
      throw InputError("", "--technique", "'" + t + "' is not registered (giq realtime --list --json)");
  for (const auto& s : a.scenes)
    if (std::none_of(cases.begin(), cases.end(), [&](const PlannedCase& c) { return c.scene() == s; }))
      throw InputError(plan_path.string(), "--scene", "'" + s + "' has no case in the plan (expected a scene file's stem, e.g. cornell)");
  std::vector<const PlannedCase*> to_measure, keep;
  auto selected = [](const std::vector<std::string>& filter, const std::string& value) {
    return filter.empty() || std::count(filter.begin(), filter.end(), value) > 0;
  };
  for (const PlannedCase& c : cases)
    (selected(a.techniques, c.technique()) && selected(a.scenes, c.scene()) ? to_measure : keep).push_back(&c);
  if (to_measure.empty()) throw InputError("", "--technique", "no planned case for these techniques and scenes");
  for (const PlannedCase* c : keep)
    if (!old.count(c->name()) || !old[c->name()].contains("bounds"))
      throw InputError(config_path.string(), c->name(), "has no bounds yet; calibrate its technique or scene too");

  // Measuring configs live beside gate.json, so that scene paths and the manifest stay relative
  // to golden/ exactly as there; they are removed afterwards. A run with "parameters" (e.g.
  // another seed) applies to the cases of techniques that declare all of them.
  std::map<std::string, ordered> measuring;
  for (const PlannedCase* c : to_measure) {
    ordered b;
    for (const auto& m : c->metrics) b[m] = {{"fail", kHuge}};
    measuring[c->name()] = b;
  }
  std::vector<fs::path> temps;
  auto temp_config = [&](const std::vector<PlannedCase>& subset) {
    const fs::path p = config_path.parent_path() / (".gate-calibrate-" + std::to_string(getpid()) + "-" +
                                                    std::to_string(temps.size()) + ".json");
    temps.push_back(p);
    write_json_file(p, config_json(plan, subset, measuring));
    return p;
  };
  std::vector<std::pair<std::string, GateRun>> runs;
  try {
    std::vector<PlannedCase> subset;
    for (const PlannedCase* c : to_measure) subset.push_back(*c);
    const fs::path all = temp_config(subset);
    std::cout << "giq golden update (renders only missing or stale goldens)..." << std::endl;
    fs::create_directories(a.out);
    const ProcessResult g =
        run_process({giq.string(), "golden", "update", "--config", all.string(), "--jobs", "1"}, fs::path(a.out) / "golden.log");
    if (g.exit_code != 0) throw InputError((fs::path(a.out) / "golden.log").string(), "giq golden update", "failed: " + g.log_tail);
    for (const auto& run : plan.at("runs")) {
      const json params = json(run.value("parameters", ordered::object()));
      std::vector<PlannedCase> varied;
      for (const PlannedCase* c : to_measure) {
        const auto& known = std::find_if(declared.begin(), declared.end(), [&](const auto& d) { return d.first == c->technique(); })->second;
        bool all_declared = true;
        for (const auto& [k, v] : params.items()) all_declared &= known.count(k) > 0;
        if (!all_declared) continue;
        PlannedCase v = *c;
        json merged = c->json.contains("parameters") ? json(c->json["parameters"]) : json::object();
        for (const auto& [k, val] : params.items()) merged[k] = val;
        if (!merged.empty()) v.json["parameters"] = merged;
        varied.push_back(std::move(v));
      }
      if (varied.empty()) continue;
      const std::string name = run.at("name").get<std::string>();
      std::cout << "giq gate, run " << name << " " << (run.contains("env") ? run["env"].dump() : params.dump()) << "..."
                << std::endl;
      runs.emplace_back(name, measure(a, giq, temp_config(varied), fs::path(a.out) / name, json(run.value("env", ordered::object()))));
    }
  } catch (...) {
    for (const auto& t : temps) fs::remove(t);
    throw;
  }
  for (const auto& t : temps) fs::remove(t);

  const double fm = plan.at("margin").at("fail").get<double>(), wm = plan.at("margin").at("warn").get<double>();
  const GateRun& first = runs.front().second;
  std::map<std::string, ordered> bounds;
  ordered record = ordered::object();
  std::vector<std::string> unresolved;
  std::printf("\n%-34s %-30s %12s %9s %12s %12s\n", "case", "metric", "value", "spread", "warn", "fail");
  for (const PlannedCase* c : to_measure) {
    ordered b, rec;
    for (const std::string& m : c->metrics) {
      std::vector<std::pair<std::string, double>> values;
      for (const auto& [run_name, run] : runs) {
        const auto ci = run.values.find(c->name());
        if (ci == run.values.end()) continue;
        const auto mi = ci->second.find(m);
        if (mi == ci->second.end() || !mi->second.value)
          throw InputError("", c->name(), m + " has no value in run " + run_name);
        if (mi->second.unresolved) unresolved.push_back(c->name() + " " + m);
        values.emplace_back(run_name, *mi->second.value);
      }
      double hi = -kHuge, lo = kHuge;
      for (const auto& [r, v] : values) hi = std::max(hi, v), lo = std::min(lo, v);
      const double spread = hi > 0.0 ? (hi - lo) / hi : 0.0;
      const ordered floor_spec = plan.at("floors").value(m, ordered(0.0));
      const double floor = floor_spec == "noise" ? noise_floor(first.metrics.at(c->name()), m) : floor_spec.get<double>();
      const ordered floor_record = floor_spec == "noise" ? ordered(floor) : floor_spec;
      const double fail_level = round_up(hi * (1.0 + fm) + floor);
      const double warn_level = std::min(round_up(hi * (1.0 + wm) + floor / 2.0), fail_level);
      b[m] = {{"fail", fail_level}, {"warn", warn_level}};
      ordered per_run = ordered::object();
      for (const auto& [r, v] : values) per_run[r] = v;
      rec[m] = {{"runs", per_run}, {"value", hi}, {"relative_spread", spread}, {"floor", floor_record}};
      std::printf("%-34s %-30s %12.5g %9.2e %12.5g %12.5g\n", c->name().c_str(), m.c_str(), hi, spread, warn_level,
                  fail_level);
    }
    bounds[c->name()] = b;
    record[c->name()] = rec;
  }
  if (!unresolved.empty()) {
    std::string list;
    for (const auto& u : unresolved) list += "\n  " + u;
    throw InputError("", "goldens", "unresolved against the golden's noise (render the goldens with more samples):" + list);
  }
  for (const PlannedCase* c : keep) bounds[c->name()] = ordered(old[c->name()]["bounds"]);
  write_json_file(config_path, config_json(plan, cases, bounds));

  // golden/calibration.json: the kept techniques' records, then the new ones, sorted by case.
  const fs::path rec_path = config_path.parent_path() / "calibration.json";
  std::map<std::string, ordered> cal;
  if (fs::exists(rec_path)) {
    const ordered prev = read_ordered_json(rec_path);
    for (const PlannedCase* c : keep)
      if (prev.contains("cases") && prev["cases"].contains(c->name())) cal[c->name()] = prev["cases"][c->name()];
  }
  for (const auto& [k, v] : record.items()) cal[k] = v;
  std::string device;
  const fs::path tj = fs::path(a.out) / runs.front().first / "cases" / to_measure.front()->name() / "technique" / "timings.json";
  if (fs::exists(tj)) device = read_json(tj).value("/device/name"_json_pointer, std::string());
  ordered cases_json = ordered::object();
  for (const auto& [k, v] : cal) cases_json[k] = v;
  ordered out;
  out["comment"] = "measured by giq gate calibrate; bounds in gate.json = value x (1 + margin) + floor";
  out["margin"] = plan.at("margin");
  out["runs"] = plan.at("runs");
  out["device"] = device;
  out["cases"] = cases_json;
  write_json_file(rec_path, out);
  std::cout << "\nwrote " << config_path.string() << " (" << cases.size() << " cases) and " << rec_path.string() << '\n';
  return 0;
}

}  // namespace

CLI::App* add_gate_calibrate_command(CLI::App& gate, int& exit_code) {
  auto a = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = gate.add_subcommand(
      "calibrate", "Write the gate config's cases and bounds from golden/gate-plan.json and measured values");
  cmd->add_option("--plan", a->plan, "The plan: case templates, margins, floors, runs")->capture_default_str();
  cmd->add_option("--config", a->config, "The gate config written (or checked)")->capture_default_str();
  cmd->add_option("--out", a->out, "Folder for the measuring gate runs")->capture_default_str();
  cmd->add_option("--technique", a->techniques, "Measure only these techniques' cases (repeatable); keep the others'");
  cmd->add_option("--scene", a->scenes,
                  "Measure only the cases of these scenes, by file stem (repeatable; with --technique, both must match)");
  cmd->add_option("--jobs", a->jobs, "Cases run in parallel")->capture_default_str();
  cmd->add_option("--device", a->device, "Vulkan device of the gate runs")->capture_default_str();
  cmd->add_option("--giq", a->giq, "giq binary whose subcommands are run (default: this one)");
  cmd->add_flag("--check", a->check,
                "Only check that the config has every case the plan and the registered techniques call for (exit 1 if not)");
  cmd->footer("Example: bounds for a newly registered technique, the others' kept:\n  giq gate calibrate --technique ddgi\n"
              "Bounds for a new built-in scene:\n  giq gate calibrate --scene dynamic");
  cmd->callback([a, &exit_code] { exit_code = run_calibrate(*a); });
  return cmd;
}

}  // namespace giq::cli
