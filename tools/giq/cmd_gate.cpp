// `giq gate`: renders each case of the gate config with its technique, scores it against its
// golden reference and checks the bounds; prints a table, writes gate-report.xml (JUnit),
// gate-summary.md and gate.json, and exits 0 (pass or warn), 1 (any failure) or 2 (bad input).
// See docs/gate.md.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "command.h"
#include "gate_runner.h"
#include "progress.h"
#include "output_guard.h"
#include "giq/base/atomic_file.h"
#include "giq/base/error.h"
#include "giq/base/version.h"
#include "giq/gate/config.h"
#include "giq/gate/junit.h"
#include "giq/gate/summary.h"
#include "subprocess.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct GateArgs {
  CaseOptions cases;
  std::string out = "gate-out";
};

json outcome_json(const gate::Outcome& o) {
  return {{"case", o.case_name},
          {"metric", o.metric},
          {"status", gate::to_string(o.status)},
          {"value", o.value && std::isfinite(*o.value) ? json(*o.value) : json(nullptr)},
          {"bound", o.bound},
          {"message", o.message},
          {"fails_gate", o.fails_gate}};
}

int run_gate(const GateArgs& a) {
  gate::Config config;
  const auto cases = load_cases(a.cases, config);
  const Toolchain tools = toolchain(a.cases);
  const gate::Manifest manifest = gate::read_manifest(config.golden_dir / "manifest.json");
  const fs::path out = a.out;
  check_output_folder(out, {config.file}, "--out");
  fs::create_directories(out);
  check_cases(tools, cases, out / "techniques.log");
  std::vector<CaseRun> runs(cases.size());
  ProgressLine line;
  std::mutex progress;
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  parallel_for(cases.size(), a.cases.jobs, [&](size_t i) {
    runs[i] = run_case(tools, *cases[i], config, manifest, out);
    std::lock_guard<std::mutex> g(progress);
    ++done;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    line.show("giq gate: %zu/%zu cases  %s elapsed  ETA %s  (%s %.1f s)", done, cases.size(),
              format_seconds(elapsed).c_str(), format_seconds(elapsed / double(done) * double(cases.size() - done)).c_str(),
              cases[i]->name.c_str(), runs[i].seconds);
  });
  line.finish();

  std::vector<gate::Outcome> outcomes;
  std::vector<std::pair<std::string, double>> seconds;
  json case_list = json::array();
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto o = gate::evaluate(*cases[i], runs[i].evidence);
    outcomes.insert(outcomes.end(), o.begin(), o.end());
    seconds.emplace_back(cases[i]->name, runs[i].seconds);
    json cj = {{"name", cases[i]->name},
               {"scene", cases[i]->scene.string()},
               {"view", cases[i]->view},
               {"camera", cases[i]->camera},
               {"technique", cases[i]->technique},
               {"test", cases[i]->test.string()},
               {"frames", {cases[i]->first_frame, cases[i]->last_frame}},
               {"layer", cases[i]->layer},
               {"dir", fs::relative(runs[i].dir, out).generic_string()},
               {"seconds", runs[i].seconds},
               {"problem", runs[i].evidence.problem}};
    json params = json::object();
    for (const auto& [k, v] : cases[i]->parameters) params[k] = v;
    cj["parameters"] = params;
    case_list.push_back(cj);
  }
  json outcome_list = json::array();
  for (const auto& o : outcomes) outcome_list.push_back(outcome_json(o));
  const int code = gate::exit_code(outcomes);
  write_file_atomically(out / "gate-report.xml", gate::junit_xml(outcomes, seconds));
  write_file_atomically(out / "gate-summary.md", gate::markdown_summary(outcomes));
  write_file_atomically(out / "gate.json", json{{"version", 1},
                                                {"giq_version", giq::version()},
                                                {"config", a.cases.config},
                                                {"passed", code == 0},
                                                {"cases", case_list},
                                                {"outcomes", outcome_list}}
                                                   .dump(2) +
                                               "\n");
  std::cout << gate::format_table(outcomes) << '\n'
            << "giq gate: " << (code == 0 ? "passed" : "FAILED") << ", "
            << gate::count_line(outcomes) << "; " << (out / "gate-report.xml").string() << ", "
            << (out / "gate-summary.md").string() << '\n';
  return code;
}

}  // namespace

void add_gate_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<GateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "gate", "Render, score and check every case of a gate config (exit 1 on failure)");
  add_case_options(cmd, a->cases);
  cmd->add_option("--out", a->out,
                  "Folder for gate-report.xml, gate-summary.md, gate.json and each case's outputs")
      ->capture_default_str();
  cmd->add_option("--device", a->cases.device,
                  "Vulkan device for giq realtime (index or part of its name)");
  cmd->add_flag("--rerender", a->cases.rerender,
                "Render and score again even where outputs of an identical run exist");
  CLI::App* calibrate = add_gate_calibrate_command(*cmd, exit_code);
  cmd->footer("Example: the project's gate on lavapipe, two cases at a time (exit 1 when a bound fails):\n  giq gate --config golden/gate.json --device llvmpipe --jobs 2 --out build/gate");
  cmd->callback([a, calibrate, &exit_code] {
    if (!calibrate->parsed()) exit_code = run_gate(*a);
  });
}

}  // namespace giq::cli
