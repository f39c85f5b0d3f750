// `giq golden update`: renders the golden references a gate config needs (missing or stale
// ones, or all with --force) and records them in the manifest. See docs/gate.md.

#include <iostream>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>

#include "command.h"
#include "gate_runner.h"
#include "giq/gate/config.h"
#include "giq/gate/golden_manifest.h"
#include "subprocess.h"

namespace giq::cli {
namespace {

namespace fs = std::filesystem;

struct GoldenArgs {
  CaseOptions cases;
  bool force = false;
  std::string launcher;
};

int run_golden_update(const GoldenArgs& a) {
  gate::Config config;
  const auto cases = load_cases(a.cases, config);
  Toolchain tools = toolchain(a.cases);
  std::istringstream words(a.launcher);
  for (std::string w; words >> w;) tools.launcher.push_back(w);
  fs::create_directories(config.golden_dir);
  gate::Manifest manifest = gate::read_manifest(config.golden_dir / "manifest.json");
  // One golden per key, even when several cases share it.
  std::vector<const gate::Case*> unique;
  std::set<std::string> keys;
  for (const gate::Case* c : cases)
    if (keys.insert(gate::golden_key(*c)).second) unique.push_back(c);
  std::vector<GoldenRun> runs(unique.size());
  std::mutex lock;
  parallel_for(unique.size(), a.cases.jobs, [&](size_t i) {
    runs[i] = update_golden(tools, *unique[i], config, a.force, manifest, lock);
  });
  int failed = 0, rendered = 0;
  for (const GoldenRun& r : runs) {
    std::cout << "  " << r.key << ": " << r.action << (r.message.empty() ? "" : "  " + r.message) << '\n';
    failed += r.action == "failed";
    rendered += r.action == "rendered";
  }
  std::cout << "giq golden update: " << rendered << " rendered, " << (runs.size() - size_t(rendered + failed))
            << " fresh, " << failed << " failed; manifest " << (config.golden_dir / "manifest.json").string()
            << '\n';
  return failed ? 1 : 0;
}

}  // namespace

void add_golden_command(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<GoldenArgs>();
  CLI::App* golden = app.add_subcommand("golden", "Golden references of the gate");
  golden->require_subcommand(1);
  CLI::App* update =
      golden->add_subcommand("update", "Render the missing or stale golden references of a gate config");
  add_case_options(update, a->cases);
  update->add_flag("--force", a->force, "Render every golden again, fresh or not");
  update->add_option("--launcher", a->launcher,
                     "Words put before each giq reference, e.g. 'mpirun -n 16' or 'srun': every golden rendered across MPI "
                     "ranks, with the same bits (needs goldens with spp; docs/reference.md, 'MPI')");
  update->footer("Example: render what a new case needs, nothing that is fresh:\n  giq golden update --config golden/gate.json");
  update->callback([a, &exit_code] { exit_code = run_golden_update(*a); });
}

}  // namespace giq::cli
