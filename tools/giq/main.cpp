// giq: measures how far real-time global-illumination techniques are from the truth.
// Exit codes: 0 ok, 1 gate failed, 2 usage or input error, 3 internal error.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <limits>
#include <malloc.h>

#include "command.h"
#include "giq/base/error.h"
#include "giq/base/suggest.h"
#include "giq/base/version.h"

namespace {

// "did you mean" for the first argument CLI11 could not place: an option of the subcommand
// that was being parsed, or a subcommand.
std::string suggestion(const CLI::App& app) {
  const CLI::App* deepest = &app;
  while (!deepest->get_subcommands().empty()) deepest = deepest->get_subcommands().front();
  std::vector<std::string> names;
  for (const CLI::Option* o : deepest->get_options())
    for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
  for (const CLI::App* sub : deepest->get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  for (const std::string& extra : deepest->remaining()) {
    const std::string name = extra.substr(0, extra.find('='));
    const std::string nearest = giq::nearest_name(name, names);
    if (!nearest.empty()) return "; for '" + name + "' did you mean '" + nearest + "'?";
  }
  return "";
}

}  // namespace

int main(int argc, char** argv) {
  // giq makes arrays of the same large sizes again and again: a scene posed every frame,
  // geometry flattened, images. glibc serves a block above 128 KiB with mmap, and gives the
  // top of the heap back to the kernel past 128 KiB, so each time the arrays' pages are
  // faulted in anew, 4 KiB at a time (a third of a frame's host time and a second of start-up
  // with a million-triangle file: bench/results/particle-host-amd-epyc-2vcpu.md). Here blocks
  // up to glibc's largest mmap threshold (32 MiB on 64-bit) come from the heap, and the heap
  // keeps what is freed: the process holds on to its peak memory instead.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max());
  CLI::App app{"giq: scores real-time global illumination against path-traced ground truth", "giq"};
  app.set_version_flag("--version", std::string("giq ") + giq::version());
  app.require_subcommand(1);
  app.fallthrough(false);

  int exit_code = 0;
  giq::cli::add_scene_command(app, exit_code);
  giq::cli::add_score_command(app, exit_code);
#ifdef GIQ_WITH_REFERENCE
  giq::cli::add_reference_command(app, exit_code);
#endif
#ifdef GIQ_WITH_VULKAN
  giq::cli::add_realtime_command(app, exit_code);
#endif
  giq::cli::add_gate_command(app, exit_code);
  giq::cli::add_golden_command(app, exit_code);
  giq::cli::add_report_command(app, exit_code);
  giq::cli::add_sweep_command(app, exit_code);
  giq::cli::add_results_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other input error (CLI11's own report adds a second).
    std::cerr << "giq: error: " << e.what() << suggestion(app) << '\n';
    return 2;
  } catch (const giq::InputError& e) {
    std::cerr << "giq: error: " << e.what() << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "giq: internal error: " << e.what() << '\n';
    return 3;
  }
  return exit_code;
}
