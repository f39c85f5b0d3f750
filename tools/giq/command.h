#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself on the app with one
// add_<name>_command call in main.cpp. A command reports failure by throwing InputError
// (exit 2) or by returning a non-zero exit code through `exit_code` (1 = gate failed).

#include <CLI/CLI.hpp>

namespace giq::cli {

void add_scene_command(CLI::App& app, int& exit_code);
void add_score_command(CLI::App& app, int& exit_code);
#ifdef GIQ_WITH_REFERENCE
void add_reference_command(CLI::App& app, int& exit_code);
// `giq reference merge`, a subcommand of `giq reference` (cmd_reference_merge.cpp).
CLI::App* add_reference_merge_command(CLI::App& reference, int& exit_code);
#endif
#ifdef GIQ_WITH_VULKAN
void add_realtime_command(CLI::App& app, int& exit_code);
#endif
void add_gate_command(CLI::App& app, int& exit_code);
// `giq gate calibrate`, a subcommand of `giq gate` (cmd_gate_calibrate.cpp).
CLI::App* add_gate_calibrate_command(CLI::App& gate, int& exit_code);
void add_golden_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);
void add_results_command(CLI::App& app, int& exit_code);

}  // namespace giq::cli
