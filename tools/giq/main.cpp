// giq: measures how far real-time global-illumination techniques are from the truth.
// Exit codes: 0 ok, 1 gate failed, 2 usage or input error, 3 internal error.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>

#include "command.h"
#include "giq/base/error.h"
#include "giq/base/version.h"

int main(int argc, char** argv) {
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
    std::cerr << "giq: error: " << e.what() << '\n';
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
