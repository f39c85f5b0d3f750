#pragma once
// The pipeline behind `giq gate` and `giq golden update` (cmd_gate.cpp, cmd_golden.cpp): for
// each case it runs the same giq
// binary's subcommands as child processes (see subprocess.h):
//
//   giq reference --scene S --view V --frames A:B --spp N | --rel-error E --seed K
//                 --width W --height H --out <golden>/<key>/frame_####.exr
//   giq realtime  --scene S --view V --technique T [--param k=v ...] --warmup A --frames B-A+1
//                 --width W --height H [--device D] --out <case>/technique
//   giq realtime  ... --no-images --warmup Wt --frames Nt --out <case>/timing   (gpu_ms bounds)
//   giq score     --ref <golden>/<key>/frame_%04d.exr --test <case>/technique/frame_%04d.exr
//                 [--frames A:B] --layer L --scene S --timings <timings.json> --out <case>/score
//
// and evaluates the case's bounds on the resulting metrics.json and timings.json.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "giq/gate/config.h"
#include "giq/gate/evaluation.h"
#include "giq/gate/golden_manifest.h"

namespace giq::cli {

struct Toolchain {
  std::filesystem::path giq;  // the binary whose subcommands render and score
  std::string device;         // passed to giq realtime --device when not empty
  bool rerender = false;      // ignore outputs of an earlier identical run
  // Words put before `giq reference` (giq golden update --launcher): an MPI launcher such as
  // "mpirun -n 16" renders each golden across ranks, with the same bits.
  std::vector<std::string> launcher;
};

// The options `giq gate` and `giq golden update` share: which cases, how many at a time, and
// which giq binary runs them.
struct CaseOptions {
  std::string config = "golden/gate.json";
  std::string only;
  int jobs = 1;
  std::string giq;
  std::string device;
  bool rerender = false;
};
void add_case_options(CLI::App* cmd, CaseOptions& o);
// Throws InputError for a giq binary that does not exist.
Toolchain toolchain(const CaseOptions& o);
// The config's cases that --only selects; throws InputError for a bad config, a bad --jobs or
// a pattern that selects nothing.
std::vector<const gate::Case*> load_cases(const CaseOptions& o, gate::Config& config);

// Config mistakes found before any work (InputError, exit 2) rather than as failing cases: a
// technique the giq binary does not register, a parameter it does not declare or outside its
// range, a view the scene does not have. `log` receives the technique listing's output.
void check_cases(const Toolchain& tools, const std::vector<const gate::Case*>& cases, const std::filesystem::path& log);

struct CaseRun {
  gate::Evidence evidence;
  double seconds = 0.0;
  std::filesystem::path dir;  // <out>/cases/<name>
};

// Never throws: every failure becomes evidence.problem, so one case cannot stop the others.
CaseRun run_case(const Toolchain& tools, const gate::Case& c, const gate::Config& config,
                 const gate::Manifest& manifest, const std::filesystem::path& out_dir);

struct GoldenRun {
  std::string key;
  std::string action;  // "fresh", "rendered", "failed"
  std::string message;
};

// Renders the golden of `c` when it is missing or stale (always with `force`) and records it
// in `manifest` (guarded by `lock`; the manifest file is rewritten after each golden so an
// interrupted update keeps what it finished).
GoldenRun update_golden(const Toolchain& tools, const gate::Case& c, const gate::Config& config,
                        bool force, gate::Manifest& manifest, std::mutex& lock);

// Runs one step (a giq subcommand writing into `dir`, its output appended to `log`) unless
// `dir` holds the outputs of a run with the same `stamp` (the command and the giq binary's
// hash): the cache the gate and `giq results` share. A non-zero exit becomes the returned
// problem, naming `what` and the log; "" when the step succeeded or was fresh.
std::string run_cached_step(const std::vector<std::string>& argv, const std::filesystem::path& dir,
                            const std::filesystem::path& log, const std::string& what, const nlohmann::json& stamp,
                            bool rerender);

// scenes::Scene::content_hash of the case's scene (throws InputError for a bad scene).
std::string scene_hash(const std::filesystem::path& scene);

}  // namespace giq::cli
