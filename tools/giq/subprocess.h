#pragma once
// Running giq's own subcommands (reference, realtime, score) as child processes: a crash or a
// validation failure in one render cannot take the gate down with it, cases run in parallel
// without sharing state, and the commands used are exactly what a user can re-run by hand.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace giq::cli {

struct ProcessResult {
  int exit_code = -1;    // the child's exit status; 128 + N when killed by signal N
  double seconds = 0.0;  // wall time
  std::string log_tail;  // the last lines of its output, for messages
};

// Runs argv[0] (a path) with arguments, stdout and stderr appended to `log_file`, in the
// working directory `cwd` (empty: this process's). Throws InputError when the program cannot
// be started.
ProcessResult run_process(const std::vector<std::string>& argv,
                          const std::filesystem::path& log_file,
                          const std::filesystem::path& cwd = {});

// A shell-quoted command line, for logs and messages.
std::string command_line(const std::vector<std::string>& argv);

// Runs task(i) for i in [0, count) on up to `jobs` threads; returns when all are done.
void parallel_for(size_t count, int jobs, const std::function<void(size_t)>& task);

// The path of the running executable (/proc/self/exe).
std::filesystem::path self_executable();

}  // namespace giq::cli
